// fin-loop flap (issue 34 (iii), issue 49 item 4): the effect tracer (effect_tracing.hpp) on the
// Hessenthaler flap's measurements (flap_traced_model.hpp). Frames: the tips (no flow; Phase I with
// the plane FSI's load), or with the 3-D run's loads (--phase1) the centrelines (the zero-flow fit
// published by the paper, sampled; the 59 MRI points of Phase I). Runs:
//   uniaxial: E held at the tensile test's 2 (1 + nu) 96.9 kPa; no flow trains, Phase I held out;
//   fitted:   E refitted (tips: on every frame; centrelines: on no flow, Phase I held out);
//   phase_I:  (centrelines) E held at fitted's, Phase I trains, no flow held out.
// A candidate counts as identifiable only when the training data exceed the fitted parameters plus
// its own by one and a held-out frame exists; otherwise the loop refuses to add whatever the tracer
// says, flagged. Per candidate it also reports the magnitude that closes the training residual
// alone (with E, when refitted) and what that predicts for the other frame.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "core/summary.hpp"
#include "fem/validation/hessenthaler_flap.hpp"

namespace finverse::loop {

struct FlapLoopOptions {
  std::filesystem::path reference;                     // hessenthaler2017.json
  std::filesystem::path fit_summary;                   // fin-fit flap's summary.json: E and the metrics carried over
  std::optional<std::filesystem::path> plane_summary;  // fin-fsi hessenthaler_plane's: the Phase I load
  // fin-fsi flap --loads of the 3-D Phase I run, and of the runs with the viscosity and the inflow
  // perturbed (optional); the MRI centreline (phaseI_centreline.csv) the 3-D frame is compared with.
  std::optional<std::filesystem::path> phase1_loads, phase1_viscosity, phase1_inflow, centreline;
  std::string name = "loop_hessenthaler";
  fem::validation::FlapMesh mesh{fem::validation::FlapModel::shell, 32, 4};
  int load_steps = 8;
  double alpha = 0.01;
  double relative_step = 0.01;
  int lm_evaluations = 40;
  std::function<void(const std::string&)> progress;
};

// Throws InvalidInput (a bad reference, fit or plane summary) naming the file.
Summary run_flap_loop(const FlapLoopOptions& options);

}  // namespace finverse::loop
