// Uniform pitching plate twin: case, model factory, loads and truth (see uniform_plate_twin.hpp).
#include "fit/validation/uniform_plate_twin.hpp"

#include <cmath>
#include <numbers>

#include "fem/errors.hpp"
#include "fem/structural_run.hpp"
#include "fem/validation/hybrid_plate_model.hpp"
#include "fit/errors.hpp"

namespace finverse::fit::validation {

namespace {

using fem::validation::HybridPlateLoad;

// The plate as a hybrid plate without beams: build_hybrid_plate's mesh, shells and leading-edge
// set, held there (HybridPlateLoad::none); the pitch is prescribed on top of that hold.
fem::validation::HybridPlateCase as_hybrid_case(const UniformPlateCase& c, double E, double nu) {
  fem::validation::HybridPlateCase h;
  h.chord = c.chord;
  h.span = c.span;
  h.thickness = c.thickness();
  h.plate = {"plate", E, nu, c.density()};
  return h;
}

}  // namespace

double UniformPlateCase::thickness() const {
  const double nu = poisson_ratio;
  return std::cbrt(12.0 * (1.0 - nu * nu) * bending_stiffness * chord * chord * chord / youngs_modulus);
}

double UniformPlateCase::density() const { return mass_ratio * chord / thickness(); }

// theta = a r s with r the ramp, s = sin(w t); products differentiated term by term.
double UniformPlateCase::pitch(double t) const {
  const double w = 2 * std::numbers::pi * frequency, Tr = ramp_periods / frequency;
  const double r = t >= Tr ? 1.0 : 0.5 * (1 - std::cos(std::numbers::pi * t / Tr));
  return pitch_amplitude * r * std::sin(w * t);
}

double UniformPlateCase::pitch_rate(double t) const {
  const double w = 2 * std::numbers::pi * frequency, Tr = ramp_periods / frequency, q = std::numbers::pi / Tr;
  const bool ramping = t < Tr;
  const double r = ramping ? 0.5 * (1 - std::cos(q * t)) : 1.0;
  const double dr = ramping ? 0.5 * q * std::sin(q * t) : 0.0;
  return pitch_amplitude * (dr * std::sin(w * t) + r * w * std::cos(w * t));
}

double UniformPlateCase::pitch_acceleration(double t) const {
  const double w = 2 * std::numbers::pi * frequency, Tr = ramp_periods / frequency, q = std::numbers::pi / Tr;
  const bool ramping = t < Tr;
  const double r = ramping ? 0.5 * (1 - std::cos(q * t)) : 1.0;
  const double dr = ramping ? 0.5 * q * std::sin(q * t) : 0.0;
  const double ddr = ramping ? 0.5 * q * q * std::cos(q * t) : 0.0;
  const double s = std::sin(w * t), c = std::cos(w * t);
  return pitch_amplitude * (ddr * s + 2 * dr * w * c - r * w * w * s);
}

RigidPlateMotion UniformPlateCase::rigid_motion() const {
  RigidPlateMotion m;
  const UniformPlateCase c = *this;
  m.theta = [c](double t) { return c.pitch(t); };
  m.thetadot = [c](double t) { return c.pitch_rate(t); };
  m.thetaddot = [c](double t) { return c.pitch_acceleration(t); };
  return m;
}

UniformPlateTwin::UniformPlateTwin(UniformPlateCase plate, int nx, int nz, fem::LoadHistory loads)
    : case_(std::move(plate)), nx_(nx), nz_(nz), loads_(std::move(loads)) {
  if (!(case_.chord > 0 && case_.span > 0 && case_.youngs_modulus > 0 && case_.mass_ratio > 0 &&
        case_.bending_stiffness > 0 && case_.frequency > 0 && case_.ramp_periods >= 1))
    throw fem::InvalidInput("uniform plate twin: chord, span, E, mass ratio, K and frequency must be > 0 and "
                            "the ramp at least one period");
  // Loads of the wrong length fail here (Model::set_load_history), not in the first evaluation.
  const std::unique_ptr<fem::Model> m = build(truth());
  leading_edge_ = translation_prescribed_nodes(*m);
  // build_hybrid_plate numbers the rectangle's nodes row by row (z), x fastest.
  for (int j = 0; j <= nz_; ++j) trailing_edge_.push_back(j * (nx_ + 1) + nx_);
  for (int n : trailing_edge_)
    if (std::abs(m->reference_positions()[n].x() - case_.chord) > 1e-9 * case_.chord)
      throw InvalidInput("uniform plate twin: the trailing-edge node numbering does not match the plate builder");
}

Eigen::VectorXd UniformPlateTwin::truth() const {
  return (Eigen::VectorXd(2) << case_.youngs_modulus, case_.poisson_ratio).finished();
}

std::unique_ptr<fem::Model> UniformPlateTwin::build(const Eigen::VectorXd& p) const {
  if (p.size() != 2)
    throw InvalidInput("uniform plate twin: " + std::to_string(p.size()) + " parameter values for 2 parameters");
  // The thickness and density stay those of the case (the truth's K and mass ratio): a trial E
  // or nu changes the plate's stiffness, not its geometry or mass.
  fem::validation::HybridPlateModel hp = fem::validation::build_hybrid_plate(
      as_hybrid_case(case_, p(0), p(1)), nx_, nz_, HybridPlateLoad::none);
  const UniformPlateCase c = case_;
  // Rotation about +z of -theta: nose up lowers the trailing edge (y = -x sin theta).
  for (int n : hp.leading_edge) hp.model.prescribe(n, 5, [c](double t) { return -c.pitch(t); });
  if (!loads_.empty()) hp.model.set_load_history(loads_);
  return std::make_unique<fem::Model>(std::move(hp.model));
}

fem::LoadHistory uniform_plate_loads(const UniformPlateCase& plate, int nx, int nz, double load_density,
                                     const std::vector<double>& times) {
  const UniformPlateTwin bare(plate, nx, nz);
  const std::unique_ptr<fem::Model> model = bare.build(bare.truth());
  return thin_airfoil_loads(*model, ThinAirfoilFlow{load_density, 1.0, plate.chord, 0.0}, plate.rigid_motion(),
                            times);
}

TargetMotion uniform_plate_truth(const UniformPlateTwin& twin, const Eigen::VectorXd& physical,
                                 const TwinTruthOptions& o) {
  if (!(o.output_interval > 0 && o.end_time > 0) || o.substeps < 1)
    throw InvalidInput("uniform plate truth: output interval and end time must be > 0, substeps >= 1");
  const long n = std::lround(std::floor(o.end_time / o.output_interval + 1e-9));
  if (n < 1) throw InvalidInput("uniform plate truth: end time shorter than one output interval");
  TargetMotion target;
  target.source = "uniform plate truth";
  for (long k = 1; k <= n; ++k) target.times.push_back(static_cast<double>(k) * o.output_interval);
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
