// The uniform-plate twin of the fit validation (tools/fit/validation/uniform_plate_{twin,fit}.hpp,
// the seed paper's sections 3.2-3.3): the case's derived thickness and density, the smooth pitch
// start, the leading-edge drive, eq. (1) vanishing at the truth and growing off it, and a very
// short fit landing near the truth. A coarse plate and time step keep it to seconds; the
// validation itself runs finer (uniform_plate_fit.hpp's defaults).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "fit/dynamic_objective.hpp"
#include "fit/validation/uniform_plate_fit.hpp"
#include "fit/validation/uniform_plate_twin.hpp"

using namespace finverse;
using fit::validation::UniformPlateCase;
using fit::validation::UniformPlateTwin;

namespace {

constexpr int kPlateNx = 6, kNz = 3, kStepsPerPeriod = 100;
constexpr double kDt = 1.0 / kStepsPerPeriod;
// Half the validation's load density (uniform_plate_fit.hpp): on this coarse grid the truth at 0.1
// stalls Newton at t = 1.82 T.
constexpr double kLoad = 0.05;

std::shared_ptr<UniformPlateTwin> make_plate_twin() {
  const UniformPlateCase c;
  std::vector<double> times;
  for (int k = 0; k <= 2 * kStepsPerPeriod; ++k) times.push_back(k * kDt);
  return std::make_shared<UniformPlateTwin>(c, kPlateNx, kNz,
                                            fit::validation::uniform_plate_loads(c, kPlateNx, kNz, kLoad, times));
}

}  // namespace

TEST(UniformPlateTwin, ThicknessDensityAndSmoothPitch) {
  const UniformPlateCase c;
  // K = E h^3 / (12 (1 - nu^2)) = 0.5 and rho_s h = 0.1 (rho_f = U = L = 1).
  const double h = c.thickness();
  EXPECT_NEAR(c.youngs_modulus * h * h * h / (12 * (1 - 0.25 * 0.25)), 0.5, 1e-12);
  EXPECT_NEAR(c.density() * h, 0.1, 1e-12);
  EXPECT_NEAR(h, 9.787e-3, 1e-6);
  // From rest, C2 at the end of the ramp, then alpha0 sin(2 pi t).
  EXPECT_EQ(c.pitch(0), 0);
  EXPECT_EQ(c.pitch_rate(0), 0);
  EXPECT_NEAR(c.pitch_acceleration(0), 0, 1e-15);
  const double e = 1e-7;
  for (double t : {0.3, 1.0, 1.7}) {
    EXPECT_NEAR((c.pitch(t + e) - c.pitch(t - e)) / (2 * e), c.pitch_rate(t), 1e-6) << t;
    EXPECT_NEAR((c.pitch_rate(t + e) - c.pitch_rate(t - e)) / (2 * e), c.pitch_acceleration(t), 1e-5) << t;
  }
  EXPECT_NEAR(c.pitch_acceleration(1 - 1e-12), c.pitch_acceleration(1 + 1e-12), 1e-9);
  EXPECT_NEAR(c.pitch(1.25), 12 * std::numbers::pi / 180, 1e-15);
}

TEST(UniformPlateTwin, LeadingEdgePitchesAboutTheSpanAxis) {
  const auto twin = make_plate_twin();
  EXPECT_EQ(twin->parameter_names(), (std::vector<std::string>{"E", "nu"}));
  EXPECT_EQ(twin->prescribed_nodes().size(), static_cast<size_t>(kNz + 1));
  const fit::TargetMotion truth =
      fit::validation::uniform_plate_truth(*twin, twin->truth(), {.output_interval = kDt, .end_time = 1.25});
  const auto X = twin->build(twin->truth())->reference_positions();
  // At t = 1.25 the pitch is alpha0 (nose up): the leading edge stays put, the trailing edge lies
  // below the chord line's reference (y < 0 on average) and the plate is bent.
  for (int n : twin->prescribed_nodes()) EXPECT_LT((truth.positions.back()[n] - X[n]).norm(), 1e-12);
  double y = 0;
  for (int n : twin->trailing_edge()) y += truth.positions.back()[n].y() / twin->trailing_edge().size();
  std::printf("uniform plate %dx%d: trailing edge y = %.3f at the pitch's peak (rigid: %.3f)\n", kPlateNx, kNz, y,
              -std::sin(twin->plate_case().pitch(1.25)));
  EXPECT_LT(y, 0);
}

TEST(UniformPlateTwin, ObjectiveVanishesAtTheTruthAndGrowsOffIt) {
  const auto twin = make_plate_twin();
  const fit::TargetMotion truth =
      fit::validation::uniform_plate_truth(*twin, twin->truth(), {.output_interval = kDt, .end_time = 2.0});
  // The last period, 10 frames, 10 steps each: the truth's own time step.
  fit::TargetMotion last;
  for (int k = truth.frame_count() - 1 - 90; k < truth.frame_count(); k += 10) {
    last.times.push_back(truth.times[k]);
    last.positions.push_back(truth.positions[k]);
  }
  const fit::DynamicObjective f(twin, last, {.start_time = 0, .substeps = 10});
  const double at_truth = fit::mean_distance(f.residuals(twin->truth()), f.sqrt_weights());
  // Round-off of the truth and the objective's own run (same time step, same Newton tolerances:
  // the dynamic objective accepts a step on the residual test, increments below 1e-6 relative).
  EXPECT_LT(at_truth, 1e-11);
  for (auto [i, factor] : {std::pair{0, 1.02}, std::pair{1, 1.05}}) {
    Eigen::VectorXd p = twin->truth();
    p(i) *= factor;
    const double off = fit::mean_distance(f.residuals(p), f.sqrt_weights());
    std::printf("uniform plate: J = %.2e at the truth, %.2e at %.2f x %s\n", at_truth, off, factor,
                twin->parameter_names()[i].c_str());
    EXPECT_GT(off, 1e-3) << twin->parameter_names()[i];  // chords: a visible change of the motion
  }
}

TEST(UniformPlateFit, AShortFitLandsNearTheTruth) {
  fit::validation::UniformPlateFitOptions o;
  o.nx = kPlateNx, o.nz = kNz, o.steps_per_period = kStepsPerPeriod, o.compared_frames = 10, o.load_scale = kLoad;
  // A box of +-0.1 decade around the truth (the basin's width): the machinery, not the global
  // search, which the validation runs over three decades.
  o.decades_below = 0.1, o.decades_above = 0.1;
  o.fit.runs = 1, o.fit.population = 4, o.fit.max_generations = 2, o.fit.threads = 2, o.fit.seed = 3;
  o.fit.polish_options.max_evaluations = 12;
  const auto t0 = std::chrono::steady_clock::now();
  const Summary s = fit::validation::run_uniform_plate_fit(o);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  double e_err = NAN, nu_err = NAN, evaluations = 0;
  for (const Metric& m : s.metrics()) {
    if (m.name == "E") e_err = m.error();
    if (m.name == "nu") nu_err = m.error();
    if (m.name == "evaluations") evaluations = m.value;
  }
  std::printf("short uniform-plate fit: E error %.2e, nu error %.2e, %g evaluations, %.1f s\n", e_err, nu_err,
              evaluations, wall);
  EXPECT_LT(e_err, 0.03);
  EXPECT_LT(nu_err, 0.05);
}
