// Tests of the deforming 2-D body whose surface the caller sets (FlowSolver::immerse_deforming,
// set_body_state, edge_traction; deforming_polygon.hpp), the FSI interface of issue 32:
//   - a rigid motion given as vertex states gives the forces of the same MovingBody;
//   - the edge traction equals the rigid SurfaceTraction on the same field (also rotating), its
//     samples sum to its totals and lie where they say (caller's edge, xi);
//   - restore() + the same state steps bitwise as before, another state does not;
//   - a flap bending with a smooth mode (area constant) and its mirror image (given clockwise)
//     give mirrored flows and forces, with the continuity residual at the solver's tolerance;
//   - a breathing polygon's net wall flux is the polygon's d(area)/dt (removed in the balance);
//   - bad states throw one-line errors naming the time;
//   - the cost of a step of the Turek-Hron body, deforming vs rigid (printed).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <string>

#include "bending_flap.hpp"
#include "cfd/flow/flow_solver.hpp"
#include "cfd/forces/surface_traction.hpp"
#include "cfd/immersed/deforming_polygon.hpp"
#include "cfd/immersed/surface_shapes.hpp"
#include "cfd/validation/cylinder_channel.hpp"
#include "cfd/validation/turek_hron_cfd.hpp"
#include "core/error.hpp"

namespace finverse::cfd {
namespace {

Polygon ellipse(double cx, double cy, double a, double b, int n) {
  std::vector<std::array<double, 2>> v;
  for (int k = 0; k < n; ++k) {
    const double t = 2 * std::numbers::pi * (k + 0.5) / n;
    v.push_back({cx + a * std::cos(t), cy + b * std::sin(t)});
  }
  return Polygon(v);
}

// An ellipse towed in +x while heaving (and pitching when `pitch`): cells cleared on every side.
MovingBody towed_ellipse(bool pitch) {
  return MovingBody{ellipse(0.4, 0.25, 0.08, 0.05, 48), {0.4, 0.25}, [pitch](double t) {
                      const double w = 2 * std::numbers::pi;
                      RigidState s;
                      s.displacement = {0.3 * t, 0.02 * std::sin(w * t)};
                      s.velocity = {0.3, 0.02 * w * std::cos(w * t)};
                      s.acceleration = {0, -0.02 * w * w * std::sin(w * t)};
                      if (pitch) {
                        s.angle = 0.2 * std::sin(w * t);
                        s.angular_velocity = 0.2 * w * std::cos(w * t);
                        s.angular_acceleration = -0.2 * w * w * std::sin(w * t);
                      }
                      return s;
                    }};
}

FlowSolver box_solver(double cfl_dt_max) {
  const StretchedGrid g(Axis::uniform(0, 1, 40), Axis::stretched_count(0, 0.5, 0.1, 0.4, 24, 1.15));
  FlowOptions opt;
  opt.nu = 2e-3;
  opt.cfl = 0.4;
  opt.dt_max = cfl_dt_max;  // variable steps: the caller asks next_dt() for t^{n+1}
  FlowSolver s;
  s.setup(g, FlowBoundary{}, opt);
  return s;
}

double rel(double a, double b, double scale) { return std::abs(a - b) / scale; }

TEST(DeformingBody, RigidMotionAsVertexStatesGivesTheMovingBodysForces) {
  const MovingBody body = towed_ellipse(false);
  FlowSolver rigid = box_solver(0.02), deform = box_solver(0.02);
  rigid.immerse(body);
  rigid.initialise({});
  deform.immerse_deforming(rigid_polygon_state(body, body.motion(0)));
  deform.initialise({});
  double worst = 0, scale = 0, worst_traction = 0, div_rigid = 0, div_deform = 0;
  std::size_t cleared = 0;
  for (int n = 0; n < 50; ++n) {
    const double t = deform.time() + deform.next_dt();
    deform.set_body_state(rigid_polygon_state(body, body.motion(t)));
    const StepStats a = rigid.step(), b = deform.step();
    ASSERT_EQ(a.time, b.time);
    div_rigid = std::max(div_rigid, a.max_divergence);
    div_deform = std::max(div_deform, b.max_divergence);
    cleared += deform.freshly_cleared().size();
    const SurfaceLoads L = SurfaceTraction(rigid.grid(), *rigid.immersed(), rigid.body_polygon())
                               .evaluate(rigid.u(0), rigid.u(1), rigid.p(), rigid.options().nu, 1.0,
                                         [&](double x, double y) { return body.velocity(rigid.body_state(), x, y); });
    const EdgeTraction E = deform.edge_traction(1.0);
    // The same traction from the rigid evaluation on the deforming run's own field.
    const SurfaceLoads R = SurfaceTraction(deform.grid(), *deform.immersed(), deform.body_polygon())
                               .evaluate(deform.u(0), deform.u(1), deform.p(), deform.options().nu, 1.0,
                                         [&](double x, double y) { return body.velocity(body.motion(b.time), x, y); });
    for (int c = 0; c < 2; ++c) {
      const auto C = static_cast<std::size_t>(c);
      scale = std::max(scale, std::abs(L.force[C]));
      worst = std::max(worst, std::abs(L.force[C] - E.force[C]));
      worst_traction = std::max(worst_traction, std::abs(R.force[C] - E.force[C]));
    }
  }
  EXPECT_GT(cleared, 20u);
  ASSERT_GT(scale, 1e-4);
  std::printf("rigid vs vertex-state path over 50 steps: max |dF| / max |F| = %.3g (traction alone %.3g), "
              "%zu cells cleared, max continuity residual %.3g (rigid) %.3g (vertex states) 1/s\n", worst / scale,
              worst_traction / scale, cleared, div_rigid, div_deform);
  EXPECT_LT(worst / scale, 1e-10);
  EXPECT_LT(worst_traction / scale, 1e-12);
}

TEST(DeformingBody, EdgeTractionOfARotatingBodyIsTheRigidTractionAndSumsToItsTotals) {
  const MovingBody body = towed_ellipse(true);
  FlowSolver s = box_solver(0.02);
  s.immerse_deforming(rigid_polygon_state(body, body.motion(0)));
  s.initialise({});
  FlowSolver r = box_solver(0.02);
  r.immerse(body);
  r.initialise({});
  // Continuity: the cut-cell residual stays at the level of the pressure solve's tolerance (both
  // paths show O(1e-6) 1/s on steps that clear cells, O(1e-14) otherwise; the flow's |u| / h ~ 10).
  double div = 0, div_rigid = 0;
  for (int n = 0; n < 12; ++n) {
    s.set_body_state(rigid_polygon_state(body, body.motion(s.time() + s.next_dt())));
    const StepStats st = s.step();
    EXPECT_LE(st.poisson_residual, s.options().poisson.rtol);
    div = std::max(div, st.max_divergence);
    div_rigid = std::max(div_rigid, r.step().max_divergence);
  }
  std::printf("pitching ellipse: max continuity residual %.3g 1/s (vertex states), %.3g 1/s (MovingBody)\n", div,
              div_rigid);
  EXPECT_LT(div, 1e-4);
  const RigidState rs = body.motion(s.time());
  const SurfaceLoads R = SurfaceTraction(s.grid(), *s.immersed(), s.body_polygon())
                             .evaluate(s.u(0), s.u(1), s.p(), s.options().nu, 1.0,
                                       [&](double x, double y) { return body.velocity(rs, x, y); });
  const EdgeTraction E = s.edge_traction(1.0);
  const double scale = std::hypot(R.force[0], R.force[1]);
  ASSERT_GT(scale, 1e-4);
  std::array<double, 2> sum{};
  const auto& v = s.deforming_body()->state().position;
  for (const EdgeTractionSample& q : E.samples) {
    sum[0] += q.force[0];
    sum[1] += q.force[1];
    ASSERT_GE(q.xi, 0.0);
    ASSERT_LE(q.xi, 1.0);
    const auto& a = v[static_cast<std::size_t>(q.edge)];
    const auto& b = v[(static_cast<std::size_t>(q.edge) + 1) % v.size()];
    EXPECT_NEAR(q.point[0], a[0] + q.xi * (b[0] - a[0]), 1e-13);
    EXPECT_NEAR(q.point[1], a[1] + q.xi * (b[1] - a[1]), 1e-13);
  }
  for (std::size_t c = 0; c < 2; ++c) {
    EXPECT_LT(rel(E.force[c], R.force[c], scale), 1e-12) << c;
    EXPECT_LT(rel(E.viscous_force[c], R.viscous_force[c], scale), 1e-12) << c;
    EXPECT_LT(rel(sum[c], E.force[c], scale), 1e-12) << c;
  }
}

// The flap of bending_flap.hpp at rest height y0, mirrored for sign = -1.
PolygonState flap(double t, double sign) { return test::bending_flap(t, 0.0, sign); }

FlowSolver flap_solver(double sign) {
  const StretchedGrid g(Axis::uniform(0, 1, 48), Axis::uniform(0, 1, 48));
  FlowOptions opt;
  opt.nu = 2e-3;
  opt.dt = 0.01;
  FlowSolver s;
  s.setup(g, FlowBoundary{}, opt);
  s.immerse_deforming(flap(0, sign));
  s.initialise({});
  return s;
}

TEST(DeformingBody, BendingFlapAndItsMirrorImageGiveMirroredFlows) {
  FlowSolver up = flap_solver(1), down = flap_solver(-1);
  ASSERT_FALSE(up.deforming_body()->reversed());
  ASSERT_TRUE(down.deforming_body()->reversed());
  double worst_div = 0, worst_flux = 0;
  std::size_t cleared = 0;
  for (int n = 0; n < 30; ++n) {
    const double t = up.time() + up.next_dt();
    up.set_body_state(flap(t, 1));
    down.set_body_state(flap(t, -1));
    const StepStats a = up.step(), b = down.step();
    EXPECT_LE(a.poisson_residual, up.options().poisson.rtol);
    worst_div = std::max({worst_div, a.max_divergence, b.max_divergence});
    worst_flux = std::max(worst_flux, std::abs(up.deforming_net_flux()));
    cleared += up.freshly_cleared().size();
  }
  EXPECT_GT(cleared, 10u);
  // The tip moves at up to a w = 0.38 m/s: the flow it drives is O(0.1) m/s.
  double umax = 0, diff = 0;
  const StretchedGrid& g = up.grid();
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) {
      const int m = g.ny() - 1 - j;
      ASSERT_EQ(up.fluid(i, j, 0), down.fluid(i, m, 0)) << i << " " << j;
      if (!up.fluid(i, j, 0)) continue;
      umax = std::max(umax, std::hypot(up.u(0)(i, j, 0), up.u(1)(i, j, 0)));
      diff = std::max({diff, std::abs(up.u(0)(i, j, 0) - down.u(0)(i, m, 0)),
                       std::abs(up.u(1)(i, j, 0) + down.u(1)(i, m, 0))});
    }
  const EdgeTraction Fu = up.edge_traction(1000.0), Fd = down.edge_traction(1000.0);
  const double scale = std::hypot(Fu.force[0], Fu.force[1]);
  std::printf("bending flap: max |u| = %.3g m/s, mirror mismatch %.3g m/s, force (%.5g, %.5g) vs mirrored "
              "(%.5g, %.5g) N/m, max continuity residual %.3g 1/s, max |net wall flux| %.3g m^2/s\n",
              umax, diff, Fu.force[0], Fu.force[1], Fd.force[0], -Fd.force[1], worst_div, worst_flux);
  EXPECT_GT(umax, 0.05);
  EXPECT_LT(diff / umax, 1e-7);
  ASSERT_GT(scale, 1e-3);
  EXPECT_LT(rel(Fu.force[0], Fd.force[0], scale), 1e-7);
  EXPECT_LT(rel(Fu.force[1], -Fd.force[1], scale), 1e-7);
  // The bending keeps the polygon's area: no net flux to remove; continuity holds to the pressure
  // solve's tolerance in every cell, cut cells included (|u| / h ~ 20 1/s).
  EXPECT_LT(worst_flux, 1e-14);
  EXPECT_LT(worst_div, 1e-4);
  // The caller's edges of the mirrored (clockwise) body: the samples of caller edge e lie on it.
  const auto& v = down.deforming_body()->state().position;
  for (const EdgeTractionSample& q : Fd.samples) {
    const auto& a = v[static_cast<std::size_t>(q.edge)];
    const auto& b = v[(static_cast<std::size_t>(q.edge) + 1) % v.size()];
    EXPECT_NEAR(q.point[0], a[0] + q.xi * (b[0] - a[0]), 1e-13);
    EXPECT_NEAR(q.point[1], a[1] + q.xi * (b[1] - a[1]), 1e-13);
  }
}

bool same_state(const std::vector<StateArray>& sa, const std::vector<StateArray>& sb) {
  if (sa.size() != sb.size()) return false;
  for (std::size_t m = 0; m < sa.size(); ++m)
    if (sa[m].name != sb[m].name || sa[m].values.size() != sb[m].values.size() ||
        (!sa[m].values.empty() &&
         std::memcmp(sa[m].values.data(), sb[m].values.data(), sa[m].values.size() * sizeof(double)) != 0))
      return false;
  return true;
}

TEST(DeformingBody, RestoreAndTheSameStateStepBitwiseAnotherStateDoesNot) {
  FlowSolver s = flap_solver(1);
  for (int n = 0; n < 6; ++n) {  // the AB2 history and a moved body
    s.set_body_state(flap(s.time() + s.next_dt(), 1));
    s.step();
  }
  const std::vector<StateArray> saved = s.state();
  const double t = s.time() + s.next_dt();
  const PolygonState A = flap(t, 1);
  PolygonState B = A;  // a coupling iterate that differs a little
  for (auto& p : B.position) p[1] += 0.002;
  for (auto& v : B.velocity) v[1] += 0.05;
  // One coupling iteration: restore (except the first pass), set the iterate, step.
  const auto pass = [&](const PolygonState& next, bool restore, std::array<double, 2>& force) {
    if (restore) s.restore(saved);
    s.set_body_state(next);
    s.step();
    force = s.edge_traction(1.0).force;
    return s.state();
  };
  std::array<double, 2> f1{}, f2{}, f3{}, f4{};
  const auto first = pass(A, false, f1);
  const auto again = pass(A, true, f2);
  EXPECT_TRUE(same_state(first, again));
  EXPECT_EQ(f1[0], f2[0]);
  EXPECT_EQ(f1[1], f2[1]);
  const auto other = pass(B, true, f3);
  EXPECT_FALSE(same_state(first, other));
  EXPECT_NE(f1[1], f3[1]);
  // And A once more: the B pass left nothing behind.
  const auto third = pass(A, true, f4);
  EXPECT_TRUE(same_state(first, third));
  EXPECT_EQ(f1[1], f4[1]);
}

TEST(DeformingBody, BreathingPolygonsNetFluxIsItsAreaRate) {
  // A regular n-gon of radius r(t) = r0 (1 + e sin(w t)): area (n/2) r^2 sin(2 pi / n), so its
  // rate is n r r' sin(2 pi / n); the vertices move radially at r'.
  const int n = 64;
  const double r0 = 0.15, e = 0.1, w = 2 * std::numbers::pi;
  const auto breathe = [&](double t) {
    const double r = r0 * (1 + e * std::sin(w * t)), rd = r0 * e * w * std::cos(w * t);
    const double ra = -r0 * e * w * w * std::sin(w * t);
    PolygonState s;
    for (int k = 0; k < n; ++k) {
      const double th = 2 * std::numbers::pi * (k + 0.5) / n, c = std::cos(th), sn = std::sin(th);
      s.position.push_back({0.5 + r * c, 0.5 + r * sn});
      s.velocity.push_back({rd * c, rd * sn});
      s.acceleration.push_back({ra * c, ra * sn});
    }
    return s;
  };
  const StretchedGrid g(Axis::uniform(0, 1, 40), Axis::uniform(0, 1, 40));
  FlowOptions opt;
  opt.nu = 2e-3;
  opt.dt = 0.01;
  FlowSolver s;
  s.setup(g, FlowBoundary{}, opt);
  s.immerse_deforming(breathe(0));
  s.initialise({});
  for (int k = 0; k < 5; ++k) {
    const double t = s.time() + s.next_dt();
    s.set_body_state(breathe(t));
    const StepStats st = s.step();
    const double r = r0 * (1 + e * std::sin(w * t)), rd = r0 * e * w * std::cos(w * t);
    const double rate = n * r * rd * std::sin(2 * std::numbers::pi / n);
    EXPECT_NEAR(s.deforming_net_flux(), rate, 1e-13 * std::abs(rate) + 1e-16);
    // The net flux is removed: continuity still holds in every cell.
    EXPECT_LT(st.max_divergence, 1e-6);
  }
}

TEST(DeformingBody, BadStatesThrowNamingTheTime) {
  FlowSolver s = flap_solver(1);
  const std::vector<StateArray> saved = s.state();
  const double t = s.time() + s.next_dt();
  const auto message = [&](const PolygonState& p) {
    try {
      s.set_body_state(p);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  PolygonState fewer = flap(t, 1);
  fewer.position.pop_back();
  fewer.velocity.pop_back();
  fewer.acceleration.pop_back();
  std::string m = message(fewer);
  EXPECT_NE(m.find("t = 0.01"), std::string::npos) << m;
  EXPECT_NE(m.find("vertices"), std::string::npos) << m;
  EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  PolygonState nan = flap(t, 1);
  nan.velocity[3][1] = std::nan("");
  m = message(nan);
  EXPECT_NE(m.find("t = 0.01"), std::string::npos) << m;
  EXPECT_NE(m.find("non-finite velocity"), std::string::npos) << m;
  PolygonState flipped = flap(t, 1);
  std::reverse(flipped.position.begin(), flipped.position.end());
  m = message(flipped);
  EXPECT_NE(m.find("inside out"), std::string::npos) << m;
  // No state for the new time level: the step says so.
  EXPECT_THROW(s.step(), Error);
  // Leaving the domain: the step names the time.
  PolygonState out = flap(t, 1);
  for (auto& p : out.position) p[0] += 0.6;
  s.set_body_state(out);
  try {
    s.step();
    ADD_FAILURE() << "no error for a body leaving the domain";
  } catch (const Error& e) {
    const std::string w = e.what();
    EXPECT_NE(w.find("t = 0.01"), std::string::npos) << w;
    EXPECT_NE(w.find("leaves the domain"), std::string::npos) << w;
  }
  // A coupling iteration recovers from a failed step by restoring.
  s.restore(saved);
  s.set_body_state(flap(t, 1));
  EXPECT_EQ(s.step().time, t);
}

// 3-D, the same contract: a sphere whose states the caller sets steps bitwise as the same motion
// given to immerse(SurfaceMotion), and restore() + the same state repeats a step bitwise.
TEST(DeformingBody, CallerSetSurfaceIn3DIsTheSurfaceMotionAndRestoresBitwise) {
  const TriangulatedSurface ref = icosphere({0.4, 0.5, 0.5}, 0.2, 2);
  const SurfaceMotion motion = [ref](double t) {
    SurfaceState st;
    st.surface = ref;
    for (auto& p : st.surface.points) {
      p[0] += 0.5 * t + 1.5 * t * t;
      p[1] += 0.02 * std::sin(6 * t) * (p[0] - 0.4);  // and a shear, so the body deforms
    }
    st.velocity.assign(ref.points.size(), Vec3{0.5 + 3 * t, 0, 0});
    st.acceleration.assign(ref.points.size(), Vec3{3, 0, 0});
    for (std::size_t k = 0; k < ref.points.size(); ++k) {
      st.velocity[k][1] = 0.12 * std::cos(6 * t) * (st.surface.points[k][0] - 0.4) + 0.02 * std::sin(6 * t) * st.velocity[k][0];
    }
    return st;
  };
  const auto make = [](FlowSolver& s) {
    const StretchedGrid g(Axis::uniform(0, 1, 16), Axis::uniform(0, 1, 16), Axis::uniform(0, 1, 16));
    FlowOptions opt;
    opt.nu = 5e-3;
    opt.dt = 0.02;
    s.setup(g, FlowBoundary::all_periodic(), opt);
  };
  FlowSolver a, b;
  make(a);
  make(b);
  a.immerse(motion);
  a.initialise({});
  b.immerse_deforming(motion(0));
  b.initialise({});
  std::size_t cleared = 0;
  for (int n = 0; n < 6; ++n) {
    a.step();
    b.set_body_state(motion(b.time() + b.next_dt()));
    b.step();
    cleared += b.freshly_cleared().size();
  }
  EXPECT_GT(cleared, 0u);
  const auto sa = a.state(), sb = b.state();
  ASSERT_EQ(sa.size() + 1, sb.size());  // b also holds the body's vertex state
  EXPECT_EQ(sb.back().name, "body_vertices");
  EXPECT_TRUE(same_state(sa, {sb.begin(), sb.end() - 1}));
  EXPECT_EQ(a.surface_forces().total[0], b.surface_forces().total[0]);
  // A coupling iteration in 3-D.
  const auto saved = b.state();
  const SurfaceState next = motion(b.time() + b.next_dt());
  b.set_body_state(next);
  b.step();
  const auto once = b.state();
  const double f = b.surface_forces().total[0];
  b.restore(saved);
  b.set_body_state(next);
  b.step();
  EXPECT_TRUE(same_state(once, b.state()));
  EXPECT_EQ(f, b.surface_forces().total[0]);
  SurfaceState bad = next;
  bad.surface.points[5][2] = std::nan("");
  b.restore(saved);
  EXPECT_THROW(b.set_body_state(bad), Error);
}

// The Turek-Hron body (cylinder + flag, one polygon) at rest in the coarse channel: a step with the
// caller-set body (every step re-placed from its vertex state) against a step of the same body as
// a MovingBody at rest; the forces agree, the cost ratio is printed.
TEST(DeformingBody, TurekHronBodyCostDeformingVsRigid) {
  const TurekHronGeometry geo;
  const double h = 2 * geo.radius / 16;
  const StretchedGrid g(Axis::uniform(0, 1.0, static_cast<int>(std::lround(1.0 / h))),
                        Axis::uniform(0, geo.height, static_cast<int>(std::lround(geo.height / h))));
  const Polygon body = turek_hron_body(geo, 512);  // the benchmark's default
  const auto make = [&] {
    FlowOptions opt = channel_benchmark_options(1e-3, 0.5, h, 1.5);
    opt.dt = 2e-3;
    FlowSolver s;
    s.setup(g, channel_benchmark_boundary(1.5, 0.1), opt);
    return s;
  };
  const MovingBody rigid_body{body, {geo.xc, geo.yc}, [](double) { return RigidState{}; }};
  FlowSolver rigid = make(), deform = make(), fixed = make();
  rigid.immerse(rigid_body);
  rigid.initialise({});
  fixed.immerse(body);  // for scale: a body that is never re-placed
  fixed.initialise({});
  PolygonState rest;
  rest.position = body.vertices();
  deform.immerse_deforming(rest);
  deform.initialise({});
  // Interleaved rounds, the fastest of each (the machine is shared).
  using clock = std::chrono::steady_clock;
  const int rounds = 3, steps = 8;
  double t_rigid = 1e300, t_deform = 1e300, t_fixed = 1e300;
  for (int r = 0; r < rounds; ++r) {
    auto t0 = clock::now();
    for (int n = 0; n < steps; ++n) fixed.step();
    t_fixed = std::min(t_fixed, std::chrono::duration<double>(clock::now() - t0).count());
    t0 = clock::now();
    for (int n = 0; n < steps; ++n) rigid.step();
    t_rigid = std::min(t_rigid, std::chrono::duration<double>(clock::now() - t0).count());
    t0 = clock::now();
    for (int n = 0; n < steps; ++n) {
      deform.set_body_state(rest);
      deform.step();
    }
    t_deform = std::min(t_deform, std::chrono::duration<double>(clock::now() - t0).count());
  }
  const SurfaceLoads L =
      SurfaceTraction(g, *rigid.immersed(), rigid.body_polygon()).evaluate(rigid.u(0), rigid.u(1), rigid.p(), 1e-3, 1000);
  const EdgeTraction E = deform.edge_traction(1000);
  std::printf("Turek-Hron body, %d x %d cells, %zu vertices: %.2f ms/step rigid (MovingBody), %.2f ms/step deforming, "
              "ratio %.2f (fixed body: %.2f ms/step); drag %.6g vs %.6g N/m\n",
              g.nx(), g.ny(), body.vertices().size(), 1e3 * t_rigid / steps, 1e3 * t_deform / steps,
              t_deform / t_rigid, 1e3 * t_fixed / steps, L.force[0], E.force[0]);
  RecordProperty("cost_ratio", std::to_string(t_deform / t_rigid));
  EXPECT_LT(std::abs(E.force[0] - L.force[0]), 1e-10 * std::abs(L.force[0]));
}

// The Turek-Hron body with each flag edge split into `segments` (vertices where the structure's
// nodes would be), its flag bent as y += d(t) ((x - x_a) / (tip - x_a))^2 beyond the arc's end
// x_a (vertical sections keep their thickness: the area stays), the arc fixed.
PolygonState bent_turek_hron(const TurekHronGeometry& geo, int segments, double d, double ddot, double dddot) {
  const Polygon body = turek_hron_body(geo, 512);
  const auto& v = body.vertices();
  // Its order: the arc from the upper flag edge round to the lower, then the tip's lower and upper
  // corners.
  const std::size_t n_arc = v.size() - 2;
  std::vector<std::array<double, 2>> pos(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n_arc));
  const double xa = v[n_arc - 1][0], tip = geo.tip_x(), lo = v[n_arc - 1][1], hi = v[0][1];
  for (int k = 1; k <= segments; ++k) pos.push_back({xa + (tip - xa) * k / segments, lo});
  for (int k = segments; k >= 1; --k) pos.push_back({xa + (tip - xa) * k / segments, hi});
  PolygonState s;
  for (auto p : pos) {
    const double xi = p[0] > xa ? (p[0] - xa) / (tip - xa) : 0.0;
    p[1] += d * xi * xi;
    s.position.push_back(p);
    s.velocity.push_back({0, ddot * xi * xi});
    s.acceleration.push_back({0, dddot * xi * xi});
  }
  return s;
}

// The flag bending in the channel flow (D/16, its thickness 3.2 cells): the run stays stable with
// continuity at the solver's tolerance while cells along the flag are cleared and covered.
TEST(DeformingBody, TurekHronFlagBendingInTheChannel) {
  const TurekHronGeometry geo;
  const double h = 2 * geo.radius / 16;
  const StretchedGrid g(Axis::uniform(0, 1.0, static_cast<int>(std::lround(1.0 / h))),
                        Axis::uniform(0, geo.height, static_cast<int>(std::lround(geo.height / h))));
  FlowOptions opt = channel_benchmark_options(1e-3, 0.5, h, 1.5);
  opt.dt = 2e-3;
  FlowSolver s;
  s.setup(g, channel_benchmark_boundary(1.5, 0.05), opt);
  const double A = 0.01, w = 2 * std::numbers::pi * 5;  // tip speed up to 0.31 m/s
  const auto state = [&](double t) {
    return bent_turek_hron(geo, 35, A * std::sin(w * t), A * w * std::cos(w * t), -A * w * w * std::sin(w * t));
  };
  s.immerse_deforming(state(0));
  s.initialise({});
  double div = 0;
  std::size_t cleared = 0;
  for (int n = 0; n < 50; ++n) {
    s.set_body_state(state(s.time() + s.next_dt()));
    const StepStats st = s.step();
    div = std::max(div, st.max_divergence);
    cleared += s.freshly_cleared().size();
  }
  const EdgeTraction E = s.edge_traction(1000);
  std::printf("Turek-Hron flag bending: %zu cells cleared over 50 steps, max continuity residual %.3g 1/s, "
              "drag %.5g lift %.5g N/m, |net wall flux| %.3g m^2/s\n",
              cleared, div, E.force[0], E.force[1], std::abs(s.deforming_net_flux()));
  EXPECT_GT(cleared, 10u);
  EXPECT_LT(div, 1e-3);  // |u| / h ~ 250 1/s
  EXPECT_TRUE(std::isfinite(E.force[0]) && std::isfinite(E.force[1]));
  EXPECT_LT(std::abs(s.deforming_net_flux()), 1e-15);
}

}  // namespace
}  // namespace finverse::cfd
