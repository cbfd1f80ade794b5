// The body of `fin-fit run` (issue 31; DESIGN.md section 5.4): stage files in, materials.h5 out.
// Reads mesh.h5, the target motion (motion.h5: the reconstruction, whose root nodes also drive
// the model), loads.h5, the base materials file (densities, the values of parameters not fitted)
// and the parameter specification (default: membrane E, every ray's E, one nu); builds the fin
// model factory and the objective -- eq. (2) quasi-static increments at the given instants, or
// eq. (1) the dynamic run from rest compared over the target's last period -- and runs the fit
// (fit_driver.hpp) with progress per generation. Every input problem is found before the first
// generation (one evaluation at the materials file's values) and thrown with the file named;
// nothing is written then. Parameters the data cannot constrain are flagged in the file and
// warned about.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fem/root_motion.hpp"
#include "fit/fit_driver.hpp"
#include "fit/fit_result.hpp"

namespace finverse::fit::io {

struct FileFitOptions {
  std::filesystem::path mesh, motion, materials, out;
  std::optional<std::filesystem::path> loads, parameters, summary;
  std::string objective = "quasi_static";  // or "dynamic"
  // quasi_static: explicit instants [s], else `instant_count` instants spread evenly over the
  // target's span starting at mid-span (1: the paper's mid-swing); dt 0 = the frame spacing.
  std::vector<double> instants;
  int instant_count = 1;
  double dt = 0;
  // dynamic: substeps per frame interval; the compared window is the target's last `periods`
  // of its period (motion.h5 T), or every frame when not periodic.
  int substeps = 4;
  double periods = 1;
  double ramp = 0;  // s of ramp from rest before the first sample (0: ten frame intervals)
  // Root rotations of the drive: fit (root nodes + the rays' tangents at the root) or zero (a
  // clamp that does not turn), fem/root_motion.hpp.
  fem::RootRotation root_rotation = fem::RootRotation::fit;
  // quasi_static: the base as the stress-free reference of the increment (QuasiStaticOptions).
  bool stress_free_base = false;
  FitOptions fit;
};

// Throws fit::InvalidInput / fem::InvalidInput / finverse::Error naming the file for bad input.
FitResult run_fit_from_files(const FileFitOptions& options, const nlohmann::json& config);

}  // namespace finverse::fit::io
