// Towed and in-line oscillating cylinder drivers; see moving_cylinder.hpp.
#include "cfd/validation/moving_cylinder.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>

#include "cfd/forces/surface_traction.hpp"
#include "core/error.hpp"

namespace finverse::cfd {

namespace {
// Cell counts that are multiples of 8 keep three halvings for the multigrid.
int round_up8(int n) { return std::max(8, 8 * ((n + 7) / 8)); }

Axis axis(double lo, double hi, double ulo, double uhi, double h) {
  constexpr double ratio = 1.05;
  return Axis::stretched_count(lo, hi, ulo, uhi, round_up8(Axis::stretched(lo, hi, ulo, uhi, h, ratio).size()), ratio);
}

// In-line force per unit depth (rho = 1) on the solver's moving body, or on fixed_body at rest.
double force_x(const FlowSolver& s, const Polygon* fixed_body = nullptr) {
  const FlowOptions& o = s.options();
  if (const MovingBody* b = s.moving_body()) {
    const SurfaceTraction tr(s.grid(), *s.immersed(), s.body_polygon());
    return tr.evaluate(s.u(0), s.u(1), s.p(), o.nu, 1.0, [&](double x, double y) {
                return b->velocity(s.body_state(), x, y);
              }).force[0];
  }
  const SurfaceTraction tr(s.grid(), *s.immersed(), *fixed_body);
  return tr.evaluate(s.u(0), s.u(1), s.p(), o.nu, 1.0).force[0];
}
}  // namespace

TowedCylinderResult run_towed_cylinder(const TowedCylinderSetup& ts) {
  if (ts.cells_per_diameter < 4 || !(ts.t_end > ts.t_compare) || !(ts.re > 0) || ts.fixed_offsets < 1)
    throw Error("towed cylinder: need cells_per_diameter >= 4, t_end > t_compare, re > 0, fixed_offsets >= 1");
  const auto t0 = std::chrono::steady_clock::now();
  const double h = 1.0 / ts.cells_per_diameter, path = ts.t_end, H = ts.half_height;
  FlowOptions opt;
  opt.nu = 1.0 / ts.re;
  opt.dt = ts.cfl * h;
  opt.coupling_time = ts.coupling_fraction * opt.dt;
  opt.helmholtz_rtol = 1e-10;
  opt.poisson.rtol = 1e-9;
  opt.cut_cell_continuity = ts.cut_cell_continuity;
  const Polygon circle = Polygon::circle(0, 0, 0.5, ts.polygon_vertices);

  // Towed: the body starts at x = 0 and travels to -path; closed box at rest.
  const StretchedGrid gt(axis(-path - 1 - H, 1 + H, -path - 1, 1, h), axis(-H, H, -1, 1, h));
  FlowSolver towed;
  towed.setup(gt, FlowBoundary{}, opt);
  towed.immerse(MovingBody{circle, {0, 0}, [](double t) {
                             RigidState s;
                             s.displacement = {-t, 0};
                             s.velocity = {-1, 0};
                             return s;
                           }});
  towed.initialise({});

  // Fixed: the mirror-image grid (the wake in the uniform core), stream U = 1; one cylinder per
  // sub-cell position along the stream (its centre on a grid vertex, then shifted by k/n of the
  // cell width there), as the towed body passes through all of them.
  const StretchedGrid gf(axis(-1 - H, path + 1 + H, -1, path + 1, h), axis(-H, H, -1, 1, h));
  FlowBoundary b;
  b[Side::XLo].type = FlowBcType::Inlet;
  b[Side::XLo].speed = 1.0;
  b[Side::XHi].type = FlowBcType::ConvectiveOutlet;
  b[Side::YLo].wall_velocity = {1, 0, 0};
  b[Side::YHi].wall_velocity = {1, 0, 0};
  const auto& fx_faces = gf.axis(0).faces();
  auto vertex = std::lower_bound(fx_faces.begin(), fx_faces.end(), 0.0);  // the face nearest to x = 0
  if (vertex != fx_faces.begin() && std::abs(*(vertex - 1)) < std::abs(*vertex)) --vertex;
  const double x0 = *vertex, dx = *(vertex + 1) - x0;
  std::vector<Polygon> bodies;
  std::vector<std::unique_ptr<FlowSolver>> fixed;
  for (int k = 0; k < ts.fixed_offsets; ++k) {
    bodies.push_back(Polygon::circle(x0 + k * dx / ts.fixed_offsets, 0, 0.5, ts.polygon_vertices));
    fixed.push_back(std::make_unique<FlowSolver>());
    fixed.back()->setup(gf, b, opt);
    // The same discretisation at rest: with the cut-cell mass balance (a moving body's) the fixed
    // cylinder is a moving body with zero motion, so that what is compared is the motion alone.
    if (opt.cut_cell_continuity)
      fixed.back()->immerse(MovingBody{bodies.back(), {0, 0}, [](double) { return RigidState{}; }});
    else
      fixed.back()->immerse(bodies.back());
    fixed.back()->initialise([](double, double, double, double) { return std::array<double, 3>{1, 0, 0}; });
  }

  TowedCylinderResult r;
  r.cells = static_cast<long>(gt.cells() + gf.cells() * static_cast<std::size_t>(ts.fixed_offsets));
  std::vector<std::vector<double>> cd_each(fixed.size());
  while (towed.time() < ts.t_end - 1e-9) {
    const StepStats st = towed.step();
    double mean = 0;
    for (std::size_t k = 0; k < fixed.size(); ++k) {
      fixed[k]->step();
      cd_each[k].push_back(2 * force_x(*fixed[k], &bodies[k]));
      mean += cd_each[k].back() / static_cast<double>(fixed.size());
    }
    ++r.steps;
    r.time.push_back(st.time);
    r.cd_towed.push_back(2 * force_x(towed));
    r.cd_fixed.push_back(mean);
    r.cd_fixed_vertex.push_back(cd_each[0].back());
    if (ts.progress) ts.progress(st);
  }
  // The body crosses filter_cells cells in filter_cells / cfl steps.
  const std::size_t w = static_cast<std::size_t>(std::max(1L, std::lround(ts.filter_cells / ts.cfl)));
  const auto average = [&](const std::vector<double>& q, std::size_t n) {
    double a = 0;
    for (std::size_t m = n + 1 - w; m <= n; ++m) a += q[m];
    return a / static_cast<double>(w);
  };
  for (std::size_t n = 0; n < r.time.size(); ++n) {
    if (r.time[n] < ts.t_compare || n + 1 < w) continue;
    r.max_relative_difference_raw = std::max(r.max_relative_difference_raw,
                                             std::abs(r.cd_towed[n] - r.cd_fixed[n]) / std::abs(r.cd_fixed[n]));
    r.cd_towed_end = average(r.cd_towed, n);
    r.cd_fixed_end = average(r.cd_fixed, n);
    r.cd_fixed_vertex_end = average(r.cd_fixed_vertex, n);
    r.max_relative_difference =
        std::max(r.max_relative_difference, std::abs(r.cd_towed_end - r.cd_fixed_end) / std::abs(r.cd_fixed_end));
    r.max_relative_difference_vertex = std::max(
        r.max_relative_difference_vertex, std::abs(r.cd_towed_end - r.cd_fixed_vertex_end) / std::abs(r.cd_fixed_vertex_end));
  }
  if (r.time.size() >= w) {
    double lo = 1e300, hi = -1e300;
    for (const auto& c : cd_each) {
      const double a = average(c, r.time.size() - 1);
      lo = std::min(lo, a);
      hi = std::max(hi, a);
    }
    r.fixed_position_spread = (hi - lo) / std::abs(r.cd_fixed_end);
  }
  r.cpu_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

OscillatingCylinderResult run_oscillating_cylinder(const OscillatingCylinderSetup& os) {
  if (os.cells_per_diameter < 4 || os.steps_per_period < 20 || os.periods < 1 || os.periods_analysed < 1 ||
      os.periods_analysed > os.periods || !(os.kc > 0) || !(os.re > 0))
    throw Error("oscillating cylinder: invalid setup (cells, steps per period >= 20, periods, kc, re)");
  const auto t0 = std::chrono::steady_clock::now();
  constexpr double pi = std::numbers::pi;
  const double h = 1.0 / os.cells_per_diameter, T = os.kc, w = 2 * pi / T, A = 1.0 / w, W = os.half_width;
  FlowOptions opt;
  opt.nu = 1.0 / os.re;
  opt.dt = T / os.steps_per_period;
  opt.helmholtz_rtol = 1e-10;
  opt.poisson.rtol = 1e-9;
  opt.fresh_cell_treatment = os.fresh_cell_treatment;
  opt.cut_cell_continuity = os.cut_cell_continuity;
  const StretchedGrid g(axis(-W, W, -A - 1, A + 1, h), axis(-W, W, -1.5, 1.5, h));
  FlowSolver s;
  s.setup(g, FlowBoundary{}, opt);
  s.immerse(MovingBody{Polygon::circle(0, 0, 0.5, os.polygon_vertices), {0, 0}, [=](double t) {
                         RigidState st;
                         st.displacement = {-A * std::sin(w * t), 0};
                         st.velocity = {-A * w * std::cos(w * t), 0};
                         st.acceleration = {A * w * w * std::sin(w * t), 0};
                         return st;
                       }});
  s.initialise({});
  OscillatingCylinderResult r;
  const long n_total = static_cast<long>(os.periods) * os.steps_per_period;
  for (long n = 0; n < n_total; ++n) {
    const StepStats st = s.step();
    r.max_continuity_residual = std::max(r.max_continuity_residual, st.max_divergence);
    r.cleared_cells += static_cast<long>(s.freshly_cleared().size());
    r.time.push_back(st.time);
    r.fx.push_back(force_x(s));
  }
  r.steps = n_total;
  // Analysis window: the last periods_analysed periods (a whole number: no leakage at f).
  const std::size_t m = static_cast<std::size_t>(os.periods_analysed) * static_cast<std::size_t>(os.steps_per_period);
  const std::size_t first = r.fx.size() - m;
  std::vector<double> f(r.fx.begin() + static_cast<long>(first), r.fx.end());
  double mean = 0, fmax = 0;
  for (double v : f) mean += v / static_cast<double>(m);
  for (double& v : f) {
    fmax = std::max(fmax, std::abs(v));
    v -= mean;
  }
  double total = 0, high = 0;
  const std::size_t k_cut = 10 * static_cast<std::size_t>(os.periods_analysed);
  for (std::size_t k = 1; k <= m / 2; ++k) {
    double re = 0, im = 0;
    for (std::size_t n = 0; n < m; ++n) {
      const double a = 2 * pi * static_cast<double>(k * n % m) / static_cast<double>(m);
      re += f[n] * std::cos(a);
      im -= f[n] * std::sin(a);
    }
    const double e = re * re + im * im;
    total += e;
    if (k > k_cut) high += e;
  }
  r.high_frequency_fraction = total > 0 ? high / total : 0;
  for (std::size_t n = first + 1; n + 1 < r.fx.size(); ++n)
    r.max_second_difference = std::max(r.max_second_difference, std::abs(r.fx[n + 1] - 2 * r.fx[n] + r.fx[n - 1]));
  r.max_second_difference /= std::max(fmax, 1e-300);
  // Morison-type fit over the window: F = a u|u| + b du/dt at the step's time level.
  double s11 = 0, s12 = 0, s22 = 0, r1 = 0, r2 = 0;
  for (std::size_t n = first; n < r.fx.size(); ++n) {
    const double t = r.time[n], u = -A * w * std::cos(w * t), du = A * w * w * std::sin(w * t);
    const double x1 = u * std::abs(u), x2 = du;
    s11 += x1 * x1;
    s12 += x1 * x2;
    s22 += x2 * x2;
    r1 += x1 * r.fx[n];
    r2 += x2 * r.fx[n];
  }
  const double det = s11 * s22 - s12 * s12;
  if (det > 0) {
    const double a = (r1 * s22 - r2 * s12) / det, b = (s11 * r2 - s12 * r1) / det;
    r.cd_morison = -2 * a;         // rho = D = 1
    r.ca_morison = -b / (pi / 4);
  }
  r.cpu_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace finverse::cfd
