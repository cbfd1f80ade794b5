// Arc-length method (arc_length.hpp) on the shallow two-bar (von Mises) truss under an apex load,
// against its exact axial-member equilibrium path; load control fails at the same load.
//
// Truss: supports at (-a, 0) and (a, 0), apex at (0, h), bars of length L0 = sqrt(a^2 + h^2).
// With the apex at height y (displacement w = h - y down), each bar has length L = sqrt(a^2 + y^2)
// and the corotational beam's axial force N = EA (L - L0) / L0 (linear local element). Vertical
// balance of the apex under the downward load P (two bars, each projecting N by y / L):
//   P(y) = 2 EA (L0 - L) / L0 * y / L = 2 EA y (1/L - 1/L0).
// dP/dy = 2 EA (a^2 / L^3 - 1/L0) = 0 gives the limit points
//   y* = +-sqrt((a^2 L0)^(2/3) - a^2),  P_lim = P(y*)  (and -P_lim at -y*);
// under P > P_lim the truss snaps through to y < -h (bars in tension).
// Bending: the bars are beams with pinned supports, rigidly joined at the apex. With an in-plane
// thickness t = 0.2 mm over a = 1 m their bending stiffness adds at most ~6 EI w / a^3 ~ 1e-5 P_lim
// to P, far below the tolerances below.
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "fem/arc_length.hpp"
#include "fem/errors.hpp"
#include "fem/static_solver.hpp"

using namespace finverse::fem;

namespace {

struct Truss {
  double a = 1.0, h = 0.1, E = 1e9, b = 0.05, t = 2e-4;
  double EA() const { return E * b * t; }
  double L0() const { return std::hypot(a, h); }
  // Downward apex load in equilibrium with apex height y.
  double load(double y) const { return 2 * EA() * y * (1 / std::hypot(a, y) - 1 / L0()); }
  double limit_height() const { return std::sqrt(std::cbrt(a * a * L0() * a * a * L0()) - a * a); }
  double limit_load() const { return load(limit_height()); }

  static constexpr int apex = 1;
  static constexpr int apex_uy = 6 * apex + 1;

  // Apex load -reference_load along y (down).
  Model model(double reference_load) const {
    Model m;
    const int mat = m.add_material({"bar", E, 0.3, 1000});
    m.add_node(Vec3(-a, 0, 0));
    m.add_node(Vec3(0, h, 0));
    m.add_node(Vec3(a, 0, 0));
    const auto section = TaperedRectangle::uniform(b, t);  // width out of plane, t in plane
    m.add_beam(0, 1, mat, section, Vec3(0, 0, 1));
    m.add_beam(1, 2, mat, section, Vec3(0, 0, 1));
    for (int n : {0, 2})
      for (int d = 0; d < 5; ++d) m.fix(n, d);  // pinned: rz free
    for (int d : {2, 3, 4}) m.fix(apex, d);      // in plane
    m.add_nodal_load(apex, 1, -reference_load);
    return m;
  }
};

// Apex height y < -h where the truss, snapped through, carries the downward load P (> 0).
double snapped_height(const Truss& tr, double P) {
  double lo = -10 * tr.h, hi = -tr.h;  // load(-h) = 0, load(-10h) >> P_lim
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (tr.load(mid) > P ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

template <class E, class F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "<no exception>";
}

}  // namespace

TEST(ArcLength, TracesVonMisesTrussThroughBothLimitPoints) {
  const Truss tr;
  const double P_lim = tr.limit_load(), P_ref = 1.5 * P_lim;
  const Model m = tr.model(P_ref);
  ArcLengthOptions o;
  // Arc lengths in the scaled norm (translations / 2a, rotations in rad); the path up to the stop
  // is ~0.7 long, so ~100 steps: fine enough to locate the limit points by a parabola.
  o.initial_arc_length = 0.004;
  o.max_arc_length = 0.008;
  o.stop_load_factor = 1.0;
  o.tracked_dofs = {6 * Truss::apex + 0, Truss::apex_uy};
  ArcLengthSolver solver(m, o);
  NodalState s = m.reference_state();
  const ArcLengthResult r = solver.solve(s, 0.0);

  ASSERT_EQ(r.stop, ArcLengthStop::load_factor);
  EXPECT_TRUE(r.stop_corrected);
  ASSERT_GE(r.path.size(), 10u);
  EXPECT_LT(r.path.size(), 150u);
  EXPECT_EQ(r.path.back().load_factor, 1.0);
  // Symbolic analyses: one for CHOLMOD and one for the LDL^T it falls back to on the indefinite
  // tangents past the first limit point; every other factorisation along the path is numeric.
  EXPECT_EQ(solver.linear_solver().symbolic_count(), 2);
  EXPECT_GT(solver.linear_solver().numeric_count(), 100);

  // Every converged point lies on the exact path; the apex stays on the symmetry axis.
  double max_error = 0;
  for (const auto& p : r.path) {
    const double y = tr.h + p.values[1];
    max_error = std::max(max_error, std::abs(p.load_factor * P_ref - tr.load(y)));
    EXPECT_NEAR(p.values[0], 0.0, 1e-9 * tr.h);
  }
  EXPECT_LT(max_error, 2e-4 * P_lim);

  // Limit points: the first local maximum of the load factor along the path and the local
  // minimum after it, refined by the parabola through the neighbouring points, against +-P_lim.
  const int n = static_cast<int>(r.path.size());
  auto extremum = [&](int sign, int from) {
    int k = from + 1;
    while (k + 1 < n && !(sign * r.path[k].load_factor > sign * r.path[k + 1].load_factor)) ++k;
    if (k + 1 >= n) {
      ADD_FAILURE() << "no limit point on the path after point " << from;
      return std::tuple{0.0, 0.0, k};
    }
    const double x0 = r.path[k - 1].values[1], x1 = r.path[k].values[1],
                 x2 = r.path[k + 1].values[1];
    const double l0 = r.path[k - 1].load_factor, l1 = r.path[k].load_factor,
                 l2 = r.path[k + 1].load_factor;
    // Vertex of the interpolating parabola l(x).
    const double d01 = (l1 - l0) / (x1 - x0), d12 = (l2 - l1) / (x2 - x1);
    const double c2 = (d12 - d01) / (x2 - x0), c1 = d01 - c2 * (x0 + x1);
    const double xv = -c1 / (2 * c2);
    const double lv = l0 + d01 * (xv - x0) + c2 * (xv - x0) * (xv - x1);
    return std::tuple{lv * P_ref, tr.h + xv, k};
  };
  const auto [p_max, y_max, k_max] = extremum(+1, 0);
  const auto [p_min, y_min, k_min] = extremum(-1, k_max);
  EXPECT_NEAR(p_max, P_lim, 2e-4 * P_lim);
  EXPECT_NEAR(p_min, -P_lim, 2e-4 * P_lim);
  EXPECT_NEAR(y_max, tr.limit_height(), 0.03 * tr.limit_height());
  EXPECT_NEAR(y_min, -tr.limit_height(), 0.03 * tr.limit_height());

  // Snapped through: at P = 1.5 P_lim the apex is below -h, at the exact root of P(y) = P_ref.
  const double y_end = tr.h + r.path.back().values[1];
  EXPECT_NEAR(y_end, snapped_height(tr, P_ref), 1e-5 * tr.h);  // bending: ~1.3e-6 h
  EXPECT_LT(y_end, -tr.h);
  RecordProperty("limit_load_found", std::to_string(p_max));
  RecordProperty("limit_load_exact", std::to_string(P_lim));
  std::printf("max |lambda P_ref - P(y)| / P_lim on the path %.2e\n", max_error / P_lim);
  std::printf("limit load: found %.8g (parabola) exact %.8g, rel err %.2e; min %.8g; "
              "y at stop %.10g exact %.10g; %zu points, %d iterations, %d cutbacks\n",
              p_max, P_lim, p_max / P_lim - 1, p_min, y_end, snapped_height(tr, P_ref),
              r.path.size(), r.total_iterations, r.cutbacks);
}

TEST(ArcLength, LoadControlFailsBeyondTheLimitLoadWhereArcLengthPasses) {
  const Truss tr;
  const double P_lim = tr.limit_load(), y_lim = tr.limit_height();
  const Model m = tr.model(1.2 * P_lim);  // lambda = 1: 20 % beyond the limit load

  // Load control up to 0.8 P_lim (lambda = 2/3) follows the path ...
  {
    StaticSolver statics(m, StaticOptions{.steps = 4});
    NodalState s = m.reference_state();
    statics.solve(s, 0, 0.8 / 1.2);
    EXPECT_NEAR(tr.load(s.position[1].y()), 0.8 * P_lim, 1e-5 * P_lim);
  }
  // ... but beyond P_lim no equilibrium near the last one exists: with 10 iterations per step it
  // stops with a one-line NotConverged at the limit load (the state is the last converged one) ...
  {
    StaticSolver statics(m, StaticOptions{.steps = 10, .max_iterations = 10});
    NodalState s = m.reference_state();
    const std::string msg = message_of<NotConverged>([&] { statics.solve(s, 0, 1); });
    EXPECT_NE(msg.find("did not converge"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_NEAR(s.position[1].y(), y_lim, 0.01 * y_lim);
  }
  // ... and with 25 it may converge, but only by jumping over the unstable branch
  // (-y* < y < y*): no load-controlled point lies on it, since there dP/dy > 0 (the load falls as
  // the apex goes down).
  std::vector<double> load_controlled;
  {
    StaticSolver statics(m, StaticOptions{.steps = 1});
    NodalState s = m.reference_state();
    try {
      for (int i = 0; i < 10; ++i) {
        statics.solve(s, 0.1 * i, 0.1 * (i + 1));
        load_controlled.push_back(s.position[1].y());
      }
    } catch (const NotConverged&) {
    }
  }
  EXPECT_GE(load_controlled.size(), 7u);  // up to 0.84 P_lim at least
  std::printf("load control: %zu of 10 increments converged, apex y:", load_controlled.size());
  for (double y : load_controlled) std::printf(" %.4f", y);
  std::printf(" (y* = %.4f)\n", y_lim);
  for (double y : load_controlled) EXPECT_FALSE(std::abs(y) < 0.99 * y_lim) << y;

  // Arc-length traces the unstable branch and reaches lambda = 1 on the snapped-through branch.
  ArcLengthOptions o;
  o.stop_load_factor = 1.0;
  o.tracked_dofs = {Truss::apex_uy};
  ArcLengthSolver solver(m, o);
  NodalState s = m.reference_state();
  const ArcLengthResult r = solver.solve(s, 0.0);
  ASSERT_EQ(r.stop, ArcLengthStop::load_factor);
  EXPECT_EQ(r.path.back().load_factor, 1.0);
  EXPECT_NEAR(s.position[1].y(), snapped_height(tr, 1.2 * P_lim), 1e-5 * tr.h);
  int unstable = 0;
  for (const auto& p : r.path) unstable += std::abs(tr.h + p.values[0]) < 0.99 * y_lim;
  EXPECT_GE(unstable, 3);
}

TEST(ArcLength, UnsymmetricTangentTracesTheSamePath) {
  // Full consistent tangent with UMFPACK LU (indefinite past the limit point): same end point.
  const Truss tr;
  const double P_lim = tr.limit_load();
  const Model m = tr.model(1.2 * P_lim);
  ArcLengthSolver solver(m, {.stop_load_factor = 1.0, .unsymmetric_tangent = true});
  NodalState s = m.reference_state();
  const ArcLengthResult r = solver.solve(s, 0.0);
  ASSERT_EQ(r.stop, ArcLengthStop::load_factor);
  EXPECT_EQ(solver.linear_solver().backend(), SolverBackend::umfpack);
  EXPECT_NEAR(s.position[1].y(), snapped_height(tr, 1.2 * P_lim), 1e-5 * tr.h);
}

TEST(ArcLength, StopsAtAPrescribedDisplacement) {
  const Truss tr;
  const double P_lim = tr.limit_load();
  const Model m = tr.model(P_lim);
  ArcLengthOptions o;
  o.stop_dof = Truss::apex_uy;
  o.stop_displacement = -1.5 * tr.h;  // y = -h/2: between the limit points, P < 0 (pull up)
  o.tracked_dofs = {Truss::apex_uy};
  ArcLengthSolver solver(m, o);
  NodalState s = m.reference_state();
  const ArcLengthResult r = solver.solve(s, 0.0);
  ASSERT_EQ(r.stop, ArcLengthStop::displacement);
  EXPECT_TRUE(r.stop_corrected);
  EXPECT_NEAR(r.path.back().values[0], -1.5 * tr.h, 1e-12);
  EXPECT_NEAR(r.path.back().load_factor * P_lim, tr.load(-0.5 * tr.h), 2e-4 * P_lim);
  EXPECT_LT(r.path.back().load_factor, 0);
}

TEST(ArcLength, MaxStepsEndsThePathWithoutError) {
  const Truss tr;
  const Model m = tr.model(tr.limit_load());
  ArcLengthOptions o;
  o.max_steps = 3;
  ArcLengthSolver solver(m, o);
  NodalState s = m.reference_state();
  const ArcLengthResult r = solver.solve(s, 0.0);
  EXPECT_EQ(r.stop, ArcLengthStop::max_steps);
  EXPECT_EQ(r.path.size(), 4u);
  for (int i = 1; i < 4; ++i) EXPECT_GT(r.path[i].load_factor, r.path[i - 1].load_factor);
}

TEST(ArcLength, OneLineErrors) {
  const Truss tr;
  const Model m = tr.model(tr.limit_load());
  auto bad = [&](ArcLengthOptions o) {
    return message_of<InvalidInput>([&] { ArcLengthSolver solver(m, o); });
  };
  EXPECT_NE(bad({.initial_load_increment = 0}).find("initial_load_increment"), std::string::npos);
  EXPECT_NE(bad({.target_iterations = 0}).find("target_iterations"), std::string::npos);
  EXPECT_NE(bad({.stop_dof = 6 * Truss::apex + 3}).find("stop_dof"), std::string::npos);
  EXPECT_NE(bad({.stop_dof = 0}).find("prescribed"), std::string::npos);
  EXPECT_NE(bad({.tracked_dofs = {99}}).find("tracked DOF 99"), std::string::npos);
  // No reference load.
  const Model unloaded = tr.model(0);
  EXPECT_NE(message_of<InvalidInput>([&] { ArcLengthSolver solver(unloaded); })
                .find("reference load"),
            std::string::npos);

  // One iteration per step cannot converge a step this large (it would once cut small enough to
  // be linear to the tolerance): cut down to the minimum, then a one-line NotConverged.
  ArcLengthSolver solver(
      m, {.initial_arc_length = 0.05, .min_arc_length = 0.02, .max_iterations = 1});
  NodalState s = m.reference_state();
  const std::string msg = message_of<NotConverged>([&] { solver.solve(s, 0.0); });
  EXPECT_NE(msg.find("arc-length did not converge"), std::string::npos) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
}
