// The flow's response to a deforming body's position with the cells' kinds frozen
// (FlowSolver::set_body_state's kinds_at; GhostCellSet(grid, body, kinds_from)), what makes the
// FSI coupling operator H(x) continuous (issue 32; docs/studies/fsi_turek_hron.md section 7):
//   - a bending frozen_flap is stepped from one saved state to positions shifted by s; by bisection on s
//     a shift s* where a cell centre crosses the wall (the kinds of the plain placement change)
//     is found, and the step is taken at s* - eps and s* + eps (eps = 1e-7 h): with the kinds
//     classified at each position the force and the velocity jump by O(1) there, with the kinds
//     frozen (at the unshifted position) by O(eps);
//   - with kinds_at equal to the body itself the step is bitwise the plain one, and restore()
//     brings back the frozen kinds (a restored step repeats bitwise).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <vector>

#include "bending_flap.hpp"
#include "cfd/flow/flow_solver.hpp"

namespace finverse::cfd {
namespace {

constexpr int kCells = test::kBendingFlapCells;
constexpr double kH = 1.0 / kCells;
PolygonState frozen_flap(double t, double dy) { return test::bending_flap(t, dy); }
const auto frozen_flap_solver = test::bending_flap_solver;

struct Response {
  std::vector<CellKind> kinds;
  double lift = 0;
  std::vector<double> u;  // u and v of every cell
};

// One step from `saved` to the frozen_flap shifted by dy, the kinds from the frozen_flap shifted by kinds_dy
// (none: the plain placement).
Response step_to(FlowSolver& s, const std::vector<StateArray>& saved, double dy, const double* kinds_dy) {
  s.restore(saved);
  const double t = s.time() + s.next_dt();
  const PolygonState k = kinds_dy ? frozen_flap(t, *kinds_dy) : PolygonState{};
  s.set_body_state(frozen_flap(t, dy), kinds_dy ? &k : nullptr);
  s.step();
  Response r;
  r.lift = s.edge_traction(1.0).force[1];
  for (int j = 0; j < kCells; ++j)
    for (int i = 0; i < kCells; ++i) {
      r.kinds.push_back(s.immersed()->kind(i, j));
      r.u.push_back(s.u(0)(i, j, 0));
      r.u.push_back(s.u(1)(i, j, 0));
    }
  return r;
}

double max_diff(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0;
  for (std::size_t n = 0; n < a.size(); ++n) m = std::max(m, std::abs(a[n] - b[n]));
  return m;
}

TEST(FrozenCellKinds, ResponseIsContinuousWhereACellCentreCrossesTheWall) {
  FlowSolver s = frozen_flap_solver();
  for (int n = 0; n < 5; ++n) {  // a moving flow and the AB2 history
    s.set_body_state(frozen_flap(s.time() + s.next_dt(), 0));
    s.step();
  }
  const std::vector<StateArray> saved = s.state();
  // Bisection on the shift for a change of the plain placement's kinds (the frozen_flap moves up by
  // 0.6 h, so some centre crosses its lower or upper side).
  double lo = 0, hi = 0.6 * kH;
  const std::vector<CellKind> k0 = step_to(s, saved, lo, nullptr).kinds;
  ASSERT_NE(k0, step_to(s, saved, hi, nullptr).kinds) << "no cell centre crossed: the test needs one";
  while (hi - lo > 1e-7 * kH) {
    const double mid = 0.5 * (lo + hi);
    (step_to(s, saved, mid, nullptr).kinds == k0 ? lo : hi) = mid;
  }
  const double eps = hi - lo, zero = 0;
  const Response a = step_to(s, saved, lo, nullptr), b = step_to(s, saved, hi, nullptr);
  const Response fa = step_to(s, saved, lo, &zero), fb = step_to(s, saved, hi, &zero);
  ASSERT_NE(a.kinds, b.kinds);
  EXPECT_EQ(fa.kinds, fb.kinds);
  const double lift_scale = std::abs(fa.lift) + 1e-3, u_scale = 0.4;  // the frozen_flap tip's speed ~0.38
  const double plain_lift = std::abs(b.lift - a.lift), frozen_lift = std::abs(fb.lift - fa.lift);
  const double plain_u = max_diff(a.u, b.u), frozen_u = max_diff(fa.u, fb.u);
  std::printf("crossing at dy = %.9g h (eps %.2g h): plain |dlift| %.3g |du| %.3g; frozen |dlift| %.3g |du| %.3g\n",
              lo / kH, eps / kH, plain_lift, plain_u, frozen_lift, frozen_u);
  // Plain: a jump of the flow near the crossing cell; frozen: of the order of eps / h.
  EXPECT_GT(plain_u, 1e-3 * u_scale) << "the plain placement's jump";
  EXPECT_LT(frozen_u, 1e3 * (eps / kH) * u_scale);
  EXPECT_LT(frozen_lift, 1e3 * (eps / kH) * lift_scale);
  EXPECT_LT(frozen_lift, 1e-2 * plain_lift) << "plain " << plain_lift << ", frozen " << frozen_lift;
}

bool same_frozen_state(const std::vector<StateArray>& sa, const std::vector<StateArray>& sb) {
  if (sa.size() != sb.size()) return false;
  for (std::size_t m = 0; m < sa.size(); ++m)
    if (sa[m].name != sb[m].name || sa[m].values.size() != sb[m].values.size() ||
        (!sa[m].values.empty() &&
         std::memcmp(sa[m].values.data(), sb[m].values.data(), sa[m].values.size() * sizeof(double)) != 0))
      return false;
  return true;
}

TEST(FrozenCellKinds, OwnKindsAreThePlainStepAndRestoreKeepsTheFrozenKinds) {
  FlowSolver plain = frozen_flap_solver(), own = frozen_flap_solver();
  for (int n = 0; n < 4; ++n) {
    const double t = plain.time() + plain.next_dt();
    const PolygonState st = frozen_flap(t, 0);
    plain.set_body_state(st);
    plain.step();
    own.set_body_state(st, &st);
    own.step();
  }
  std::vector<StateArray> a = plain.state(), b = own.state();
  // The same flow; only the kinds' flag differs (0: the body's own, 1: given).
  ASSERT_EQ(a.back().name, "body_kinds");
  EXPECT_EQ(a.back().values[0], 0.0);
  EXPECT_EQ(b.back().values[0], 1.0);
  a.pop_back();
  b.pop_back();
  EXPECT_TRUE(same_frozen_state(a, b));

  // Frozen kinds at a shifted position survive restore(): the next step repeats bitwise.
  const double t = own.time() + own.next_dt();
  const PolygonState k = frozen_flap(t, 0.3 * kH);
  own.set_body_state(frozen_flap(t, 0), &k);
  own.step();
  const std::vector<StateArray> saved = own.state();
  const auto next = [&] {
    own.set_body_state(frozen_flap(own.time() + own.next_dt(), 0));
    own.step();
    return own.state();
  };
  const std::vector<StateArray> first = next();
  own.restore(saved);
  EXPECT_TRUE(same_frozen_state(first, next()));
}

}  // namespace
}  // namespace finverse::cfd
