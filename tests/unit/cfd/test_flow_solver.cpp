// Tests of the Navier-Stokes fractional-step solver: observed order of accuracy in space and in
// time (Taylor-Green), discrete continuity after every step, momentum conservation in a periodic
// box, plane Poiseuille flow (periodic with a body force, and inlet/outlet with walls), 3-D paths,
// checkpoint restart bitwise equality, thread-count independence, blow-up detection.
#include <gtest/gtest.h>

#include <omp.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <string>

#include "cfd/io/flow_checkpoint.hpp"
#include "cfd/flow/flow_solver.hpp"
#include "cfd/validation/taylor_green.hpp"
#include "core/error.hpp"

namespace finverse::cfd {
namespace {

using std::numbers::pi;

// ---- order of accuracy ------------------------------------------------------------------------

TEST(TaylorGreen, SecondOrderInSpaceOnUniformAndStretchedGrids) {
  for (double stretch : {0.0, 0.3}) {
    TaylorGreenSetup s;
    s.dt = 0.025;
    s.t_end = 0.5;
    s.stretch = stretch;
    s.coupling_time = 0.0125;
    s.n = 16;
    const TaylorGreenResult a = run_taylor_green(s);
    s.n = 32;
    const TaylorGreenResult b = run_taylor_green(s);
    s.n = 64;
    const TaylorGreenResult c = run_taylor_green(s);
    const double ou = std::log2(b.u_l2 / c.u_l2), op = std::log2(b.p_l2 / c.p_l2);
    std::printf("stretch %.1f: u L2 %.3e %.3e %.3e (order %.3f), p L2 %.3e %.3e %.3e (order %.3f)\n", stretch, a.u_l2,
                b.u_l2, c.u_l2, ou, a.p_l2, b.p_l2, c.p_l2, op);
    EXPECT_GT(std::log2(a.u_l2 / b.u_l2), 1.9);
    EXPECT_GT(ou, 1.9);
    EXPECT_GT(op, 1.9);
    EXPECT_GT(std::log2(a.u_linf / b.u_linf), 1.8);
    EXPECT_GT(std::log2(b.u_linf / c.u_linf), 1.8);
  }
}

TEST(TaylorGreen, SecondOrderInTimeOnAFixedGrid) {
  // nu large enough that the Crank-Nicolson error is what the study sees; differences of runs
  // with dt, dt/2, dt/4 on one grid (Richardson), so the spatial error cancels.
  TaylorGreenSetup s;
  s.n = 24;
  s.nu = 0.2;
  s.stretch = 0.3;
  s.coupling_time = 0.0125;
  std::vector<TaylorGreenResult> r;
  for (double dt : {0.1, 0.05, 0.025}) {
    s.dt = dt;
    r.push_back(run_taylor_green(s));
  }
  const double d1 = velocity_difference(r[0], r[1]), d2 = velocity_difference(r[1], r[2]);
  std::printf("time differences %.3e %.3e, order %.3f\n", d1, d2, std::log2(d1 / d2));
  EXPECT_GT(std::log2(d1 / d2), 1.85);
  EXPECT_LT(std::log2(d1 / d2), 2.3);  // second, not higher: the scheme is CN/AB2
}

TEST(TaylorGreen, ClassicalCouplingCarriesAnOrderDtTerm) {
  // The documented reason for coupling_time: with tau = dt, the difference between dt and dt/2
  // halves (first order) on a fixed grid.
  TaylorGreenSetup s;
  s.n = 16;
  s.stretch = 0.3;
  s.coupling_time = 0;
  std::vector<TaylorGreenResult> r;
  for (double dt : {0.1, 0.05, 0.025}) {
    s.dt = dt;
    r.push_back(run_taylor_green(s));
  }
  const double order = std::log2(velocity_difference(r[0], r[1]) / velocity_difference(r[1], r[2]));
  EXPECT_NEAR(order, 1.0, 0.2);
}

// ---- continuity and conservation ----------------------------------------------------------------

// A smooth periodic flow without symmetries: a Taylor-Green-like vortex pair plus a uniform drift.
VelocityFunction wavy_flow(int dim) {
  return [dim](double x, double y, double z, double) {
    const double sz = dim == 3 ? std::sin(z + 0.3) : 0.0;
    return std::array<double, 3>{0.4 + std::sin(x) * std::cos(y + 0.2) + 0.3 * sz,
                                 -0.2 - std::cos(x) * std::sin(y + 0.2) + 0.2 * std::sin(2 * x),
                                 dim == 3 ? 0.1 + 0.5 * std::sin(x + y) : 0.0};
  };
}

StretchedGrid periodic_grid(int dim, int n) {
  const StretchedGrid g2 = taylor_green_grid(n, 0.25);
  if (dim == 2) return g2;
  return StretchedGrid(g2.axis(0), g2.axis(1), g2.axis(0));
}

TEST(FlowSolver, FacesDivergenceFreeAndMomentumConservedInAPeriodicBox) {
  for (int dim : {2, 3}) {
    FlowOptions opt;
    opt.nu = 0.02;
    opt.dt = 0.05;
    opt.poisson.rtol = 1e-10;
    FlowSolver s;
    s.setup(periodic_grid(dim, dim == 2 ? 32 : 16), FlowBoundary::all_periodic(), opt);
    s.initialise(wavy_flow(dim));
    double m0[3];
    for (int c = 0; c < dim; ++c) m0[c] = s.momentum(c);
    EXPECT_LT(s.max_divergence(), 1e-9);
    const double e0 = s.kinetic_energy();
    for (int n = 0; n < 10; ++n) {
      const StepStats st = s.step();
      // Discrete continuity to the Poisson tolerance after every step.
      EXPECT_LT(st.max_divergence, 1e-8) << "dim " << dim << " step " << st.step;
      EXPECT_GT(st.poisson_iterations, 0);
    }
    for (int c = 0; c < dim; ++c)
      EXPECT_NEAR(s.momentum(c), m0[c], 1e-11 * (std::abs(m0[c]) + 1)) << "dim " << dim << " component " << c;
    // Viscosity only removes energy.
    EXPECT_LT(s.kinetic_energy(), e0);
    EXPECT_GT(s.kinetic_energy(), 0.5 * e0);
  }
}

// ---- Poiseuille flow ------------------------------------------------------------------------------

// Plane Poiseuille flow driven by a body force G between no-slip walls at y = 0, H = 1:
// u = G y (H - y) / (2 nu). Periodic in x (and z in 3-D). Returns the max error at steady state.
double periodic_poiseuille_error(int ny, int dim) {
  const double G = 1.0, nu = 1.0;
  // One smooth stretched mapping sampled ever finer (Axis::refined): a convergence family.
  Axis ay = Axis::stretched_count(0, 1, 0.25, 0.75, 8, 1.2);
  while (ay.size() < ny) ay = ay.refined();
  StretchedGrid g = dim == 2 ? StretchedGrid(Axis::uniform(0, 1, 4), ay)
                             : StretchedGrid(Axis::uniform(0, 1, 4), ay, Axis::uniform(0, 1, 4));
  FlowBoundary b;
  b[Side::XLo].type = b[Side::XHi].type = FlowBcType::Periodic;
  b[Side::ZLo].type = b[Side::ZHi].type = FlowBcType::Periodic;
  FlowOptions opt;
  opt.nu = nu;
  opt.dt = 0.01;  // nu dt / h^2 <= 10: Crank-Nicolson still damps the stiffest start-up modes
  opt.body_force = [G](double, double, double, double) { return std::array<double, 3>{G, 0, 0}; };
  FlowSolver s;
  s.setup(g, b, opt);
  s.initialise({});
  for (int n = 0; n < 400; ++n) s.step();  // t = 4: the slowest mode has decayed by exp(-4 pi^2)
  double e = 0;
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) {
        const double y = g.yc(j);
        e = std::max(e, std::abs(s.u(0)(i, j, k) - G * y * (1 - y) / (2 * nu)));
        e = std::max(e, std::abs(s.u(1)(i, j, k)));
      }
  return e;
}

TEST(Poiseuille, PeriodicChannelConvergesAtSecondOrder) {
  const double e8 = periodic_poiseuille_error(8, 2), e16 = periodic_poiseuille_error(16, 2),
               e32 = periodic_poiseuille_error(32, 2);
  std::printf("Poiseuille max error %.3e %.3e %.3e (u_max 0.125)\n", e8, e16, e32);
  EXPECT_LT(e32, 2e-3 * 0.125);
  EXPECT_GT(std::log2(e16 / e32), 1.9);
  // The 3-D code path gives the same answer.
  EXPECT_NEAR(periodic_poiseuille_error(16, 3), e16, 1e-9);
}

TEST(Poiseuille, InletOutletChannelKeepsTheProfileAndPressureGradient) {
  // Parabolic inlet (ramped), convective outlet, no-slip walls, CFL-controlled steps: the fully
  // developed solution is the inlet profile everywhere with dp/dx = -8 nu Um / H^2.
  const double nu = 0.1, Um = 1.0, L = 3.0, H = 1.0;
  const StretchedGrid g(Axis::uniform(0, L, 48), Axis::stretched_count(0, H, 0.3, 0.7, 16, 1.2));
  FlowBoundary b;
  b[Side::XLo].type = FlowBcType::Inlet;
  b[Side::XLo].profile = InletProfile::Parabolic;
  b[Side::XLo].speed = Um;
  b[Side::XLo].ramp_time = 0.5;
  b[Side::XHi].type = FlowBcType::ConvectiveOutlet;
  FlowOptions opt;
  opt.nu = nu;
  opt.cfl = 0.5;
  opt.dt_max = 0.02;
  FlowSolver s;
  s.setup(g, b, opt);
  s.initialise({});
  double t_inlet = 0;
  while (s.time() < 4.0) {
    const StepStats st = s.step();
    EXPECT_LT(st.max_divergence, 1e-8) << "step " << st.step;
    EXPECT_LE(st.cfl, 0.6);  // chosen from the old velocity for 0.5; measured with the new one
    t_inlet = st.time;
  }
  ASSERT_GT(t_inlet, 0);
  double e = 0, flux_out = 0, flux_in = 0;
  for (int j = 0; j < g.ny(); ++j) {
    const double y = g.yc(j), exact = 4 * Um * y * (H - y) / (H * H);
    for (int i = 0; i < g.nx(); ++i) e = std::max(e, std::abs(s.u(0)(i, j, 0) - exact));
    flux_in += s.face_velocity()(0, 0, j, 0) * g.dy(j);
    flux_out += s.face_velocity()(0, g.nx(), j, 0) * g.dy(j);
  }
  const double gradient = (s.p()(36, 8, 0) - s.p()(12, 8, 0)) / (g.xc(36) - g.xc(12));
  std::printf("channel: max |u - parabola| %.3e, dp/dx %.5f (exact %.5f), fluxes %.12f %.12f\n", e, gradient,
              -8 * nu * Um / (H * H), flux_in, flux_out);
  EXPECT_LT(e, 0.01 * Um);
  EXPECT_NEAR(gradient, -8 * nu * Um / (H * H), 0.02 * 8 * nu * Um / (H * H));
  EXPECT_NEAR(flux_out, flux_in, 1e-12);
  EXPECT_NEAR(flux_in, 2.0 / 3.0 * Um * H, 0.01);
}

TEST(Poiseuille, ThreeDimensionalDuctWithZeroGradientOutlet) {
  // 3-D non-periodic paths: duct with the product-parabola inlet, four no-slip walls, a zero-
  // gradient outlet. Continuity to the Poisson tolerance every step, exact mass balance, and the
  // mirror symmetries of the duct kept.
  const StretchedGrid g(Axis::uniform(0, 2, 16), Axis::uniform(0, 1, 8),
                        Axis({0, 0.08, 0.2, 0.35, 0.5, 0.65, 0.8, 0.92, 1}));  // stretched, symmetric
  FlowBoundary b;
  b[Side::XLo].type = FlowBcType::Inlet;
  b[Side::XLo].profile = InletProfile::Parabolic;
  b[Side::XHi].type = FlowBcType::ZeroGradientOutlet;
  FlowOptions opt;
  opt.nu = 0.05;
  opt.dt = 0.02;
  FlowSolver s;
  s.setup(g, b, opt);
  s.initialise({});
  for (int n = 0; n < 10; ++n) EXPECT_LT(s.step().max_divergence, 1e-8);
  double qin = 0, qout = 0;
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j) {
      qin += s.face_velocity()(0, 0, j, k) * g.dy(j) * g.dz(k);
      qout += s.face_velocity()(0, g.nx(), j, k) * g.dy(j) * g.dz(k);
    }
  EXPECT_NEAR(qout, qin, 1e-13);
  EXPECT_GT(qin, 0.4);  // 4/9 of the centreline speed times the area, sampled at face centres
  // The duct's mirror symmetries y -> 1 - y and z -> 1 - z.
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j)
      EXPECT_NEAR(s.u(0)(8, j, k), s.u(0)(8, g.ny() - 1 - j, g.nz() - 1 - k), 1e-9);
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j) EXPECT_NEAR(s.u(0)(8, j, k), s.u(0)(8, g.ny() - 1 - j, k), 1e-9);
}

TEST(FlowBoundary, InletRampAndProfiles) {
  const StretchedGrid g(Axis::uniform(0, 2, 4), Axis::uniform(-1, 1, 4), Axis::uniform(0, 2, 4));
  FlowBoundary b;
  b[Side::XLo].type = FlowBcType::Inlet;
  b[Side::XLo].profile = InletProfile::Parabolic;
  b[Side::XLo].speed = 2.0;
  b[Side::XLo].ramp_time = 1.0;
  b[Side::XHi].type = FlowBcType::Inlet;  // uniform, pointing into the domain (-x)
  b.validate(3);
  EXPECT_DOUBLE_EQ(b.velocity(g, Side::XLo, 0, 0, 1, 2.0)[0], 2.0);   // centre of the duct
  EXPECT_DOUBLE_EQ(b.velocity(g, Side::XLo, 0, 0, 1, 0.5)[0], 1.0);   // half-way up the ramp
  EXPECT_NEAR(b.velocity(g, Side::XLo, 0, 0.5, 1, 2.0)[0], 1.5, 1e-14);  // 4 s (H - s) / H^2 = 3/4
  EXPECT_DOUBLE_EQ(b.velocity(g, Side::XHi, 2, 0.3, 0.1, 0)[0], -1.0);
  b[Side::YLo].type = FlowBcType::Periodic;
  EXPECT_THROW(b.validate(3), Error);
}

// ---- restart, threads, blow-up ------------------------------------------------------------------

FlowSolver channel_solver() {
  const StretchedGrid g(Axis::uniform(0, 2, 24), Axis::stretched_count(0, 1, 0.3, 0.7, 12, 1.2));
  FlowBoundary b;
  b[Side::XLo].type = FlowBcType::Inlet;
  b[Side::XLo].profile = InletProfile::Parabolic;
  b[Side::XLo].ramp_time = 0.2;
  b[Side::XHi].type = FlowBcType::ConvectiveOutlet;
  b[Side::YHi].type = FlowBcType::Slip;
  FlowOptions opt;
  opt.nu = 0.01;
  opt.cfl = 0.4;
  opt.dt_max = 0.02;
  FlowSolver s;
  s.setup(g, b, opt);
  s.initialise([](double, double y, double, double) { return std::array<double, 3>{0.1 * y, 0.05 * std::sin(3 * y), 0}; });
  return s;
}

bool same_flow_state(const FlowSolver& a, const FlowSolver& b) {
  const auto sa = a.state(), sb = b.state();
  if (sa.size() != sb.size()) return false;
  for (std::size_t m = 0; m < sa.size(); ++m)
    if (sa[m].values.size() != sb[m].values.size() ||
        (!sa[m].values.empty() && std::memcmp(sa[m].values.data(), sb[m].values.data(), sa[m].values.size() * sizeof(double)) != 0))
      return false;
  return true;
}

TEST(FlowSolver, RestartFromCheckpointIsBitwiseIdentical) {
  FlowSolver full = channel_solver();
  for (int n = 0; n < 5; ++n) full.step();
  const auto path = std::filesystem::temp_directory_path() / ("finverse_cfd_checkpoint_" + std::to_string(::getpid()) + ".h5");
  write_checkpoint(path, full);
  for (int n = 0; n < 5; ++n) full.step();

  FlowSolver restarted = channel_solver();
  EXPECT_FALSE(same_flow_state(full, restarted));
  read_checkpoint(path, restarted);
  std::filesystem::remove(path);
  EXPECT_EQ(restarted.steps(), 5);
  for (int n = 0; n < 5; ++n) restarted.step();
  EXPECT_TRUE(same_flow_state(full, restarted));
  EXPECT_EQ(restarted.time(), full.time());
}

TEST(FlowSolver, ResultsIndependentOfThreadCount) {
  // 128^2 cells: above parallel_min_cells, so the loops and reductions really run in parallel.
  auto run = [](int threads) {
    const int saved = omp_get_max_threads();
    omp_set_num_threads(threads);
    FlowOptions opt;
    opt.nu = 0.01;
    opt.cfl = 0.4;
    opt.dt_max = 0.05;
    FlowSolver s;
    s.setup(periodic_grid(2, 128), FlowBoundary::all_periodic(), opt);
    s.initialise(wavy_flow(2));
    for (int n = 0; n < 3; ++n) s.step();
    omp_set_num_threads(saved);
    return s;
  };
  const FlowSolver a = run(1), b = run(3);
  EXPECT_TRUE(same_flow_state(a, b));
}

TEST(FlowSolver, BlowUpEndsWithAnErrorNamingTheStep) {
  FlowOptions opt;
  opt.nu = 1e-3;
  opt.dt = 4.0;  // CFL of order 40
  FlowSolver s;
  s.setup(taylor_green_grid(16, 0.0), FlowBoundary::all_periodic(), opt);
  s.initialise(wavy_flow(2));
  try {
    s.step();
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("step 1 "), std::string::npos) << m;
    EXPECT_NE(m.find("CFL"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
  // A body force that turns non-finite after t = 0.032: the step that meets it is named.
  FlowSolver nan_run;
  opt.dt = 0.01;
  opt.body_force = [](double, double, double, double t) {
    return std::array<double, 3>{t > 0.032 ? std::nan("") : 0.0, 0, 0};
  };
  nan_run.setup(taylor_green_grid(16, 0.0), FlowBoundary::all_periodic(), opt);
  nan_run.initialise(wavy_flow(2));
  for (int n = 0; n < 3; ++n) nan_run.step();
  try {
    nan_run.step();
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("step 4:"), std::string::npos) << e.what();
  }
  FlowSolver bad_start;
  bad_start.setup(taylor_green_grid(16, 0.0), FlowBoundary::all_periodic(), opt);
  EXPECT_THROW(bad_start.initialise([](double, double, double, double) {
    return std::array<double, 3>{std::nan(""), 0, 0};
  }), Error);
}

TEST(FlowSolver, RejectsBadOptions) {
  FlowSolver s;
  FlowOptions opt;
  opt.dt = 0;
  opt.cfl = 0.5;  // dt_max infinite
  EXPECT_THROW(s.setup(taylor_green_grid(8, 0.0), FlowBoundary::all_periodic(), opt), Error);
}

}  // namespace
}  // namespace finverse::cfd
