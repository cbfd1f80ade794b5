// Output of a file-driven structural run: the node positions over time as a finverse/motion
// contract file (time, points, velocity for dynamic runs; the same schema fin-mesh writes, so
// that fin-diff, fin-report and the fitter's objective read the structural response and the
// reconstruction alike) and a ParaView series of the shell surface with the displacement field.
// Both are written only after the whole run succeeded; the HDF5 file atomically
// (tools/core/hdf5_file), the .pvd last, so no output looks complete after a failure.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/provenance.hpp"
#include "core/stage_files.hpp"
#include "fem/structural_run.hpp"

namespace finverse::fem::io {

stage::Motion to_motion(const std::vector<RunFrame>& frames, std::optional<double> period);

void write_run_output(const std::filesystem::path& h5, const std::optional<std::filesystem::path>& pvd,
                      const stage::Mesh& mesh, const std::vector<RunFrame>& frames,
                      std::optional<double> period, const Provenance& provenance,
                      std::optional<std::string> effects = std::nullopt);  // the "effects" attribute

}  // namespace finverse::fem::io
