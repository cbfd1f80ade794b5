// The Hessenthaler flap as a traced model (flap_traced_model.hpp).
#include "loop/flap_traced_model.hpp"

#include <algorithm>
#include <cmath>

#include "loop/errors.hpp"

namespace finverse::loop {

namespace fv = fem::validation;

const std::vector<FlapCandidate>& flap_candidates() {
  // Bounds: density within +-60 kg/m^3 (the net buoyancy is 105 kg/m^3, so the flap stays lighter
  // than the glycerol); a rest arc whose tip offset k L^2 / 2 reaches 17 mm; a cup whose edges rise
  // k (b/2)^2 / 2 = 0.6 mm; the distal half between 1.5 and 0.2 times E; the test-to-experiment
  // modulus factor between 0.3 and 3 (log10, as every modulus).
  static const std::vector<FlapCandidate> all{
      {"density_error", {"solid_density_error", "kg/m^3", -60, 60, fit::Scale::linear, std::nullopt}, 0},
      {"precurved_rest_shape", {"rest_curvature", "1/m", -8, 8, fit::Scale::linear, std::nullopt}, 0},
      {"cupped_rest_shape", {"rest_cupping", "1/m", -40, 40, fit::Scale::linear, std::nullopt}, 0},
      {"distal_softening", {"distal_softening", "1", -0.5, 0.8, fit::Scale::linear, std::nullopt}, 0},
      {"modulus_offset", {"modulus_factor", "1", 0.3, 3, fit::Scale::log10, std::nullopt}, 1},
  };
  return all;
}

FlapTracedModel::FlapTracedModel(FlapTraceSetup setup) : setup_(std::move(setup)) {
  if (!(setup_.youngs_modulus > 0) || !std::isfinite(setup_.youngs_modulus))
    throw InvalidInput("flap loop: the Young's modulus must be positive");
  if (setup_.frames.empty()) throw InvalidInput("flap loop: no measured frame");
  if (setup_.candidates.empty())
    for (const auto& c : flap_candidates()) names_.push_back(c.name);
  else
    names_ = setup_.candidates;
  for (const auto& n : names_) candidate(n);
}

const FlapCandidate& FlapTracedModel::candidate(const std::string& name) const {
  for (const auto& c : flap_candidates())
    if (c.name == name) return c;
  throw InvalidInput("flap loop: unknown candidate '" + name +
                     "' (expected density_error, precurved_rest_shape, cupped_rest_shape, distal_softening or "
                     "modulus_offset)");
}

fit::ParameterSpace FlapTracedModel::base_space() const {
  if (!setup_.refit_modulus) return {};
  return fit::ParameterSpace({{"E", "Pa", 2e4, 2e6, fit::Scale::log10, std::nullopt}}, "flap loop");
}

Eigen::VectorXd FlapTracedModel::base_start() const {
  if (!setup_.refit_modulus) return Eigen::VectorXd(0);
  return Eigen::VectorXd::Constant(1, setup_.youngs_modulus);
}

std::vector<fit::Parameter> FlapTracedModel::effect_parameters(const std::string& name) const {
  return {candidate(name).parameter};
}

std::vector<ScoreDirection> FlapTracedModel::score_directions(const std::string& name) const {
  const auto& c = candidate(name);
  const double h = setup_.relative_step * (c.parameter.upper - c.parameter.lower);
  return {{Eigen::VectorXd::Constant(1, c.off + h), h}};
}

Eigen::VectorXd FlapTracedModel::effect_off(const std::string& name) const {
  return Eigen::VectorXd::Constant(1, candidate(name).off);
}

std::vector<double> FlapTracedModel::tips(const std::vector<std::string>& effects,
                                          const Eigen::VectorXd& physical) const {
  const int base = setup_.refit_modulus ? 1 : 0;
  if (physical.size() != base + static_cast<Eigen::Index>(effects.size()))
    throw InvalidInput("flap loop: expected " + std::to_string(base + effects.size()) + " parameters");
  double E = setup_.refit_modulus ? physical(0) : setup_.youngs_modulus, density_error = 0;
  fv::FlapShape shape;
  for (std::size_t k = 0; k < effects.size(); ++k) {
    const double v = physical(base + static_cast<Eigen::Index>(k));
    const std::string& e = effects[k];
    candidate(e);
    if (e == "density_error")
      density_error = v;
    else if (e == "precurved_rest_shape")
      shape.rest_curvature = v;
    else if (e == "cupped_rest_shape")
      shape.rest_cupping = v;
    else if (e == "distal_softening")
      shape.distal_softening = v;
    else
      E *= v;  // modulus_offset
  }
  const auto& f = setup_.flap;
  const double buoyancy = (f.fluid_density - f.solid_density - density_error) * f.gravity * f.width * f.thickness;
  std::vector<double> out;
  for (const auto& frame : setup_.frames) {
    const fv::FlapLoad load{buoyancy, frame.flow_transverse, frame.flow_along};
    out.push_back(fv::flap_deflection(f, E, setup_.mesh, load, shape, setup_.load_steps).tip);
  }
  return out;
}

Eigen::VectorXd FlapTracedModel::residuals(const std::vector<std::string>& effects,
                                           const Eigen::VectorXd& physical) const {
  const std::vector<double> t = tips(effects, physical);
  Eigen::VectorXd r = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(t.size()));
  for (std::size_t k = 0; k < t.size(); ++k) r(3 * static_cast<Eigen::Index>(k) + 2) = t[k] - setup_.frames[k].measured;
  return r;
}

}  // namespace finverse::loop
