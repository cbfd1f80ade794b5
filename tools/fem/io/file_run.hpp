// A structural run from stage files to stage files (the body of `fin-fem run`): read mesh.h5,
// the materials file, optional loads.h5 and motion.h5; build the model (fin_model.hpp); run the
// analysis over the output times (structural_run.hpp) with progress and ETA on stderr; write the
// response (run_output.hpp). Output times: those of loads.h5, else those of motion.h5 (one of
// the two is required; with both, the load times must lie within the motion's, or the motion be
// periodic (motion.h5 T): it is then repeated to cover them, periodic_motion.hpp). Effects
// (fin_layout.hpp): rest shapes before the model is built, the others after loads and motion.
// Instead of motion.h5, an analytic root drive (drive.json) may move the root.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "fem/root_motion.hpp"
#include "fem/structural_run.hpp"

namespace finverse::fem::io {

struct FileRunOptions {
  std::filesystem::path mesh, materials, out;
  std::optional<std::filesystem::path> loads, motion, pvd;
  // Candidate effects (fem/effects, a JSON list): applied to the model, recorded in the output's
  // "effects" attribute. Periodic effects take the loads' or motion's period as the beat.
  std::optional<std::filesystem::path> effects;
  // The analytic root drive (root_drive_file.hpp; frequency_hz required) instead of motion.h5: the
  // fin starts at rest at t = 0 and the drive's own smooth start; without loads the output times
  // are `periods` periods after the drive's ramp (rounded up to whole periods), frames_per_period
  // per period. A structural run in vacuo, or under periodic loads.
  std::optional<std::filesystem::path> root_drive;
  double periods = 1;
  int frames_per_period = 40;
  RunOptions run;
  RootRotation root_rotation = RootRotation::fit;
  double ramp = 0;  // s before the first output time; 0: ten output intervals
  std::array<double, 3> gravity{0, 0, 0};
};

struct FileRunSummary {
  int frames = 0;
  long newton_iterations = 0;
};

// Throws (InvalidInput, SingularMatrix, NotConverged, finverse::Error for file problems) before
// anything is written.
FileRunSummary run_from_files(const FileRunOptions& options, const nlohmann::json& config);

}  // namespace finverse::fem::io
