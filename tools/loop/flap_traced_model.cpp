// The Hessenthaler flap as a traced model (flap_traced_model.hpp).
#include "loop/flap_traced_model.hpp"

#include <algorithm>
#include <cmath>

#include "loop/errors.hpp"
#include "fem/errors.hpp"

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
      // Flow side (a 3-D frame and the perturbed runs only): the glycerol's viscosity within
      // +-30 % (its temperature), the inflows' speed within +-20 % (the pump's calibration).
      {"viscosity_error", {"viscosity_factor", "1", 0.7, 1.3, fit::Scale::linear, std::nullopt}, 1},
      {"inflow_error", {"inflow_factor", "1", 0.8, 1.2, fit::Scale::linear, std::nullopt}, 1},
  };
  return all;
}

FlapTracedModel::FlapTracedModel(FlapTraceSetup setup) : setup_(std::move(setup)) {
  if (!(setup_.youngs_modulus > 0) || !std::isfinite(setup_.youngs_modulus))
    throw InvalidInput("flap loop: the Young's modulus must be positive");
  if (setup_.frames.empty()) throw InvalidInput("flap loop: no measured frame");
  bool flow_3d = false;
  for (const auto& f : setup_.frames) {
    if (f.centreline.size() != setup_.frames.front().centreline.size())
      throw InvalidInput("flap loop: every frame needs the same number of centreline points");
    if (f.flow_3d) {
      flow_3d = true;
      if (setup_.mesh.model != fv::FlapModel::shell || f.flow_3d->along != setup_.mesh.along ||
          f.flow_3d->across != setup_.mesh.across)
        throw InvalidInput("flap loop: the 3-D load of " + f.flow_3d->source.string() + " is on a " +
                           std::to_string(f.flow_3d->along) + " x " + std::to_string(f.flow_3d->across) +
                           " strip, the loop's is not that shell strip");
    }
  }
  const auto available = [&](const std::string& n) {
    if (n == "viscosity_error") return flow_3d && setup_.viscosity_run.has_value();
    if (n == "inflow_error") return flow_3d && setup_.inflow_run.has_value();
    return true;
  };
  if (setup_.candidates.empty()) {
    for (const auto& c : flap_candidates())
      if (available(c.name)) names_.push_back(c.name);
  } else {
    names_ = setup_.candidates;
  }
  for (const auto& n : names_)
    if (!available(candidate(n).name))
      throw InvalidInput("flap loop: candidate " + n + " needs a 3-D frame and the run with that factor perturbed");
  for (const auto* run : {&setup_.viscosity_run, &setup_.inflow_run})
    if (*run && std::abs((run == &setup_.viscosity_run ? (*run)->viscosity_factor : (*run)->inflow_factor) - 1) < 1e-6)
      throw InvalidInput("flap loop: " + (*run)->source.string() + " is not a perturbed run (its factor is 1)");
}

const FlapCandidate& FlapTracedModel::candidate(const std::string& name) const {
  for (const auto& c : flap_candidates())
    if (c.name == name) return c;
  throw InvalidInput("flap loop: unknown candidate '" + name +
                     "' (expected density_error, precurved_rest_shape, cupped_rest_shape, distal_softening or "
                     "modulus_offset, viscosity_error, inflow_error)");
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
  // Central (every off value is inside its bounds): a density error and E enter the no-flow
  // deflection only as their ratio, so the density's one-sided difference would differ from
  // span(J) by its curvature term alone, and score on it.
  return {{Eigen::VectorXd::Constant(1, c.off + h), h, true}};
}

Eigen::VectorXd FlapTracedModel::effect_off(const std::string& name) const {
  return Eigen::VectorXd::Constant(1, candidate(name).off);
}

std::vector<double> FlapTracedModel::tips(const std::vector<std::string>& effects,
                                          const Eigen::VectorXd& physical) const {
  std::vector<double> out;
  for (const auto& d : deflections(effects, physical)) out.push_back(d.tip);
  return out;
}

std::vector<fv::FlapDeflection> FlapTracedModel::deflections(const std::vector<std::string>& effects,
                                                             const Eigen::VectorXd& physical) const {
  const int base = setup_.refit_modulus ? 1 : 0;
  if (physical.size() != base + static_cast<Eigen::Index>(effects.size()))
    throw InvalidInput("flap loop: expected " + std::to_string(base + effects.size()) + " parameters");
  double E = setup_.refit_modulus ? physical(0) : setup_.youngs_modulus, density_error = 0;
  double viscosity = 1, inflow = 1;
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
    else if (e == "viscosity_error")
      viscosity = v;
    else if (e == "inflow_error")
      inflow = v;
    else
      E *= v;  // modulus_offset
  }
  const auto& f = setup_.flap;
  const double buoyancy = (f.fluid_density - f.solid_density - density_error) * f.gravity * f.width * f.thickness;
  std::vector<fv::FlapDeflection> out;
  for (const auto& frame : setup_.frames) {
    if (frame.flow_3d) {
      out.push_back(settle_in_flow(frame, E, buoyancy, shape, viscosity, inflow));
      continue;
    }
    const fv::FlapLoad load{buoyancy, frame.flow_transverse, frame.flow_along, {}};
    out.push_back(fv::flap_deflection(f, E, setup_.mesh, load, shape, setup_.load_steps));
  }
  return out;
}

// The flap in the 3-D flow: the tip t where the structure under the load F(t) (linear in the
// tip, plus the flow-side errors' share) ends at t again. phi(t) = tip(S(F(t))) - t falls steeply
// (about -15 to -30 per unit: the tip meets the jet's edge), so secants converge in a few steps.
fv::FlapDeflection FlapTracedModel::settle_in_flow(const FlapFrame& frame, double E, double buoyancy,
                                                   const fv::FlapShape& shape, double viscosity,
                                                   double inflow) const {
  const FlapFlowLoad& base = *frame.flow_3d;
  const auto load_at = [&](double t) {
    Eigen::VectorXd F = base.at(t);
    if (viscosity != 1)
      F += (viscosity - 1) / (setup_.viscosity_run->viscosity_factor - 1) * (setup_.viscosity_run->at(t) - base.at(t));
    if (inflow != 1)
      F += (inflow - 1) / (setup_.inflow_run->inflow_factor - 1) * (setup_.inflow_run->at(t) - base.at(t));
    return F;
  };
  fv::FlapDeflection d;
  const auto phi = [&](double t) {
    const Eigen::VectorXd F = load_at(t);
    const fv::FlapLoad load{buoyancy, {}, {}, std::vector<double>(F.data(), F.data() + F.size())};
    d = fv::flap_deflection(setup_.flap, E, setup_.mesh, load, shape, setup_.load_steps);
    return d.tip - t;
  };
  double t0 = base.tip0, p0 = phi(t0), t1 = t0 + 0.5e-3, p1 = phi(t1);
  for (int k = 0; k < 30; ++k) {
    if (std::abs(t1 - t0) < 1e-9 && std::abs(p1) < 1e-7) return d;
    if (p1 == p0) break;
    const double t2 = t1 - p1 * (t1 - t0) / (p1 - p0);
    t0 = t1, p0 = p1;
    t1 = t2, p1 = phi(t1);
  }
  if (std::abs(p1) < 1e-7) return d;
  throw fem::NotConverged("flap loop: the flap found no rest in the 3-D flow's load (tip " +
                          std::to_string(t1 * 1e3) + " mm, mismatch " + std::to_string(p1 * 1e3) + " mm)");
}

double FlapTracedModel::centreline_at(const fv::FlapDeflection& d, double z) {
  const auto& c = d.centreline;
  if (c.empty()) throw InvalidInput("flap loop: a deflection without centreline");
  if (z <= c.front()[0]) return 0.0;
  for (std::size_t k = 0; k + 1 < c.size(); ++k)
    if (z <= c[k + 1][0]) {
      const double dz = c[k + 1][0] - c[k][0], a = dz > 0 ? (z - c[k][0]) / dz : 0;
      return (1 - a) * c[k][1] + a * c[k + 1][1] - c.front()[1];
    }
  return c.back()[1] - c.front()[1];
}

Eigen::VectorXd FlapTracedModel::residuals(const std::vector<std::string>& effects,
                                           const Eigen::VectorXd& physical) const {
  const auto d = deflections(effects, physical);
  const std::size_t points = std::max<std::size_t>(1, setup_.frames.front().centreline.size());
  Eigen::VectorXd r = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(3 * points * d.size()));
  for (std::size_t k = 0; k < d.size(); ++k) {
    const auto& frame = setup_.frames[k];
    if (frame.centreline.empty()) {
      r(static_cast<Eigen::Index>(3 * k + 2)) = d[k].tip - frame.measured;
      continue;
    }
    for (std::size_t i = 0; i < points; ++i) {
      const auto& [z, y] = frame.centreline[i];
      r(static_cast<Eigen::Index>(3 * (k * points + i) + 2)) = centreline_at(d[k], z) - y;
    }
  }
  return r;
}

}  // namespace finverse::loop
