// Checkpoint and restart of the flow solver with a moving immersed body (flow_checkpoint.hpp,
// FlowSolver::state/restore): a 2-D rigid cylinder heaving and pitching across a box, and a 3-D
// triangulated sphere moving through a periodic box. Stepping 2N times and stepping N times, writing
// a checkpoint, reading it into a fresh solver and stepping N more give bitwise the same state and
// the same body forces, while cells are cleared by the moving body along the way. A body that
// leaves the domain ends the run with a one-line error naming the time.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <numbers>
#include <string>

#include "cfd/io/flow_checkpoint.hpp"
#include "cfd/flow/flow_solver.hpp"
#include "cfd/immersed/surface_shapes.hpp"
#include "cfd/forces/surface_traction.hpp"
#include "core/error.hpp"

namespace finverse::cfd {
namespace {

std::filesystem::path scratch(const std::string& name) {
  return std::filesystem::temp_directory_path() /
         ("finverse_moving_ckpt_" + std::to_string(::getpid()) + "_" + name + ".h5");
}

void expect_same_state(const FlowSolver& a, const FlowSolver& b) {
  const auto sa = a.state(), sb = b.state();
  ASSERT_EQ(sa.size(), sb.size());
  for (std::size_t m = 0; m < sa.size(); ++m) {
    ASSERT_EQ(sa[m].name, sb[m].name);
    ASSERT_EQ(sa[m].values.size(), sb[m].values.size()) << sa[m].name;
    EXPECT_TRUE(sa[m].values.empty() ||
                std::memcmp(sa[m].values.data(), sb[m].values.data(), sa[m].values.size() * sizeof(double)) == 0)
        << sa[m].name << " differs";
  }
}

// Steps `full` 2n times and `restarted` n times + checkpoint + read into `fresh` + n times;
// `fresh` is a solver set up as `full` but not stepped. Returns the cells cleared in the run.
std::size_t run_both(const std::function<FlowSolver()>& make, int n, const std::string& name, FlowSolver& full,
                     FlowSolver& restarted) {
  full = make();
  std::size_t cleared = 0;
  for (int k = 0; k < 2 * n; ++k) {
    full.step();
    cleared += full.freshly_cleared().size();
  }
  FlowSolver first = make();
  for (int k = 0; k < n; ++k) first.step();
  const auto path = scratch(name);
  write_checkpoint(path, first);
  restarted = make();
  read_checkpoint(path, restarted);
  std::filesystem::remove(path);
  EXPECT_EQ(restarted.steps(), n);
  EXPECT_EQ(restarted.time(), first.time());
  for (int k = 0; k < n; ++k) restarted.step();
  return cleared;
}

TEST(MovingCheckpoint, RigidBodyIn2DRestartsBitwise) {
  const auto make = [] {
    const StretchedGrid g(Axis::uniform(0, 1, 40), Axis::stretched_count(0, 0.5, 0.1, 0.4, 24, 1.15));
    std::vector<std::array<double, 2>> v;
    for (int k = 0; k < 48; ++k) {
      const double t = 2 * std::numbers::pi * (k + 0.5) / 48;
      v.push_back({0.4 + 0.08 * std::cos(t), 0.25 + 0.05 * std::sin(t)});
    }
    // An ellipse towed in +x while heaving and pitching: cells are cleared on every side.
    const MovingBody body{Polygon(v), {0.4, 0.25}, [](double t) {
                            const double w = 2 * std::numbers::pi;
                            RigidState s;
                            s.displacement = {0.3 * t, 0.02 * std::sin(w * t)};
                            s.velocity = {0.3, 0.02 * w * std::cos(w * t)};
                            s.acceleration = {0, -0.02 * w * w * std::sin(w * t)};
                            s.angle = 0.2 * std::sin(w * t);
                            s.angular_velocity = 0.2 * w * std::cos(w * t);
                            s.angular_acceleration = -0.2 * w * w * std::sin(w * t);
                            return s;
                          }};
    FlowOptions opt;
    opt.nu = 2e-3;
    opt.cfl = 0.4;
    opt.dt_max = 0.02;  // variable steps: the time-step history is part of the state
    FlowSolver s;
    s.setup(g, FlowBoundary{}, opt);
    s.immerse(body);
    s.initialise({});
    return s;
  };
  FlowSolver full, restarted;
  const std::size_t cleared = run_both(make, 8, "rigid", full, restarted);
  EXPECT_GT(cleared, 0u);
  expect_same_state(full, restarted);
  EXPECT_EQ(restarted.time(), full.time());
  const SurfaceLoads a = SurfaceTraction(full.grid(), *full.immersed(), full.body_polygon())
                             .evaluate(full.u(0), full.u(1), full.p(), full.options().nu, 1.0);
  const SurfaceLoads b = SurfaceTraction(restarted.grid(), *restarted.immersed(), restarted.body_polygon())
                             .evaluate(restarted.u(0), restarted.u(1), restarted.p(), restarted.options().nu, 1.0);
  EXPECT_EQ(a.force[0], b.force[0]);
  EXPECT_EQ(a.force[1], b.force[1]);
  EXPECT_NE(a.force[0], 0.0);
}

TEST(MovingCheckpoint, TriangulatedBodyIn3DRestartsBitwise) {
  const auto make = [] {
    const StretchedGrid g(Axis::uniform(0, 1, 16), Axis::uniform(0, 1, 16), Axis::uniform(0, 1, 16));
    const TriangulatedSurface ref = icosphere({0.4, 0.5, 0.5}, 0.2, 2);
    FlowOptions opt;
    opt.nu = 5e-3;
    opt.dt = 0.02;
    FlowSolver s;
    s.setup(g, FlowBoundary::all_periodic(), opt);
    // Started impulsively through fluid at rest and accelerating: more than a cell width before
    // the checkpoint, so cells have been solid and cleared again (a ghost cell's solid-cell
    // velocity from an earlier time is part of the state).
    s.immerse(SurfaceMotion([ref](double t) {
      SurfaceState st;
      st.surface = ref;
      for (auto& p : st.surface.points) p[0] += 0.5 * t + 1.5 * t * t;
      st.velocity.assign(ref.points.size(), Vec3{0.5 + 3 * t, 0, 0});
      st.acceleration.assign(ref.points.size(), Vec3{3, 0, 0});
      return st;
    }));
    s.initialise({});
    return s;
  };
  FlowSolver full, restarted;
  const std::size_t cleared = run_both(make, 6, "surface", full, restarted);
  EXPECT_GT(cleared, 0u);
  expect_same_state(full, restarted);
  const SurfaceForces a = full.surface_forces(), b = restarted.surface_forces();
  for (int d = 0; d < 3; ++d) EXPECT_EQ(a.total[static_cast<std::size_t>(d)], b.total[static_cast<std::size_t>(d)]);
  EXPECT_NE(a.total[0], 0.0);
}

TEST(MovingCheckpoint, BodyLeavingTheDomainIsAOneLineError) {
  // A sphere heading for the x+ wall at 1 m/s (its surface reaches x = 1 at t = 0.3). Small steps:
  // its ghost cells' image points leave the grid first; one long step: it jumps across the wall,
  // which the bounding-box check catches.
  for (const double dt : {0.05, 0.4}) {
    SCOPED_TRACE(dt);
    const StretchedGrid g(Axis::uniform(0, 1, 12), Axis::uniform(0, 1, 12), Axis::uniform(0, 1, 12));
    const TriangulatedSurface ref = icosphere({0.5, 0.5, 0.5}, 0.2, 1);
    FlowOptions opt;
    opt.nu = 5e-3;
    opt.dt = dt;
    opt.cfl_limit = 100;
    FlowSolver s;
    s.setup(g, FlowBoundary{}, opt);
    s.immerse(SurfaceMotion([ref](double t) {
      SurfaceState st;
      st.surface = ref;
      for (auto& p : st.surface.points) p[0] += t;
      st.velocity.assign(ref.points.size(), Vec3{1, 0, 0});
      return st;
    }));
    s.initialise({});
    std::string what;
    long steps = 0;
    try {
      for (; steps < 20; ++steps) s.step();
    } catch (const Error& e) {
      what = e.what();
    }
    EXPECT_LE(static_cast<double>(steps) * dt, 0.3);  // caught when it happens
    EXPECT_NE(what.find(dt > 0.3 ? "leaves the domain" : "too close to the domain boundary"), std::string::npos)
        << what;
    EXPECT_NE(what.find("t = "), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace finverse::cfd
