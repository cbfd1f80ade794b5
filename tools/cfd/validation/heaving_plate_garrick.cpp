// The heaving plate against Garrick's theory: grid, runs and averages; see heaving_plate_garrick.hpp.
#include "cfd/validation/heaving_plate_garrick.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "cfd/forces/surface_traction.hpp"
#include "cfd/validation/case_support.hpp"
#include "core/error.hpp"

namespace finverse::cfd {

namespace {
using std::numbers::pi;
}  // namespace

double HeavingPlateSetup::period() const { return pi / reduced_frequency; }

Polygon heaving_plate_polygon(double thickness, int end_vertices) {
  const double r = thickness / 2;
  std::vector<std::array<double, 2>> v;
  // Counter-clockwise: the trailing-edge arc from the lower side up, then the leading-edge arc
  // from the upper side down; the straight sides are the two edges between the arcs.
  for (int i = 0; i <= end_vertices; ++i) {
    const double a = -pi / 2 + pi * i / end_vertices;
    v.push_back({1 - r + r * std::cos(a), r * std::sin(a)});
  }
  for (int i = 0; i <= end_vertices; ++i) {
    const double a = pi / 2 + pi * i / end_vertices;
    v.push_back({r + r * std::cos(a), r * std::sin(a)});
  }
  return Polygon(std::move(v));
}

HeavingPlateResult run_heaving_plate(const HeavingPlateSetup& hs) {
  if (!(hs.re > 0) || !(hs.reduced_frequency > 0) || hs.amplitudes.empty() || !(hs.thickness > 0) ||
      !(hs.ramp_periods > 0) || hs.ramp_periods > hs.periods - hs.periods_averaged ||
      hs.thickness >= 0.5 || hs.cells_per_chord < 8 || hs.periods_averaged < 1 || hs.periods_averaged > hs.periods ||
      !(hs.cfl > 0) || hs.end_vertices < 2)
    throw Error("heaving plate: need re, k > 0, amplitudes, 0 < thickness < c/2, cells_per_chord >= 8, "
                "1 <= periods_averaged <= periods, 0 < ramp_periods <= periods - periods_averaged, cfl > 0, "
                "end_vertices >= 2");
  for (double a : hs.amplitudes)
    if (!(a > 0) || a > 1) throw Error("heaving plate: amplitudes h0/c must lie in (0, 1]");
  const double h = 1.0 / hs.cells_per_chord, T = hs.period(), w = 2 * pi / T;
  const double amax = *std::max_element(hs.amplitudes.begin(), hs.amplitudes.end());
  const double ylim = amax + hs.thickness / 2 + hs.box_margin;
  if (!(hs.half_height > 2 * ylim) || !(hs.upstream > 2 * hs.box_margin) || !(hs.downstream > 2 * hs.box_behind))
    throw Error("heaving plate: the domain must extend well beyond the uniform box around the plate's path");
  // One grid for every run (the plate at rest included), covering the largest amplitude's path.
  using validation::multigrid_axis;
  const StretchedGrid g(multigrid_axis(-hs.upstream, 1 + hs.downstream, -hs.box_margin, 1 + hs.box_behind, h, hs.stretch_ratio),
                        multigrid_axis(-hs.half_height, hs.half_height, -ylim, ylim, h, hs.stretch_ratio));
  HeavingPlateResult r;
  r.h = h;
  r.cells = static_cast<long>(g.cells());
  r.steps_per_period = std::max(20L, static_cast<long>(std::ceil(T / (hs.cfl * h))));
  r.dt = T / static_cast<double>(r.steps_per_period);
  r.steps = r.steps_per_period * hs.periods;

  FlowOptions opt;
  opt.nu = 1.0 / hs.re;
  opt.dt = r.dt;
  opt.helmholtz_rtol = 1e-10;
  opt.poisson.rtol = 1e-9;
  FlowBoundary b;
  b[Side::XLo].type = FlowBcType::Inlet;
  b[Side::XLo].speed = 1.0;
  b[Side::XHi].type = FlowBcType::ConvectiveOutlet;
  // The side walls slide with the stream: no boundary layer of their own.
  b[Side::YLo].wall_velocity = {1, 0, 0};
  b[Side::YHi].wall_velocity = {1, 0, 0};
  const Polygon plate = heaving_plate_polygon(hs.thickness, hs.end_vertices);

  const auto run = [&](double h0) {
    const auto t0 = std::chrono::steady_clock::now();
    HeavingPlateRun q;
    q.amplitude = h0;
    FlowSolver s;
    s.setup(g, b, opt);
    // The plate at rest is a moving body with zero motion: the same discretisation (cut-cell mass
    // balance, wall pressure datum) as the heaving plate, so the difference is the motion's.
    // y = h0 r(t) sin(omega t): the amplitude ramps up as r = (1 - cos(pi t / T_r)) / 2 over the
    // first T_r = ramp_periods T. A plate set moving normal to itself impulsively has singular edge
    // velocities (a CFL of 2.4 in the first step at Re 1000 and c/100); the averaged periods come
    // after the ramp.
    const double tr = hs.ramp_periods * T;
    s.immerse(MovingBody{plate, {0.5, 0}, [=](double t) {
                           const auto [ramp, dramp, ddramp] = validation::cosine_ramp(t, tr);
                           const double sn = std::sin(w * t), cs = std::cos(w * t);
                           RigidState st;
                           st.displacement = {0, h0 * ramp * sn};
                           st.velocity = {0, h0 * (dramp * sn + ramp * w * cs)};
                           st.acceleration = {0, h0 * (ddramp * sn + 2 * dramp * w * cs - ramp * w * w * sn)};
                           return st;
                         }});
    s.initialise([](double, double, double, double) { return std::array<double, 3>{1, 0, 0}; });
    const long first = r.steps - static_cast<long>(hs.periods_averaged) * r.steps_per_period;
    std::vector<double> period_means(static_cast<std::size_t>(hs.periods_averaged), 0.0);
    const std::string tag = h0 > 0 ? "h0/c " + std::to_string(h0) : "at rest";
    for (long n = 0; n < r.steps; ++n) {
      StepStats st;
      try {
        st = s.step();
      } catch (const Error& e) {
        if (h0 == 0) throw;  // nothing to compare without the plate at rest
        q.failed = true;
        q.error = e.what();
        break;
      }
      q.max_cfl = std::max(q.max_cfl, st.cfl);
      q.max_divergence = std::max(q.max_divergence, st.max_divergence);
      if (h0 == 0) r.time.push_back(st.time);
      const MovingBody& body = *s.moving_body();
      const SurfaceTraction tr(s.grid(), *s.immersed(), s.body_polygon());
      const SurfaceLoads l = tr.evaluate(s.u(0), s.u(1), s.p(), opt.nu, 1.0, [&](double x, double y) {
        return body.velocity(s.body_state(), x, y);
      });
      // rho = U = c = 1: coefficient = 2 F.
      q.cx.push_back(2 * l.force[0]);
      q.cy.push_back(2 * l.force[1]);
      if (n >= first) {
        const double m = static_cast<double>(hs.periods_averaged * r.steps_per_period);
        q.mean_cx += 2 * l.force[0] / m;
        q.mean_cx_pressure += 2 * l.pressure_force[0] / m;
        q.mean_cx_viscous += 2 * l.viscous_force[0] / m;
        q.mean_cp += -2 * l.force[1] * s.body_state().velocity[1] / m;
        period_means[static_cast<std::size_t>((n - first) / r.steps_per_period)] +=
            2 * l.force[0] / static_cast<double>(r.steps_per_period);
      }
      if (hs.progress) hs.progress(tag, st);
    }
    if (q.failed) {
      q.mean_cx = q.mean_cx_pressure = q.mean_cx_viscous = q.mean_cp = std::nan("");
    } else {
      const auto [lo, hi] = std::minmax_element(period_means.begin(), period_means.end());
      q.cx_period_spread = *hi - *lo;
    }
    q.cpu_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return q;
  };
  r.rest = run(0.0);
  for (double a : hs.amplitudes) r.heaving.push_back(run(a));
  return r;
}

}  // namespace finverse::cfd
