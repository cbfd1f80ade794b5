// The hybrid-plate twin set-up shared by the fit validations and the benchmark (see
// hybrid_plate_setup.hpp).
#include "fit/validation/hybrid_plate_setup.hpp"

#include <cmath>
#include <numbers>

#include "fit/errors.hpp"
#include "fit/validation/thin_airfoil_loads.hpp"

namespace finverse::fit::validation {


HybridPlateTwinRun make_hybrid_plate_twin(const HybridPlateSetup& o, bool with_loads) {
  HybridPlateTwinRun t;
  t.plate = fem::validation::read_hybrid_plate_case(o.case_file);
  t.period = 1.0 / t.plate.frequency;
  t.dt = t.period / o.steps_per_period;
  t.qs_dt = t.period / o.qs_steps_per_period;
  const double end = o.periods * t.period;
  fem::LoadHistory loads;
  if (with_loads) {
    // The case is nondimensional: fluid density, free-stream speed and chord are 1.
    const HybridPlateTwin bare(t.plate, o.nx, o.nz);
    const auto model = bare.build(bare.truth());
    const double A = t.plate.heave_amplitude, w = 2 * std::numbers::pi * t.plate.frequency;
    RigidPlateMotion m;
    m.h = [=](double s) { return A * (1 - std::cos(w * s)); };
    m.hdot = [=](double s) { return A * w * std::sin(w * s); };
    m.hddot = [=](double s) { return A * w * w * std::cos(w * s); };
    // Sampled finely enough for both objectives' time steps (linear in between).
    const double h = std::min(t.dt, t.qs_dt);
    std::vector<double> times;
    for (int k = 0; k * h <= end + 0.5 * h; ++k) times.push_back(k * h);
    loads = thin_airfoil_loads(*model, ThinAirfoilFlow{o.load_scale, 1.0, t.plate.chord, 0.0}, m, times);
  }
  t.factory = std::make_shared<HybridPlateTwin>(t.plate, o.nx, o.nz, std::move(loads));
  const auto truth_at = [&](double step) {
    TwinTruthOptions to;
    to.output_interval = step;
    to.substeps = 1;
    to.end_time = std::round(end / step) * step;
    TargetMotion m = hybrid_plate_truth(*t.factory, t.factory->truth(), to);
    m.source = "hybrid plate truth";
    return m;
  };
  t.truth = truth_at(t.dt);
  t.qs_truth = o.qs_steps_per_period == o.steps_per_period ? t.truth : truth_at(t.qs_dt);
  return t;
}

// Moduli: a three-decade log10 interval around the truth, 10^-1.3 below to 10^1.7 above (off
// centre); nu in [0.15, 0.45] as the paper.
ParameterSpace hybrid_plate_space(const HybridPlateTwin& twin) {
  const auto names = twin.parameter_names();
  const Eigen::VectorXd truth = twin.truth();
  std::vector<Parameter> p;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const double x = truth(static_cast<Eigen::Index>(i));
    if (names[i] == "nu")
      p.push_back({names[i], "1", 0.15, 0.45, Scale::linear, x});
    else
      p.push_back({names[i], "rho U^2", x * std::pow(10.0, -1.3), x * std::pow(10.0, 1.7), Scale::log10, x});
  }
  return ParameterSpace(p, "hybrid plate twin");
}

// The last period, compared_frames equally spaced frames (eq. (1)).
TargetMotion last_period_frames(const HybridPlateTwinRun& t, const HybridPlateSetup& o, int* substeps) {
  if (o.steps_per_period % o.compared_frames != 0)
    throw InvalidInput("hybrid plate fit: steps per period must be a multiple of the compared frames");
  *substeps = o.steps_per_period / o.compared_frames;
  TargetMotion w;
  w.source = t.truth.source;
  const int n = t.truth.frame_count();  // frame k is t = (k + 1) dt
  for (int j = o.compared_frames - 1; j >= 0; --j) {
    const int k = n - 1 - j * *substeps;
    w.times.push_back(t.truth.times[k]);
    w.positions.push_back(t.truth.positions[k]);
  }
  return w;
}

// Mid-swing instants of the last period (heave velocity extremes), as the paper's eq. (2).
std::vector<double> mid_swing_instants(const HybridPlateTwinRun& t, const HybridPlateSetup& o) {
  std::vector<double> s;
  const double start = (o.periods - 1) * t.period;
  for (int j = 0; j < o.instants; ++j) {
    const double ti = start + t.period / 4 + j * t.period / (2.0 * o.instants);
    s.push_back(std::round(ti / t.qs_dt) * t.qs_dt);
  }
  return s;
}

}  // namespace finverse::fit::validation
