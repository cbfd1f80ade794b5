// The spanwise-uniform plate, 3-D thin body against the 2-D section: grids, motion, runs and the
// last period's force measures; see spanwise_plate_2d3d.hpp.
#include "cfd/validation/spanwise_plate_2d3d.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <numbers>

#include "cfd/forces/surface_traction.hpp"
#include "cfd/validation/case_support.hpp"
#include "cfd/io/fin_input.hpp"
#include "cfd/validation/thin_plate_case.hpp"
#include "core/error.hpp"

namespace finverse::cfd {

namespace {
using std::numbers::pi;

// Heave y and counter-clockwise pitch theta with their first two time derivatives.
struct Pose {
  double y = 0, dy = 0, ddy = 0, th = 0, dth = 0, ddth = 0;
};

Pose pose(const SpanwisePlateSetup& s, double t) {
  const double w = 2 * pi / s.period, tr = s.ramp_periods * s.period;
  const auto [r, dr, ddr] = validation::cosine_ramp(t, tr);
  const double sn = std::sin(w * t), cs = std::cos(w * t);
  Pose p;
  // (r f)'' = r'' f + 2 r' f' + r f'' for f = h0 sin(wt) and f = -theta0 cos(wt).
  p.y = s.heave * r * sn;
  p.dy = s.heave * (dr * sn + r * w * cs);
  p.ddy = s.heave * (ddr * sn + 2 * dr * w * cs - r * w * w * sn);
  p.th = -s.pitch * r * cs;
  p.dth = -s.pitch * (dr * cs - r * w * sn);
  p.ddth = -s.pitch * (ddr * cs - 2 * dr * w * sn - r * w * w * cs);
  return p;
}

// Mean, fundamental amplitude and the rms above the 10th harmonic of one whole period of samples
// (equally spaced, t_n = t0 + n T / N): the discrete Fourier series is exact there.
struct PeriodMeasures {
  double mean = 0, amplitude = 0, noise = 0;
};

PeriodMeasures measure(const std::vector<double>& c, std::size_t first, std::size_t n) {
  PeriodMeasures m;
  const int kept = std::min<int>(10, static_cast<int>(n / 2) - 1);
  std::vector<std::complex<double>> a(static_cast<std::size_t>(kept) + 1);
  for (int h = 0; h <= kept; ++h) {
    std::complex<double> s = 0;
    for (std::size_t q = 0; q < n; ++q)
      s += c[first + q] * std::polar(1.0, -2 * pi * h * static_cast<double>(q) / static_cast<double>(n));
    a[static_cast<std::size_t>(h)] = s / static_cast<double>(n);
  }
  m.mean = a[0].real();
  m.amplitude = 2 * std::abs(a[1]);
  double rss = 0;
  for (std::size_t q = 0; q < n; ++q) {
    double smooth = m.mean;
    for (int h = 1; h <= kept; ++h)
      smooth += 2 * (a[static_cast<std::size_t>(h)] *
                     std::polar(1.0, 2 * pi * h * static_cast<double>(q) / static_cast<double>(n)))
                        .real();
    rss += (c[first + q] - smooth) * (c[first + q] - smooth);
  }
  m.noise = std::sqrt(rss / static_cast<double>(n));
  return m;
}
}  // namespace

SpanwisePlateResult run_spanwise_plate(const SpanwisePlateSetup& s) {
  if (!(s.re > 0) || !(s.period > 0) || !(s.heave >= 0) || !(s.pitch >= 0) || s.cells_per_chord < 8 ||
      !(s.thickness_cells > 0) || s.span_cells < 1 || s.overhang_cells < 1 || s.periods < 1 ||
      !(s.ramp_periods >= 0) || s.ramp_periods > s.periods - 1 || !(s.cfl > 0) || s.frames_per_period < 8)
    throw Error("spanwise plate: need re, period > 0, heave, pitch >= 0, cells_per_chord >= 8, thickness_cells > 0, "
                "span_cells, overhang_cells >= 1, 0 <= ramp_periods <= periods - 1, cfl > 0, frames_per_period >= 8");
  SpanwisePlateResult r;
  const double h = 1.0 / s.cells_per_chord, t = s.thickness_cells * h;
  r.h = h;
  r.thickness = t;
  r.span = s.span_cells * h;
  r.steps_per_period = std::max(20L, static_cast<long>(std::ceil(s.period / (s.cfl * h))));
  r.dt = s.period / static_cast<double>(r.steps_per_period);
  r.steps = r.steps_per_period * s.periods;
  // The box covers the pitched plate's path: |y| <= h0 + (c - pivot) sin(theta0) + t/2.
  const double ylim = s.heave + std::max(s.pivot, 1 - s.pivot) * std::sin(s.pitch) + t / 2 + s.box_margin;
  if (!(s.half_height > 1.5 * ylim)) throw Error("spanwise plate: half_height must exceed 1.5 x the plate's path");
  // One x-y grid for both runs.
  using validation::multigrid_axis;
  const Axis ax = multigrid_axis(-s.upstream, 1 + s.downstream, -s.box_margin, 1 + s.box_behind, h, s.stretch_ratio);
  const Axis ay = multigrid_axis(-s.half_height, s.half_height, -ylim, ylim, h, s.stretch_ratio);
  // The plate's span runs from 0 to span + 2 overhang; the slab sits in its middle.
  const double z0 = s.overhang_cells * h;
  const Axis az = Axis::uniform(z0, z0 + r.span, s.span_cells);

  FlowOptions opt;
  opt.nu = 1.0 / s.re;
  opt.dt = r.dt;
  opt.helmholtz_rtol = 1e-10;
  opt.poisson.rtol = 1e-9;
  opt.cut_cell_continuity = !s.staircase;
  FlowBoundary b;
  b[Side::XLo].type = FlowBcType::Inlet;
  b[Side::XLo].speed = 1.0;
  b[Side::XHi].type = FlowBcType::ConvectiveOutlet;
  // The y walls slide with the stream (no boundary layer of their own); the z sides are slip walls,
  // symmetry planes of the spanwise-uniform flow.
  b[Side::YLo].wall_velocity = {1, 0, 0};
  b[Side::YHi].wall_velocity = {1, 0, 0};
  b[Side::ZLo].type = FlowBcType::Slip;
  b[Side::ZHi].type = FlowBcType::Slip;

  const auto march = [&](FlowSolver& solver, SpanwisePlateRun& q, const std::string& tag, bool record_time,
                         const std::function<std::array<double, 2>()>& force) {
    for (long n = 0; n < r.steps; ++n) {
      StepStats st;
      try {
        st = solver.step();
      } catch (const Error& e) {
        q.failed = true;
        q.error = e.what();
        return;
      }
      q.max_cfl = std::max(q.max_cfl, st.cfl);
      q.max_divergence = std::max(q.max_divergence, st.max_divergence);
      if (record_time) r.time.push_back(st.time);
      const auto f = force();
      q.cx.push_back(f[0]);
      q.cy.push_back(f[1]);
      if (s.progress) s.progress(tag, st);
    }
  };
  const auto summarise = [&](SpanwisePlateRun& q) {
    if (q.failed) {
      q.mean_ct = q.cl_amplitude = q.mean_cl = q.cx_noise = q.cy_noise = std::nan("");
      return;
    }
    const auto N = static_cast<std::size_t>(r.steps_per_period), first = static_cast<std::size_t>(r.steps) - N;
    const PeriodMeasures x = measure(q.cx, first, N), y = measure(q.cy, first, N);
    q.mean_ct = -x.mean;
    q.cx_noise = x.noise;
    q.mean_cl = y.mean;
    q.cl_amplitude = y.amplitude;
    q.cy_noise = y.noise;
  };

  // 2-D: the section as a rigid polygon.
  {
    const auto t0 = std::chrono::steady_clock::now();
    const StretchedGrid g(ax, ay);
    r.flat.cells = static_cast<long>(g.cells());
    FlowSolver solver;
    solver.setup(g, b, opt);
    const Polygon section({{0, -t / 2}, {1, -t / 2}, {1, t / 2}, {0, t / 2}});
    solver.immerse(MovingBody{section, {s.pivot, 0}, [&s](double time) {
                                const Pose p = pose(s, time);
                                RigidState st;
                                st.displacement = {0, p.y};
                                st.velocity = {0, p.dy};
                                st.acceleration = {0, p.ddy};
                                st.angle = p.th;
                                st.angular_velocity = p.dth;
                                st.angular_acceleration = p.ddth;
                                return st;
                              }});
    solver.initialise([](double, double, double, double) { return std::array<double, 3>{1, 0, 0}; });
    march(solver, r.flat, "2-D", true, [&] {
      const MovingBody& body = *solver.moving_body();
      const SurfaceTraction tr(solver.grid(), *solver.immersed(), solver.body_polygon());
      const SurfaceLoads l = tr.evaluate(solver.u(0), solver.u(1), solver.p(), opt.nu, 1.0, [&](double x, double y) {
        return body.velocity(solver.body_state(), x, y);
      });
      // rho = U = c = 1: coefficient = 2 F per unit depth.
      return std::array<double, 2>{2 * l.force[0], 2 * l.force[1]};
    });
    summarise(r.flat);
    r.flat.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }

  // 3-D: the fin's path, from the mid-surface and sampled node positions as fin-cfd fin reads them.
  {
    const auto t0 = std::chrono::steady_clock::now();
    io::ThinPlateSetup ps;
    ps.chord = 1;
    ps.span = r.span + 2 * z0;
    ps.nx = s.cells_per_chord;
    ps.nz = s.span_cells + 2 * s.overhang_cells;
    ps.thickness = t;
    ps.pivot = s.pivot;
    ps.period = s.period;
    io::ThinPlateFiles files = io::make_thin_plate(ps);
    // make_thin_plate's periodic motion has no smooth start: the frames are resampled here with
    // this case's pose (the same as the 2-D body's), not periodic, a quarter period past the end so
    // that the natural spline's end condition stays out of the run.
    const auto nv = files.mesh.points.dim(0);
    const double frame_dt = s.period / s.frames_per_period;
    const auto nf = static_cast<std::size_t>(std::ceil((s.periods + 0.25) * s.frames_per_period)) + 1;
    stage::Motion& m = files.motion;
    m.time = NdArray<double>({nf});
    m.points = NdArray<double>({nf, nv, 3});
    m.velocity = NdArray<double>();
    m.period.reset();
    for (std::size_t k = 0; k < nf; ++k) {
      const double time = frame_dt * static_cast<double>(k);
      m.time(k) = time;
      const Pose p = pose(s, time);
      for (std::size_t i = 0; i < nv; ++i) {
        const double rx = files.mesh.points(i, 0) - s.pivot;
        m.points(k, i, 0) = s.pivot + rx * std::cos(p.th);
        m.points(k, i, 1) = p.y + rx * std::sin(p.th);
        m.points(k, i, 2) = files.mesh.points(i, 2);
      }
    }
    const io::FinInput in = io::make_fin_input(files.mesh, files.motion, "spanwise plate mesh", "spanwise plate motion");
    const StretchedGrid g(ax, ay, az);
    r.slab.cells = static_cast<long>(g.cells());
    FlowOptions o3 = opt;
    o3.cut_cell_continuity_3d = !s.staircase;  // on: as fin-cfd fin (FinFlowOptions::cut_cells)
    o3.surface_crosses = {false, false, true};
    FlowSolver solver;
    solver.setup(g, b, o3);
    solver.immerse(FinSurfaceMotion::as_surface_motion(in.motion));
    solver.initialise([](double, double, double, double) { return std::array<double, 3>{1, 0, 0}; });
    march(solver, r.slab, "3-D", false, [&] {
      const SurfaceForces f = solver.surface_forces(1.0);
      return std::array<double, 2>{2 * f.total[0] / r.span, 2 * f.total[1] / r.span};
    });
    summarise(r.slab);
    r.slab.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  return r;
}

}  // namespace finverse::cfd
