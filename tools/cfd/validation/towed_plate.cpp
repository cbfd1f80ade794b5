// Towed against fixed flat plate, the sheet and the closed body (see towed_plate.hpp).
#include "cfd/validation/towed_plate.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <memory>
#include <numbers>

#include "cfd/flow/flow_solver.hpp"
#include "cfd/forces/surface_traction.hpp"
#include "cfd/immersed/rigid_motion.hpp"
#include "core/error.hpp"

namespace finverse::cfd::validation {
namespace {

constexpr double kLeadingEdge = 2.53;  // x of the plate's leading edge at t = 0 (off the grid's lines)

struct Geometry {
  double ca, sa;  // cos, sin of the incidence
};

// The sheet: the mid-line in 8 segments, trailing edge below the leading edge (positive incidence
// against a stream along +x).
void immerse_sheet(FlowSolver& f, const TowedPlateSetup& s, const Geometry& g, bool towed) {
  SheetTopology t{2, 9, {}};
  std::vector<Vec3> rest;
  for (int k = 0; k <= 8; ++k) {
    const double xi = k / 8.0;
    rest.push_back({kLeadingEdge + xi * g.ca, -xi * g.sa, 0});
    if (k < 8) t.elements.push_back({k, k + 1, -1});
  }
  SheetMotion m = [rest](double) { return SheetState{rest, {}}; };
  if (towed)
    m = [rest](double time) {
      SheetState st{rest, std::vector<Vec3>(rest.size(), Vec3{-1, 0, 0})};
      for (Vec3& x : st.position) x[0] -= time;
      return st;
    };
  f.immerse_sheet(t, rest, s.sheet, m);
}

// The closed body: a rectangle of the chord and two cells' thickness around the same mid-line.
Polygon closed_plate(const Geometry& g, double thickness) {
  const double nx = g.sa, ny = g.ca, e = 0.5 * thickness;  // unit normal of the mid-line
  const std::array<double, 2> le{kLeadingEdge, 0}, te{kLeadingEdge + g.ca, -g.sa};
  return Polygon({{le[0] - e * nx, le[1] - e * ny},
                  {te[0] - e * nx, te[1] - e * ny},
                  {te[0] + e * nx, te[1] + e * ny},
                  {le[0] + e * nx, le[1] + e * ny}});
}

std::array<double, 2> closed_force(const FlowSolver& f) {
  const MovingBody* b = f.moving_body();
  const SurfaceTraction tr(f.grid(), *f.immersed(), f.body_polygon());
  const auto F = tr.evaluate(f.u(0), f.u(1), f.p(), f.options().nu, 1.0, [&](double x, double y) {
                     return b->velocity(f.body_state(), x, y);
                   }).force;
  return {F[0], F[1]};
}

// One run: the force coefficients after every step.
void run_one(const TowedPlateSetup& s, bool sheet, bool towed, std::vector<double>& cd, std::vector<double>& cl,
             std::vector<double>* time, long& steps, std::size_t& cells, std::size_t& markers) {
  const double h = 1.0 / s.cells_per_chord;
  const StretchedGrid grid(Axis::uniform(0, 4, 4 * s.cells_per_chord), Axis::uniform(-1, 1, 2 * s.cells_per_chord));
  const double a = s.incidence_deg * std::numbers::pi / 180;
  const Geometry g{std::cos(a), std::sin(a)};
  FlowOptions opt;
  opt.nu = 1.0 / s.re;
  opt.dt = s.cfl * h;
  opt.poisson.rtol = 1e-10;
  FlowSolver f;
  f.setup(grid, FlowBoundary::all_periodic(), opt);
  if (sheet) {
    immerse_sheet(f, s, g, towed);
    markers = f.sheet()->size();
  } else {
    const double U = towed ? -1.0 : 0.0;
    f.immerse(MovingBody{closed_plate(g, 2 * h), {kLeadingEdge, 0}, [U](double t) {
                           RigidState r;
                           r.displacement = {U * t, 0};
                           r.velocity = {U, 0};
                           return r;
                         }});
  }
  const double U = towed ? 0.0 : 1.0;
  f.initialise([U](double, double, double, double) { return std::array<double, 3>{U, 0, 0}; });
  const long n = std::lround(s.t_end / opt.dt);
  for (long k = 0; k < n; ++k) {
    f.step();
    std::array<double, 2> F{};
    if (sheet) {
      const Vec3 t = f.sheet_loads().total;
      F = {t[0], t[1]};
    } else {
      F = closed_force(f);
    }
    cd.push_back(2 * F[0]);
    cl.push_back(2 * F[1]);
    if (time) time->push_back(f.time());
  }
  steps = n;
  cells = grid.cells();
}

void compare(const TowedPlateSetup& s, const std::vector<double>& time, TowedPlatePair& p) {
  double scale = 0, diff = 0, kt = 0, kf = 0;
  const std::size_t n = time.size();
  for (std::size_t k = 1; k + 1 < n; ++k) {
    if (time[k] < s.t_compare) continue;
    for (const auto& [fixed, towed] : {std::pair{&p.cd_fixed, &p.cd_towed}, std::pair{&p.cl_fixed, &p.cl_towed}}) {
      const auto& F = *fixed;
      const auto& T = *towed;
      scale = std::max(scale, std::abs(F[k]));
      diff = std::max(diff, std::abs(T[k] - F[k]));
      kt = std::max(kt, std::abs(T[k] - 0.5 * (T[k - 1] + T[k + 1])));
      kf = std::max(kf, std::abs(F[k] - 0.5 * (F[k - 1] + F[k + 1])));
    }
  }
  p.max_difference = diff / scale;
  p.max_departure_towed = kt / scale;
  p.max_departure_fixed = kf / scale;
  p.cd_fixed_end = p.cd_fixed.back();
  p.cl_fixed_end = p.cl_fixed.back();
}

}  // namespace

TowedPlateResult run_towed_plate(const TowedPlateSetup& s) {
  if (s.cells_per_chord < 8 || !(s.re > 0) || !(s.cfl > 0) || !(s.t_end > s.t_compare))
    throw Error("towed plate: need cells_per_chord >= 8, re > 0, cfl > 0, t_end > t_compare");
  TowedPlateResult r;
  for (bool sheet : {true, false}) {
    if (!sheet && !s.closed) continue;
    const auto t0 = std::chrono::steady_clock::now();
    TowedPlatePair& p = sheet ? r.sheet : r.closed;
    std::size_t markers = 0;
    run_one(s, sheet, false, p.cd_fixed, p.cl_fixed, sheet ? &r.time : nullptr, r.steps, r.cells, markers);
    run_one(s, sheet, true, p.cd_towed, p.cl_towed, nullptr, r.steps, r.cells, markers);
    if (sheet) r.markers = markers;
    compare(s, r.time, p);
    p.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
  return r;
}

}  // namespace finverse::cfd::validation
