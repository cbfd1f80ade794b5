// Test (b): the added-mass model problem (added_mass_tube.hpp, Causin, Gerbeau & Nobile 2005) with
// rho_f L / (rho_s h_s) = 10: the plain iteration's error operator has spectral radius > 1 (printed),
// constant omega = 1 is reported as diverged, Aitken (both rules) and IQN-ILS converge to the
// monolithic solution, IQN-ILS in fewer iterations. Mean and max iterations per step are printed
// for each acceleration and for IQN-ILS's reuse depth q.
#include <gtest/gtest.h>

#include <cstdio>

#include "added_mass_tube.hpp"
#include "fsi/aitken.hpp"
#include "fsi/constant_relaxation.hpp"
#include "fsi/iqn_ils.hpp"

namespace finverse::fsi {
namespace {

constexpr double kDt = 0.01;
constexpr int kSteps = 40;

struct RunResult {
  double mean = 0.0;
  int max = 0;
  double error = 0.0;  // max over steps of |eta - eta_monolithic| / max |eta_monolithic|
  std::string failure;
};

RunResult run(const test::TubeParameters& params, std::unique_ptr<Acceleration> acceleration) {
  test::AddedMassTube tube(params);
  CouplingOptions options;
  options.convergence.relative_tolerance = 1e-6;
  options.max_iterations = 200;
  ImplicitCoupling coupling(tube.layout(), tube.state(), std::move(acceleration), options);
  Eigen::VectorXd eta = Eigen::VectorXd::Zero(params.n), v = eta;
  RunResult result;
  double total = 0.0, largest = 0.0, worst = 0.0;
  try {
    for (int n = 1; n <= kSteps; ++n) {
      const StepStatistics stats = coupling.advance(tube, kDt);
      total += stats.iterations;
      result.max = std::max(result.max, stats.iterations);
      tube.monolithic_step(eta, v, n * kDt, kDt);
      largest = std::max(largest, eta.norm());
      worst = std::max(worst, (coupling.state().head(params.n) - eta).norm());
    }
  } catch (const Error& e) {
    result.failure = e.what();
    return result;
  }
  result.mean = total / kSteps;
  result.error = worst / largest;
  return result;
}

void print(const char* name, const RunResult& r) {
  if (!r.failure.empty()) {
    std::printf("[ tube    ] %-26s %s\n", name, r.failure.c_str());
  } else {
    std::printf("[ tube    ] %-26s mean %5.2f  max %3d  |eta - monolithic| / |eta| = %.1e\n", name,
                r.mean, r.max, r.error);
  }
}

class AddedMassTube : public ::testing::TestWithParam<double> {};

TEST_P(AddedMassTube, AitkenAndIqnConvergeWherePlainIterationDiverges) {
  test::TubeParameters params;
  params.mass = GetParam();
  const test::AddedMassTube tube(params);
  const double radius = tube.plain_iteration_radius(kDt);
  std::printf("[ tube    ] rho_f L / m = %.0f, n = %d, dt = %.3g: plain iteration radius %.2f\n",
              params.rho_f * params.length / params.mass, params.n, kDt, radius);
  EXPECT_GT(radius, 1.0);
  // The added-mass instability does not go away with a smaller step.
  EXPECT_GT(tube.plain_iteration_radius(kDt / 10.0), radius);

  const InterfaceLayout layout = tube.layout();
  const RunResult plain = run(params, std::make_unique<ConstantRelaxation>(1.0));
  print("constant omega = 1", plain);
  EXPECT_NE(plain.failure.find("coupling diverged at step 1"), std::string::npos);

  const RunResult seed = run(params, std::make_unique<AitkenRelaxation>(layout));
  print("Aitken (seed paper rule)", seed);
  AitkenOptions literal;
  literal.rule = AitkenRule::SeedPaperLiteral;
  print("Aitken (seed, literal)", run(params, std::make_unique<AitkenRelaxation>(layout, literal)));
  AitkenOptions it;
  it.rule = AitkenRule::IronsTuck;
  const RunResult irons = run(params, std::make_unique<AitkenRelaxation>(layout, it));
  print("Aitken (Irons-Tuck)", irons);
  RunResult iqn_default;
  for (int q : {0, 1, 2, 4, 8, 16}) {
    IqnIlsOptions options;
    options.reused_time_steps = q;
    const RunResult r = run(params, std::make_unique<IqnIls>(layout, options));
    char name[64];
    std::snprintf(name, sizeof name, "IQN-ILS q = %d", q);
    print(name, r);
    EXPECT_TRUE(r.failure.empty()) << r.failure;
    EXPECT_LT(r.error, 1e-4);
    if (q == IqnIlsOptions{}.reused_time_steps) iqn_default = r;
  }
  for (double eps : {0.0, 1e-1}) {  // the QR1 filter threshold (default 1e-2 above)
    IqnIlsOptions options;
    options.filter_epsilon = eps;
    char name[64];
    std::snprintf(name, sizeof name, "IQN-ILS q = 8, eps = %g", eps);
    print(name, run(params, std::make_unique<IqnIls>(layout, options)));
  }
  {
    IqnIlsOptions options;
    options.block_scaling = false;
    print("IQN-ILS q = 8, no scaling", run(params, std::make_unique<IqnIls>(layout, options)));
  }
  ASSERT_TRUE(seed.failure.empty()) << seed.failure;
  ASSERT_TRUE(irons.failure.empty()) << irons.failure;
  EXPECT_LT(seed.error, 1e-4);
  EXPECT_LT(irons.error, 1e-4);
  EXPECT_LT(iqn_default.mean, std::min(seed.mean, irons.mean));
}

// rho_f L / m = 10 and 100 (wall mass 0.1 and 0.01).
INSTANTIATE_TEST_SUITE_P(MassRatios, AddedMassTube, ::testing::Values(0.1, 0.01));

}  // namespace
}  // namespace finverse::fsi
