// Hybrid plate twin: model factory, pressure loads and truth motion (see hybrid_plate_twin.hpp).
#include "fit/validation/hybrid_plate_twin.hpp"

#include <cmath>

#include <Eigen/Geometry>

#include "fem/structural_run.hpp"
#include "fit/errors.hpp"

namespace finverse::fit::validation {

using fem::validation::HybridPlateLoad;

HybridPlateTwin::HybridPlateTwin(fem::validation::HybridPlateCase plate, int nx, int nz, fem::LoadHistory loads)
    : case_(std::move(plate)), nx_(nx), nz_(nz), loads_(std::move(loads)) {
  fem::validation::HybridPlateModel hp = fem::validation::build_hybrid_plate(case_, nx_, nz_, HybridPlateLoad::heave);
  leading_edge_ = hp.leading_edge;
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
  const std::unique_ptr<fem::Model> model = twin.build(physical);
  for (const fem::RunFrame& f : fem::run_structural_analysis(*model, run, target.times))
    target.positions.push_back(f.state.position);
  return target;
}

}  // namespace finverse::fit::validation
