// The bodies of `fin-loop residual` and `fin-loop trace` (issue 34): stage files in, residual.h5
// / loop.h5 and JSON digests out. Every input problem (different meshes or time bases, a file of
// the wrong schema, an unknown effect or parameter) is thrown, naming the file or flag, before
// anything is written.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fem/root_motion.hpp"
#include "fem/structural_run.hpp"
#include "fit/levenberg_marquardt.hpp"
#include "loop/io/loop_files.hpp"

namespace finverse::loop::io {

struct FileResidualOptions {
  std::filesystem::path mesh, reconstruction, prediction, out;
  std::optional<std::filesystem::path> summary;
  std::optional<double> period;  // else the reconstruction's (or prediction's) T
  int harmonics = 3;
  int modes = 5;
};

// Node weights of the residual: a third of each shell triangle's area per node (the mean weight
// for nodes on no triangle), root nodes 0, normalised to mean 1 (as fit/node_weights.hpp).
Eigen::VectorXd mesh_node_weights(const stage::Mesh& mesh);

ResidualAnalysis run_residual_from_files(const FileResidualOptions& options, const nlohmann::json& config);

struct FileTraceOptions {
  std::filesystem::path mesh, motion, materials, out;
  // materials.h5 of fin-fit; none: the default fin parameters at the materials file's values.
  std::optional<std::filesystem::path> fit;
  std::optional<std::filesystem::path> loads, candidates, summary;
  // The root drive's motion (default: --motion): a twin's target carries its own deformed rays,
  // whose tangents would otherwise turn the drive's fitted root rotation.
  std::optional<std::filesystem::path> root_motion;
  std::vector<std::string> parameters;  // refitted subset of the fit's; empty: all
  int drive_harmonics = 0;  // > 0: the root motion through this many harmonics of the beat (fem/io/harmonic_motion.hpp)
  int drive_order = 0;      // > 0: the root drive's correction of this order refitted too (fit/drive_parameters.hpp)
  std::optional<double> frequency;      // beat frequency for periodic effects; else 1 / motion.h5 T
  std::optional<double> period;         // for the held-out split; else motion.h5 T, else 1 / frequency
  fem::Analysis analysis = fem::Analysis::quasi_static;  // of the model runs (fin-fem run's default)
  int substeps = 4;                                       // dynamic
  double spectral_radius = 0.8;                           // dynamic
  // dynamic: each step's Newton starts where the last ended and refactorises every iteration,
  // what the thin fin needs (docs/studies/fin_dynamic_run.md).
  bool full_newton = false;
  double ramp = 0;
  fem::RootRotation root_rotation = fem::RootRotation::fit;
  int max_effects = 3;
  double alpha = 0.01;
  bool refit_base = true;
  double relative_step = 0.01;
  fit::LmOptions lm;
};

TraceRecord run_trace_from_files(const FileTraceOptions& options, const nlohmann::json& config);

}  // namespace finverse::loop::io
