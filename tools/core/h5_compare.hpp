// Dataset-by-dataset comparison of two HDF5 files: every dataset and attribute in either file,
// numeric values under per-dataset tolerances, strings exactly, dtype and shape mismatches, and
// datasets missing on either side. The provenance attributes (producer, config, inputs) are
// ignored: they say how a file was made, not what it holds.
#pragma once

#include <filesystem>
#include <vector>

#include "core/array_compare.hpp"
#include "core/tolerances.hpp"

namespace finverse {

std::vector<Comparison> compare_hdf5(const std::filesystem::path& reference, const std::filesystem::path& candidate,
                                     const Tolerances& tolerances);

}  // namespace finverse
