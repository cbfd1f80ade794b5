// fin-loop flap (issue 34, validation 2 (iii)): the effect tracer (effect_tracing.hpp) on the
// Hessenthaler flap's measured tip deflections (flap_traced_model.hpp), twice:
//   uniaxial: E held at the tensile test's 2 (1 + nu) 96.9 kPa, what a user would have; the no-flow
//             tip is the training datum, the Phase I tip (if a flow load is given) held out;
//   fitted:   E refitted from fin-fit flap's value on every frame; no frame left to hold out.
// A frame carries one datum, so the data identify at most as many parameters as there are
// training frames: a candidate counts as identifiable only when the training data exceed the
// fitted parameters plus its own by one (a residual degree of freedom to test it) and a held-out
// frame exists for the rule "held-out error falls". Otherwise the loop refuses to add whatever
// the tracer says, and the summary flags it. Per candidate it also reports the magnitude that
// closes the training residual alone (with E, when refitted) and what that predicts for the other
// frame: where those agree across candidates the data cannot tell them apart.
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
