// Hybrid plate twin: model factory, pressure loads and truth motion (see hybrid_plate_twin.hpp).
#include "fit/validation/hybrid_plate_twin.hpp"

#include <cmath>

#include <Eigen/Geometry>

#include "fem/structural_run.hpp"
#include "fit/errors.hpp"

namespace finverse::fit::validation {

using fem::validation::HybridPlateLoad;

namespace {

// Smooth start (issue 31). The twin's truth runs from rest without damping (in vacuo, and the
// prescribed loads do not feed back, so there is no fluid damping either). Started abruptly --
// the heave A (1 - cos wt) jumps to the acceleration A w^2 at t = 0 and the thin-airfoil loads
// to their added-mass value -- the plate rings at its first natural frequency (1.63 Hz for the
// case, 3.3x the drive) forever, with a tip amplitude of ~3x the heave amplitude at load density
// 1 (measured on 8 x 8): that free vibration dominated the last period. Eq. (2) cannot represent
// it (no load drives it), so the quasi-static fit ran every modulus to its upper bound, and it
// made eq. (1)'s landscape multimodal (the ringing's phase omega_n(E) t shifts by radians for a
// 10 % change of E). Drive and loads are therefore multiplied by a C2 window rising from 0 to 1
// over the first period (u^3 (10 - 15 u + 6 u^2), u = t f): the motion from the second period
// on is the case's, and the free vibration left is ~1e-3 of the forced response.
double start_window(double t, double period) {
  if (t <= 0) return 0;
  if (t >= period) return 1;
  const double u = t / period;
  return u * u * u * (10 - 15 * u + 6 * u * u);
}

fem::LoadHistory windowed(const fem::LoadHistory& loads, double period) {
  if (loads.empty()) return loads;
  std::vector<Eigen::VectorXd> values;
  values.reserve(loads.times().size());
  for (double t : loads.times()) values.push_back(start_window(t, period) * loads.at(t));
  return fem::LoadHistory(loads.times(), std::move(values), loads.ramp());
}

}  // namespace

HybridPlateTwin::HybridPlateTwin(fem::validation::HybridPlateCase plate, int nx, int nz, fem::LoadHistory loads)
    : case_(std::move(plate)), nx_(nx), nz_(nz), loads_(std::move(loads)) {
  fem::validation::HybridPlateModel hp = fem::validation::build_hybrid_plate(case_, nx_, nz_, HybridPlateLoad::heave);
  leading_edge_ = hp.leading_edge;
  if (!(case_.frequency > 0)) throw InvalidInput("hybrid plate twin: the heave frequency must be > 0");
  loads_ = windowed(loads_, 1.0 / case_.frequency);
  // Loads of the wrong length fail here, not in the first evaluation.
  if (!loads_.empty()) hp.model.set_load_history(loads_);
}

std::vector<std::string> HybridPlateTwin::parameter_names() const {
  std::vector<std::string> names{"E_s"};
  for (size_t b = 0; b < case_.beams.size(); ++b) names.push_back("E_b" + std::to_string(b + 1));
  names.push_back("nu");
  return names;
}

Eigen::VectorXd HybridPlateTwin::truth() const {
  Eigen::VectorXd p(static_cast<Eigen::Index>(case_.beams.size() + 2));
  p(0) = case_.plate.youngs_modulus;
  for (size_t b = 0; b < case_.beams.size(); ++b) p(static_cast<Eigen::Index>(b + 1)) = case_.beams[b].material.youngs_modulus;
  p(p.size() - 1) = case_.plate.poisson_ratio;
  return p;
}

std::unique_ptr<fem::Model> HybridPlateTwin::build(const Eigen::VectorXd& p) const {
  if (p.size() != parameter_count())
    throw InvalidInput("hybrid plate twin: " + std::to_string(p.size()) + " parameter values for " +
                       std::to_string(parameter_count()) + " parameters");
  fem::validation::HybridPlateCase c = case_;
  const double nu = p(p.size() - 1);
  c.plate.youngs_modulus = p(0);
  c.plate.poisson_ratio = nu;
  for (size_t b = 0; b < c.beams.size(); ++b) {
    c.beams[b].material.youngs_modulus = p(static_cast<Eigen::Index>(b + 1));
    c.beams[b].material.poisson_ratio = nu;
  }
  fem::validation::HybridPlateModel hp = fem::validation::build_hybrid_plate(c, nx_, nz_, HybridPlateLoad::heave);
  const double period = 1.0 / c.frequency;
  for (int n : hp.leading_edge)
    hp.model.prescribe(n, 1, [c, period](double t) { return start_window(t, period) * c.heave(t); });
  if (!loads_.empty()) hp.model.set_load_history(loads_);
  return std::make_unique<fem::Model>(std::move(hp.model));
}

fem::LoadHistory hybrid_plate_pressure_loads(const fem::validation::HybridPlateCase& plate, int nx, int nz,
                                             const std::function<double(double)>& pressure,
                                             const std::vector<double>& times) {
  const fem::validation::HybridPlateModel hp =
      fem::validation::build_hybrid_plate(plate, nx, nz, HybridPlateLoad::none);
  const fem::Model& m = hp.model;
  const auto& X = m.reference_positions();
  // Unit-pressure nodal forces along -y from the shell triangles (the beams carry no pressure).
  Eigen::VectorXd unit = Eigen::VectorXd::Zero(fem::kDofsPerNode * m.node_count());
  for (const auto& e : m.elements()) {
    const auto n = e->nodes();
    if (n.size() != 3) continue;
    const double area = 0.5 * (X[n[1]] - X[n[0]]).cross(X[n[2]] - X[n[0]]).norm();
    for (int v : n) unit(fem::kDofsPerNode * v + 1) -= area / 3.0;
  }
  std::vector<Eigen::VectorXd> values;
  for (double t : times) values.push_back(pressure(t) * unit);
  return fem::LoadHistory(times, std::move(values));
}

TargetMotion hybrid_plate_truth(const HybridPlateTwin& twin, const Eigen::VectorXd& physical,
                                const TwinTruthOptions& o) {
  const auto& c = twin.plate_case();
  const double h = o.output_interval > 0 ? o.output_interval : c.time_step;
  const double end = o.end_time > 0 ? o.end_time : c.periods / c.frequency;
  const long n = std::lround(std::floor(end / h + 1e-9));
  if (n < 1) throw InvalidInput("hybrid plate truth: end time shorter than one output interval");
  TargetMotion target;
  target.source = "hybrid plate truth";
  for (long k = 1; k <= n; ++k) target.times.push_back(static_cast<double>(k) * h);
  fem::RunOptions run;
  run.analysis = fem::Analysis::dynamic;
  run.start_time = 0;
  run.substeps = o.substeps;
  run.dynamic_options.spectral_radius = o.spectral_radius;
  // As DynamicObjective (dynamic_objective.cpp): the smooth start's first steps move by ~1e-12.
  run.dynamic_options.increment_tolerance = 1e-6;
  const std::unique_ptr<fem::Model> model = twin.build(physical);
  for (const fem::RunFrame& f : fem::run_structural_analysis(*model, run, target.times))
    target.positions.push_back(f.state.position);
  return target;
}

}  // namespace finverse::fit::validation
