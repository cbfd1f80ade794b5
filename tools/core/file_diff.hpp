// fin-diff's dispatcher: compares two files by kind (HDF5, VTK XML, .pvd collections) or two
// directories file by file (every comparable file in either), and rewrites a reference from a
// candidate on --update. The golden-file regression tests (tests/regression/<stage>/<case>/)
// are directories compared this way, with their tolerances.json.
#pragma once

#include <filesystem>
#include <vector>

#include "core/array_compare.hpp"
#include "core/tolerances.hpp"

namespace finverse {

std::vector<Comparison> diff_paths(const std::filesystem::path& reference, const std::filesystem::path& candidate,
                                   const Tolerances& tolerances);

// Copies the candidate over the reference (each comparable file, atomically); a reference
// directory keeps its other files (tolerances.json, README).
void update_reference(const std::filesystem::path& reference, const std::filesystem::path& candidate);

bool is_comparable(const std::filesystem::path& p);

}  // namespace finverse
