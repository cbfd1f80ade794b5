// The Hessenthaler (2017) silicone flap as a traced model (traced_model.hpp; issue 34 (iii), issue
// 49): the shell strip of fem/validation/hessenthaler_flap.hpp against the flap's measurements, one
// frame per state (no flow: buoyancy alone; Phase I: plus a flow load). A frame is its tip (one
// 3-row block (0, 0, tip - measured), as fin-fit flap) or its centreline (one such block per point,
// y at the point's z); only the deflection is measured, one datum per block. The Phase I load is a
// given profile (the plane FSI's, labelled) or the 3-D run's, linear in the tip (flap_flow_load.hpp),
// the flap then sitting where load and shape agree. The base parameter is E (log10), refitted or
// held (a tensile-test modulus). Candidates, one parameter each: a solid density error, a rest shape
// curved along the length or cupped across the width, a softer distal half, a test-to-experiment
// modulus factor (in span(J) when E is refitted), and with the 3-D load a viscosity and an inflow
// error (from runs with the factor perturbed).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "fem/validation/hessenthaler_flap.hpp"
#include "loop/flap_flow_load.hpp"
#include "loop/traced_model.hpp"

namespace finverse::loop {

struct FlapFrame {
  std::string name;     // "no_flow", "phase_I_plane", ...
  double measured = 0;  // tip deflection along the buoyancy [m]
  // The flow's load per unit length [N/m] on equal stations from the clamp (empty: no flow).
  std::vector<double> flow_transverse, flow_along;
  // The measured centreline (z, y) [m]: one residual point per entry instead of the tip (every
  // frame of a setup the same count); empty: the tip alone.
  std::vector<std::array<double, 2>> centreline;
  std::optional<FlapFlowLoad> flow_3d;  // the 3-D flow's load near its root (shell only)
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
  // The same 3-D runs with the viscosity or the inflow perturbed: the flow-side candidates.
  std::optional<FlapFlowLoad> viscosity_run, inflow_run;
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
  // The score directions are central differences at 1 % of a parameter's range: their error is
  // O(1e-4) of the sensitivity, so a candidate within 1e-3 of span(J) (the density or a modulus
  // factor against a refitted E) cannot be told from it and scores 0 (TraceOptions).
  static constexpr double kInSpanTolerance = 1e-3;

  // Throws InvalidInput for an unknown candidate, no frame, or a non-positive modulus.
  explicit FlapTracedModel(FlapTraceSetup setup);

  fit::ParameterSpace base_space() const override;
  Eigen::VectorXd base_start() const override;
  std::vector<std::string> candidates() const override { return names_; }
  std::vector<fit::Parameter> effect_parameters(const std::string& candidate) const override;
  std::vector<ScoreDirection> score_directions(const std::string& candidate) const override;
  Eigen::VectorXd effect_off(const std::string& candidate) const override;
  int frame_count() const override { return static_cast<int>(setup_.frames.size()); }
  int data_per_point() const override { return 1; }  // only the deflection is measured
  Eigen::VectorXd residuals(const std::vector<std::string>& effects, const Eigen::VectorXd& physical) const override;

  // Predicted tip deflection per frame [m] with `effects` on (parameters as residuals()).
  std::vector<double> tips(const std::vector<std::string>& effects, const Eigen::VectorXd& physical) const;
  // The same, whole: the centreline and tip per frame.
  std::vector<fem::validation::FlapDeflection> deflections(const std::vector<std::string>& effects,
                                                           const Eigen::VectorXd& physical) const;
  // y of a deflected centreline (flap frame x, z) at z, linear between stations (tip beyond).
  static double centreline_at(const fem::validation::FlapDeflection& d, double z);
  const FlapTraceSetup& setup() const { return setup_; }

 private:
  const FlapCandidate& candidate(const std::string& name) const;
  fem::validation::FlapDeflection settle_in_flow(const FlapFrame& frame, double E, double buoyancy,
                                                 const fem::validation::FlapShape& shape, double viscosity,
                                                 double inflow) const;

  FlapTraceSetup setup_;
  std::vector<std::string> names_;
};

}  // namespace finverse::loop
