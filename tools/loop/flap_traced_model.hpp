// The Hessenthaler (2017) silicone flap as a traced model (traced_model.hpp; issue 34, validation 2
// (iii)): the shell strip of fem/validation/hessenthaler_flap.hpp against the flap's measured tip
// deflections, one frame per measured state (no flow: buoyancy alone; Phase I: buoyancy plus a
// flow load taken as known, e.g. the plane FSI's time mean, labelled so). Each frame is one 3-row
// block (0, 0, tip - measured) as in fin-fit flap: only the tip's deflection along the buoyancy is
// measured, so a frame carries one datum. The base parameter is E (log10), refitted, or none with
// E held at a given value (a user's tensile-test modulus). Candidate effects that a strip can
// carry, one parameter each: a solid density error, a rest shape curved along the length or
// cupped across the width, a softer distal half, and a modulus offset between the material test
// and the experiment (E times a factor: inside span(J) whenever E is refitted).
#pragma once

#include <string>
#include <vector>

#include "fem/validation/hessenthaler_flap.hpp"
#include "loop/traced_model.hpp"

namespace finverse::loop {

struct FlapFrame {
  std::string name;     // "no_flow", "phase_I_plane", ...
  double measured = 0;  // tip deflection along the buoyancy [m]
  // The flow's load per unit length [N/m] on equal stations from the clamp (empty: no flow).
  std::vector<double> flow_transverse, flow_along;
};

struct FlapTraceSetup {
  fem::validation::HessenthalerFlap flap;
  fem::validation::FlapMesh mesh{fem::validation::FlapModel::shell, 32, 4};
  int load_steps = 8;
  double youngs_modulus = 0;  // [Pa]: the base's start, or its fixed value
  bool refit_modulus = true;
  std::vector<FlapFrame> frames;
  std::vector<std::string> candidates;  // names of flap_candidates(); empty: all
  double relative_step = 0.01;          // score direction: this fraction of a parameter's range
};

// Every candidate with its parameter (name, unit, bounds, scale) and its "off" value.
struct FlapCandidate {
  std::string name;
  fit::Parameter parameter;
  double off = 0;
};
const std::vector<FlapCandidate>& flap_candidates();

class FlapTracedModel : public TracedModel {
 public:
  // Throws InvalidInput for an unknown candidate, no frame, or a non-positive modulus.
  explicit FlapTracedModel(FlapTraceSetup setup);

  fit::ParameterSpace base_space() const override;
  Eigen::VectorXd base_start() const override;
  std::vector<std::string> candidates() const override { return names_; }
  std::vector<fit::Parameter> effect_parameters(const std::string& candidate) const override;
  std::vector<ScoreDirection> score_directions(const std::string& candidate) const override;
  Eigen::VectorXd effect_off(const std::string& candidate) const override;
  int frame_count() const override { return static_cast<int>(setup_.frames.size()); }
  Eigen::VectorXd residuals(const std::vector<std::string>& effects, const Eigen::VectorXd& physical) const override;

  // Predicted tip deflection per frame [m] with `effects` on (parameters as residuals()).
  std::vector<double> tips(const std::vector<std::string>& effects, const Eigen::VectorXd& physical) const;
  const FlapTraceSetup& setup() const { return setup_; }

 private:
  const FlapCandidate& candidate(const std::string& name) const;

  FlapTraceSetup setup_;
  std::vector<std::string> names_;
};

}  // namespace finverse::loop
