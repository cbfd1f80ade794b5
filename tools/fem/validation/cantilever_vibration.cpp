// Cantilever vibration validation: first three bending frequencies of a uniform cantilever
// against Euler-Bernoulli theory, (a) from the linearised generalized eigenproblem, (b) from the
// spectrum of a simulated free vibration after a tip impulse (generalized-alpha, rho_inf = 1);
// and the energy drift of an undamped free vibration over 100 periods.
#include "fem/validation/cases.hpp"

#include <chrono>
#include <cmath>
#include <numbers>
#include <sstream>

#include "fem/errors.hpp"
#include "fem/generalized_alpha.hpp"
#include "fem/modal.hpp"
#include "fem/model.hpp"
#include "fem/spectral_peaks.hpp"
#include "fem/static_solver.hpp"

namespace finverse::fem::validation {

double cantilever_beta_l(int n) {
  if (n < 1) throw InvalidInput("cantilever_beta_l: n must be >= 1");
  // Root near (2n - 1) pi / 2; Newton on f(x) = cos x cosh x + 1 converges from there.
  double x = (2 * n - 1) * std::numbers::pi / 2;
  if (n == 1) x = 1.875;
  for (int it = 0; it < 100; ++it) {
    const double f = std::cos(x) * std::cosh(x) + 1;
    const double df = -std::sin(x) * std::cosh(x) + std::cos(x) * std::sinh(x);
    const double dx = f / df;
    x -= dx;
    if (std::abs(dx) < 1e-15 * x) break;
  }
  return x;
}

namespace {
struct Beam {
  double L = 1.0, width = 0.02, thickness = 0.01, E = 2.0e11, nu = 0.3, rho = 7800;
  double EI() const { return E * width * thickness * thickness * thickness / 12.0; }
  double mass_per_length() const { return rho * width * thickness; }
  double omega(int n) const {
    const double b = cantilever_beta_l(n);
    return b * b / (L * L) * std::sqrt(EI() / mass_per_length());
  }
};

// Fraction of a mode's translational amplitude in z (bending about the thin direction).
double z_fraction(const Eigen::VectorXd& shape) {
  double z = 0, all = 0;
  for (int i = 0; i < shape.size(); ++i) {
    if (i % kDofsPerNode >= 3) continue;
    all += shape(i) * shape(i);
    if (i % kDofsPerNode == 2) z += shape(i) * shape(i);
  }
  return all > 0 ? z / all : 0;
}
}  // namespace

Summary run_cantilever_vibration(const VibrationOptions& opt) {
  if (opt.elements < 3) throw InvalidInput("cantilever_vibration: --elements must be >= 3");
  const Beam beam;
  Model model;
  const int mat = model.add_material({"steel", beam.E, beam.nu, beam.rho});
  const int ne = opt.elements, tip = ne;
  for (int i = 0; i <= ne; ++i) model.add_node(Vec3(beam.L * i / ne, 0, 0));
  for (int i = 0; i < ne; ++i)
    model.add_beam(i, i + 1, mat, TaperedRectangle::uniform(beam.width, beam.thickness),
                   Vec3(0, 1, 0));
  model.fix_node(0);

  Summary report(
      "validation", "cantilever_vibration",
      "Uniform cantilever: first three bending frequencies against Euler-Bernoulli (linearised "
      "eigenproblem and spectrum of a simulated free vibration), and energy drift of an undamped "
      "free vibration over 100 periods with generalized-alpha (rho_inf = 1)");
  const std::string eb_source =
      "Euler-Bernoulli cantilever, omega_n = (beta_n L)^2 sqrt(EI/(rho A L^4)), cos(bL)cosh(bL) = -1 "
      "(beta_n L = 1.87510407, 4.69409113, 7.85475744)";
  report.parameters() = {{"length_m", beam.L},
                         {"width_m", beam.width},
                         {"thickness_m", beam.thickness},
                         {"youngs_modulus_Pa", beam.E},
                         {"density_kg_m3", beam.rho},
                         {"elements", ne},
                         {"solver", to_string(opt.backend)},
                         {"steps_per_period_spectrum", opt.steps_per_period_spectrum},
                         {"periods_spectrum", opt.periods_spectrum},
                         {"steps_per_period_energy", opt.steps_per_period_energy},
                         {"periods_energy", opt.periods_energy},
                         {"spectral_radius", 1.0}};

  // (a) Eigenproblem; keep the z-bending modes (the y-bending, torsion and axial modes of the
  // 3-D model interleave with them).
  ModalOptions mo;
  mo.modes = 12;
  mo.backend = opt.backend;
  const ModalResult modes = modal_analysis(model, model.reference_state(), mo);
  std::vector<double> bending;
  for (int k = 0; k < modes.omega.size() && bending.size() < 3; ++k)
    if (z_fraction(modes.shapes.col(k)) > 0.9) bending.push_back(modes.frequency(k));
  if (bending.size() < 3) throw NotConverged("cantilever_vibration: fewer than 3 z-bending modes among the first 12");
  for (int n = 1; n <= 3; ++n) {
    const double f_ref = beam.omega(n) / (2 * std::numbers::pi);
    report.relative("f" + std::to_string(n) + "_eigen", bending[n - 1], f_ref,
                    opt.frequency_tolerance, eb_source, "Hz");
  }

  const double T1 = 2 * std::numbers::pi / beam.omega(1);

  // (b) Free vibration after a tip impulse: every mode gets a comparable velocity amplitude.
  {
    DynamicOptions dyn;
    dyn.time_step = T1 / opt.steps_per_period_spectrum;
    dyn.spectral_radius = 1.0;
    dyn.backend = opt.backend;
    GeneralizedAlpha integrator(model, dyn);
    DynamicState s = integrator.reference_state();
    const double v0 = 1e-3 * beam.L * beam.omega(1);  // tip amplitude ~1e-3 L: linear range
    s.velocity(kDofsPerNode * tip + 2) = v0;
    integrator.initialize(s);
    const int steps = static_cast<int>(std::lround(opt.periods_spectrum * opt.steps_per_period_spectrum));
    std::vector<double> signal;
    signal.reserve(steps);
    int iterations = 0;
    for (int k = 0; k < steps; ++k) {
      iterations += integrator.step(s).iterations;
      signal.push_back(s.velocity(kDofsPerNode * tip + 2));
    }
    const auto peaks = spectral_peaks(signal, dyn.time_step, 3, 0.5 / (opt.periods_spectrum * T1));
    for (int n = 1; n <= 3; ++n) {
      const double f_ref = beam.omega(n) / (2 * std::numbers::pi);
      const double f = n <= static_cast<int>(peaks.size()) ? peaks[n - 1].frequency : NAN;
      report.relative("f" + std::to_string(n) + "_dynamic", f, f_ref, opt.frequency_tolerance,
                      eb_source, "Hz");
    }
    report.info("spectrum_time_steps", steps);
    report.info("spectrum_newton_iterations_per_step", static_cast<double>(iterations) / steps);
  }

  // (c) Energy: release from a static tip deflection of 1e-3 L, undamped, 100 periods.
  {
    Model loaded;  // same structure with the tip load that makes the initial shape
    const int m2 = loaded.add_material({"steel", beam.E, beam.nu, beam.rho});
    for (int i = 0; i <= ne; ++i) loaded.add_node(Vec3(beam.L * i / ne, 0, 0));
    for (int i = 0; i < ne; ++i)
      loaded.add_beam(i, i + 1, m2, TaperedRectangle::uniform(beam.width, beam.thickness),
                      Vec3(0, 1, 0));
    loaded.fix_node(0);
    loaded.add_nodal_load(tip, 2, 3 * beam.EI() / std::pow(beam.L, 3) * 1e-3 * beam.L);
    StaticOptions so;
    so.steps = 1;
    so.backend = opt.backend;
    StaticSolver statics(loaded, so);
    NodalState initial = loaded.reference_state();
    statics.solve(initial, 0, 1);

    DynamicOptions dyn;
    dyn.time_step = T1 / opt.steps_per_period_energy;
    dyn.spectral_radius = 1.0;
    dyn.backend = opt.backend;
    GeneralizedAlpha integrator(model, dyn);
    DynamicState s = integrator.reference_state();
    s.configuration = initial;
    integrator.initialize(s);
    const double e0 = integrator.kinetic_energy(s) + integrator.strain_energy(s);
    const int steps = static_cast<int>(std::lround(opt.periods_energy * opt.steps_per_period_energy));
    double drift = 0;
    for (int k = 0; k < steps; ++k) {
      integrator.step(s);
      const double e = integrator.kinetic_energy(s) + integrator.strain_energy(s);
      drift = std::max(drift, std::abs(e - e0) / e0);
    }
    report.at_most("energy_drift", drift, opt.energy_drift_goal,
                   "DESIGN/brief: undamped linear-range vibration, max |E(t) - E(0)| / E(0) over " +
                       std::to_string(static_cast<int>(opt.periods_energy)) + " periods");
    report.info("initial_energy", e0, "J");
    report.info("energy_time_steps", steps);
  }
  return report;
}

}  // namespace finverse::fem::validation
