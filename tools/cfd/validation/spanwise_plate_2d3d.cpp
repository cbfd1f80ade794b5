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
// The four runs in named steps: set up the shared grid axes and boundary, then each run marches
// the same steps and measures its last period.
class SpanwisePlate {
 public:
  explicit SpanwisePlate(const SpanwisePlateSetup& s);
  SpanwisePlateResult run();

 private:
  void march(FlowSolver& solver, SpanwisePlateRun& q, const std::string& tag,
             const std::function<std::array<double, 2>()>& force);
  void summarise(SpanwisePlateRun& q) const;
  void flat_closed(SpanwisePlateRun& q);
  void slab_closed(SpanwisePlateRun& q);
  void flat_sheet(SpanwisePlateRun& q);
  void slab_sheet(SpanwisePlateRun& q);
  void run_sheet(SpanwisePlateRun& q, const std::string& tag, const StretchedGrid& g, const FlowBoundary& b,
                 const SheetTopology& topo, const std::vector<Vec3>& rest, double span);
  SheetForcingOptions sheet_options() const {
    SheetForcingOptions o;
    o.band_correction = !s_.raw_sheet_force;
    return o;
  }
  // The sheet's nodes at time t: rest positions (x, 0, z) under the pose, with velocities.
  SheetState sheet_state(const std::vector<Vec3>& rest, double t) const;

  const SpanwisePlateSetup& s_;
  SpanwisePlateResult r_;
  Axis ax_, ay_;
  FlowOptions opt_;
  FlowBoundary b_;
};

SpanwisePlate::SpanwisePlate(const SpanwisePlateSetup& s) : s_(s) {
  if (!(s.re > 0) || !(s.period > 0) || !(s.heave >= 0) || !(s.pitch >= 0) || s.cells_per_chord < 8 ||
      !(s.thickness_cells > 0) || s.span_cells < 1 || s.overhang_cells < 1 || s.periods < 1 ||
      !(s.ramp_periods >= 0) || s.ramp_periods > s.periods - 1 || !(s.cfl > 0) || s.frames_per_period < 8)
    throw Error("spanwise plate: need re, period > 0, heave, pitch >= 0, cells_per_chord >= 8, thickness_cells > 0, "
                "span_cells, overhang_cells >= 1, 0 <= ramp_periods <= periods - 1, cfl > 0, frames_per_period >= 8");
  if (s.sheet && s.span_cells < 4) throw Error("spanwise plate: the periodic sheet slab needs span_cells >= 4");
  const double h = 1.0 / s.cells_per_chord, t = s.thickness_cells * h;
  r_.h = h;
  r_.thickness = t;
  r_.span = s.span_cells * h;
  r_.steps_per_period = std::max(20L, static_cast<long>(std::ceil(s.period / (s.cfl * h))));
  r_.dt = s.period / static_cast<double>(r_.steps_per_period);
  r_.steps = r_.steps_per_period * s.periods;
  // The box covers the pitched plate's path: |y| <= h0 + (c - pivot) sin(theta0) + t/2.
  const double ylim = s.heave + std::max(s.pivot, 1 - s.pivot) * std::sin(s.pitch) + t / 2 + s.box_margin;
  if (!(s.half_height > 1.5 * ylim)) throw Error("spanwise plate: half_height must exceed 1.5 x the plate's path");
  // One x-y grid for every run.
  using validation::multigrid_axis;
  ax_ = multigrid_axis(-s.upstream, 1 + s.downstream, -s.box_margin, 1 + s.box_behind, h, s.stretch_ratio);
  ay_ = multigrid_axis(-s.half_height, s.half_height, -ylim, ylim, h, s.stretch_ratio);
  opt_.nu = 1.0 / s.re;
  opt_.dt = r_.dt;
  opt_.helmholtz_rtol = 1e-10;
  opt_.poisson.rtol = 1e-9;
  opt_.cut_cell_continuity = !s.staircase;
  b_[Side::XLo].type = FlowBcType::Inlet;
  b_[Side::XLo].speed = 1.0;
  b_[Side::XHi].type = FlowBcType::ConvectiveOutlet;
  // The y walls slide with the stream (no boundary layer of their own); the z sides are slip walls
  // (the closed slab) or periodic (the sheet's slab), both spanwise-uniform flow.
  b_[Side::YLo].wall_velocity = {1, 0, 0};
  b_[Side::YHi].wall_velocity = {1, 0, 0};
  b_[Side::ZLo].type = FlowBcType::Slip;
  b_[Side::ZHi].type = FlowBcType::Slip;
}

SpanwisePlateResult SpanwisePlate::run() {
  if (s_.closed) {
    flat_closed(r_.flat);
    slab_closed(r_.slab);
  }
  if (s_.sheet) {
    flat_sheet(r_.flat_sheet);
    slab_sheet(r_.slab_sheet);
  }
  return r_;
}

void SpanwisePlate::march(FlowSolver& solver, SpanwisePlateRun& q, const std::string& tag,
                          const std::function<std::array<double, 2>()>& force) {
  const auto t0 = std::chrono::steady_clock::now();
  q.ran = true;
  for (long n = 0; n < r_.steps && !q.failed; ++n) {
    StepStats st;
    try {
      st = solver.step();
    } catch (const Error& e) {
      q.failed = true;
      q.error = e.what();
      break;
    }
    q.max_cfl = std::max(q.max_cfl, st.cfl);
    q.max_divergence = std::max(q.max_divergence, st.max_divergence);
    if (static_cast<long>(r_.time.size()) == n) r_.time.push_back(st.time);  // the longest run's times
    const auto f = force();
    q.cx.push_back(f[0]);
    q.cy.push_back(f[1]);
    if (s_.progress) s_.progress(tag, st);
  }
  summarise(q);
  q.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void SpanwisePlate::summarise(SpanwisePlateRun& q) const {
  if (q.failed) {
    q.mean_ct = q.cl_amplitude = q.mean_cl = q.cx_noise = q.cy_noise = std::nan("");
    return;
  }
  const auto N = static_cast<std::size_t>(r_.steps_per_period), first = static_cast<std::size_t>(r_.steps) - N;
  const PeriodMeasures x = measure(q.cx, first, N), y = measure(q.cy, first, N);
  q.mean_ct = -x.mean;
  q.cx_noise = x.noise;
  q.mean_cl = y.mean;
  q.cl_amplitude = y.amplitude;
  q.cy_noise = y.noise;
}

// 2-D, closed: the section as a rigid polygon.
void SpanwisePlate::flat_closed(SpanwisePlateRun& q) {
  const double t = r_.thickness;
  const StretchedGrid g(ax_, ay_);
  q.cells = static_cast<long>(g.cells());
  FlowSolver solver;
  solver.setup(g, b_, opt_);
  const Polygon section({{0, -t / 2}, {1, -t / 2}, {1, t / 2}, {0, t / 2}});
  solver.immerse(MovingBody{section, {s_.pivot, 0}, [this](double time) {
                              const Pose p = pose(s_, time);
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
  march(solver, q, "2-D closed", [&] {
    const MovingBody& body = *solver.moving_body();
    const SurfaceTraction tr(solver.grid(), *solver.immersed(), solver.body_polygon());
    const SurfaceLoads l = tr.evaluate(solver.u(0), solver.u(1), solver.p(), opt_.nu, 1.0,
                                       [&](double x, double y) { return body.velocity(solver.body_state(), x, y); });
    // rho = U = c = 1: coefficient = 2 F per unit depth.
    return std::array<double, 2>{2 * l.force[0], 2 * l.force[1]};
  });
}

// 3-D, closed: the fin's path, from the mid-surface and sampled node positions as fin-cfd fin
// reads them; the plate reaches overhang_cells beyond both slip walls.
void SpanwisePlate::slab_closed(SpanwisePlateRun& q) {
  const double h = r_.h, z0 = s_.overhang_cells * h;
  io::ThinPlateSetup ps;
  ps.chord = 1;
  ps.span = r_.span + 2 * z0;
  ps.nx = s_.cells_per_chord;
  ps.nz = s_.span_cells + 2 * s_.overhang_cells;
  ps.thickness = r_.thickness;
  ps.pivot = s_.pivot;
  ps.period = s_.period;
  io::ThinPlateFiles files = io::make_thin_plate(ps);
  // make_thin_plate's periodic motion has no smooth start: the frames are resampled here with
  // this case's pose (the same as the 2-D body's), not periodic, a quarter period past the end so
  // that the natural spline's end condition stays out of the run.
  const auto nv = files.mesh.points.dim(0);
  const double frame_dt = s_.period / s_.frames_per_period;
  const auto nf = static_cast<std::size_t>(std::ceil((s_.periods + 0.25) * s_.frames_per_period)) + 1;
  stage::Motion& m = files.motion;
  m.time = NdArray<double>({nf});
  m.points = NdArray<double>({nf, nv, 3});
  m.velocity = NdArray<double>();
  m.period.reset();
  for (std::size_t k = 0; k < nf; ++k) {
    const double time = frame_dt * static_cast<double>(k);
    m.time(k) = time;
    const Pose p = pose(s_, time);
    for (std::size_t i = 0; i < nv; ++i) {
      const double rx = files.mesh.points(i, 0) - s_.pivot;
      m.points(k, i, 0) = s_.pivot + rx * std::cos(p.th);
      m.points(k, i, 1) = p.y + rx * std::sin(p.th);
      m.points(k, i, 2) = files.mesh.points(i, 2);
    }
  }
  const io::FinInput in = io::make_fin_input(files.mesh, files.motion, "spanwise plate mesh", "spanwise plate motion");
  const StretchedGrid g(ax_, ay_, Axis::uniform(z0, z0 + r_.span, s_.span_cells));
  q.cells = static_cast<long>(g.cells());
  FlowOptions o3 = opt_;
  o3.cut_cell_continuity_3d = !s_.staircase;  // on: as fin-cfd fin (FinFlowOptions::cut_cells)
  o3.surface_crosses = {false, false, true};
  FlowSolver solver;
  solver.setup(g, b_, o3);
  solver.immerse(FinSurfaceMotion::as_surface_motion(in.motion));
  solver.initialise([](double, double, double, double) { return std::array<double, 3>{1, 0, 0}; });
  march(solver, q, "3-D closed", [&] {
    const SurfaceForces f = solver.surface_forces(1.0);
    return std::array<double, 2>{2 * f.total[0] / r_.span, 2 * f.total[1] / r_.span};
  });
}

SheetState SpanwisePlate::sheet_state(const std::vector<Vec3>& rest, double t) const {
  const Pose p = pose(s_, t);
  const double c = std::cos(p.th), sn = std::sin(p.th);
  SheetState st;
  for (const Vec3& x : rest) {
    const double rx = x[0] - s_.pivot;
    st.position.push_back({s_.pivot + rx * c, p.y + rx * sn, x[2]});
    st.velocity.push_back({-rx * sn * p.dth, p.dy + rx * c * p.dth, 0});
  }
  return st;
}

// 2-D, sheet: the section's mid-line, one node per cell along the chord.
void SpanwisePlate::flat_sheet(SpanwisePlateRun& q) {
  const int n = s_.cells_per_chord;
  SheetTopology topo{2, static_cast<std::size_t>(n + 1), {}};
  std::vector<Vec3> rest;
  for (int i = 0; i <= n; ++i) {
    rest.push_back({static_cast<double>(i) / n, 0, 0});
    if (i < n) topo.elements.push_back({i, i + 1, -1});
  }
  run_sheet(q, "2-D sheet", StretchedGrid(ax_, ay_), b_, topo, rest, 1.0);
}

// 3-D, sheet: the mid-surface from seam to seam of a z-periodic slab (nodes on both seams, one row
// of markers there), the same nodes along the chord as the 2-D sheet.
void SpanwisePlate::slab_sheet(SpanwisePlateRun& q) {
  const int n = s_.cells_per_chord, nz = s_.span_cells;
  const double z0 = s_.overhang_cells * r_.h;
  SheetTopology topo{3, static_cast<std::size_t>((n + 1) * (nz + 1)), {}};
  std::vector<Vec3> rest;
  const auto node = [n](int i, int k) { return k * (n + 1) + i; };
  for (int k = 0; k <= nz; ++k)
    for (int i = 0; i <= n; ++i) rest.push_back({static_cast<double>(i) / n, 0, z0 + r_.span * k / nz});
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < n; ++i) {
      topo.elements.push_back({node(i, k), node(i + 1, k), node(i + 1, k + 1)});
      topo.elements.push_back({node(i, k), node(i + 1, k + 1), node(i, k + 1)});
    }
  FlowBoundary b = b_;
  b[Side::ZLo].type = FlowBcType::Periodic;
  b[Side::ZHi].type = FlowBcType::Periodic;
  run_sheet(q, "3-D sheet", StretchedGrid(ax_, ay_, Axis::uniform(z0, z0 + r_.span, nz)), b, topo, rest, r_.span);
}

// One sheet run: the sheet moved by the pose from an impulsive start in the stream, its force per
// unit span (span 1 in 2-D) as coefficients.
void SpanwisePlate::run_sheet(SpanwisePlateRun& q, const std::string& tag, const StretchedGrid& g,
                              const FlowBoundary& b, const SheetTopology& topo, const std::vector<Vec3>& rest,
                              double span) {
  q.cells = static_cast<long>(g.cells());
  FlowSolver solver;
  solver.setup(g, b, opt_);
  solver.immerse_sheet(topo, rest, sheet_options(), [this, rest](double t) { return sheet_state(rest, t); });
  solver.initialise([](double, double, double, double) { return std::array<double, 3>{1, 0, 0}; });
  march(solver, q, tag, [&] {
    const Vec3 F = solver.sheet_loads(1.0).total;
    return std::array<double, 2>{2 * F[0] / span, 2 * F[1] / span};
  });
}

}  // namespace

SpanwisePlateResult run_spanwise_plate(const SpanwisePlateSetup& setup) { return SpanwisePlate(setup).run(); }

}  // namespace finverse::cfd
