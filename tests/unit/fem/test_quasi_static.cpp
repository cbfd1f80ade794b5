// The quasi-static increment of eq. (2): marching in small increments reproduces the full static
// solution, a base out of equilibrium is taken as balanced, and the factorisation is reused
// across calls and modulus changes.
#include <cmath>

#include <gtest/gtest.h>

#include "fem/quasi_static_increment.hpp"
#include "fem_test_models.hpp"

using namespace finverse::fem;
using finverse::fem::test::cantilever;

namespace {
constexpr double L = 0.5, E = 2e9, b = 0.01, t = 0.002;
constexpr int n = 8;
const double EI = E * b * t * t * t / 12;

Eigen::VectorXd tip_load(const Model& m, double fz, double fy = 0) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(kDofsPerNode * m.node_count());
  f(kDofsPerNode * n + 2) = fz;
  f(kDofsPerNode * n + 1) = fy;
  return f;
}
}  // namespace

TEST(QuasiStatic, MarchingSmallIncrementsReproducesTheFullStaticSolution) {
  const double P = 3.0 * EI / (L * L);
  Model m = cantilever(n, L, E, b, t, b, t);
  // Load turning in the y-z plane while growing: path independent for an elastic structure.
  m.set_load_history(LoadHistory({0.0, 1.0}, {tip_load(m, 0), tip_load(m, P, 0.3 * P)}));
  std::vector<double> times;
  for (int k = 0; k <= 20; ++k) times.push_back(k / 20.0);
  QuasiStaticIncrement inc(m);
  int frames = 0;
  const auto states = march_quasi_static(inc, m.reference_state(), times, [&](int, const NodalState&) { ++frames; });
  EXPECT_EQ(frames, 20);

  StaticSolver full(m, StaticOptions{.steps = 10});
  NodalState x = m.reference_state();
  full.solve(x, 0.0, 1.0);
  EXPECT_LT((states.back().position[n] - x.position[n]).norm(), 1e-8 * L);
  EXPECT_LT((states.back().rotation[n] - x.rotation[n]).norm(), 1e-8);
  EXPECT_GT(std::abs(x.position[n].z()), 0.4 * L);
  // One symbolic analysis for the whole march.
  EXPECT_EQ(inc.solver().linear_solver().symbolic_count(), 1);
}

TEST(QuasiStatic, BaseOutOfEquilibriumIsTakenAsBalanced) {
  // Base: the unloaded reference, although f_ext(t) = P0 there. The increment responds to the
  // load increment only, i.e. equals a fresh solve under dP.
  const double P0 = 1e-3 * EI / (L * L), dP = 1e-6 * EI / (L * L);
  Model m = cantilever(n, L, E, b, t, b, t);
  m.set_load_history(LoadHistory({0.0, 1.0}, {tip_load(m, P0), tip_load(m, P0 + dP)}));
  QuasiStaticIncrement inc(m);
  QuasiStaticInfo info;
  const auto dx = inc.displacement_increment(m.reference_state(), 0.0, 1.0, &info);
  EXPECT_NEAR(info.base_imbalance, P0 / dP, 1e-6 * P0 / dP);
  const double w = dP * L * L * L / (3 * EI);
  EXPECT_NEAR(dx[n].z(), w, 1e-5 * w);
}

TEST(QuasiStatic, ModulusChangesBetweenCallsReuseTheFactorisation) {
  const double dP = 1e-6 * EI / (L * L);
  Model m = cantilever(n, L, E, b, t, b, t);
  m.set_load_history(LoadHistory({0.0, 1.0}, {tip_load(m, 0), tip_load(m, dP)}));
  QuasiStaticIncrement inc(m);
  const NodalState base = m.reference_state();
  const double w1 = inc.displacement_increment(base, 0.0, 1.0)[n].z();
  m.set_region_youngs_modulus(0, 4 * E);  // what a fitter does between individuals
  const double w4 = inc.displacement_increment(base, 0.0, 1.0)[n].z();
  EXPECT_NEAR(w4, w1 / 4, 1e-6 * w1);
  EXPECT_EQ(inc.solver().linear_solver().symbolic_count(), 1);
}
