// Poiseuille flow in a round pipe with the fluid inside the immersed wall; see pipe_poiseuille.hpp.
// The pipe's axis runs through a column of cell centres (it is offset by half a cell), so the
// centreline speed and pressure are read at cell centres without interpolation.
#include "cfd/validation/pipe_poiseuille.hpp"

#include <cmath>
#include <numbers>

#include "cfd/cases/flow_case.hpp"
#include "cfd/forces/surface_traction_3d.hpp"
#include "cfd/immersed/surface_shapes.hpp"
#include "core/error.hpp"

namespace finverse::cfd::validation {

namespace {

// The case as a user's file would give it: the wall a cylinder with fluid: inside reaching three
// cells beyond the z sides, the inlet's parabola on its cross-section, a zero-gradient outlet.
cases::FlowCaseSpec pipe_case(const PipePoiseuilleSetup& p, double U, double h, double& centre) {
  const double D = p.diameter, R = D / 2;
  // A multiple of 8 cells across (the multigrid), at least three cells of wall around the pipe.
  const int nxy = 8 * static_cast<int>(std::ceil((D / h + 7) / 8));
  const int nz = 8 * std::max(1, static_cast<int>(std::lround(p.length_diameters * D / h / 8)));
  const double W = 0.5 * nxy * h, Lz = nz * h;
  centre = 0.5 * h;
  cases::FlowCaseSpec s;
  s.name = "pipe_poiseuille";
  s.domain = {-W, W, -W, W, 0, Lz};
  s.core = s.domain;
  s.h = h;
  s.nu = p.mu / p.rho;
  s.rho = p.rho;
  for (int k = 0; k < 4; ++k) s.sides[static_cast<std::size_t>(k)].type = FlowBcType::NoSlip;
  s.sides[4].type = FlowBcType::Inlet;
  s.sides[4].pipes = {{{centre, centre, 0}, R, U}};
  s.sides[5].type = FlowBcType::ZeroGradientOutlet;
  cases::CaseBody wall;
  wall.name = "pipe";
  wall.surface = cylinder_between({centre, centre, -3 * h}, {centre, centre, Lz + 3 * h}, R, 256);
  enclose_fluid(wall.surface);
  wall.encloses_fluid = true;
  wall.source = "cylinder, 256 segments";
  s.bodies.push_back(wall);
  s.initial_field = [=](double x, double y, double, double) {
    const double r2 = (x - centre) * (x - centre) + (y - centre) * (y - centre);
    return std::array<double, 3>{0, 0, r2 < R * R ? U * (1 - r2 / (R * R)) : 0.0};
  };
  s.t_end = p.t_end > 0 ? p.t_end : 3 * Lz / (0.5 * U);
  s.cfl = p.cfl;
  s.reference_speed = U;
  s.reference_area = std::numbers::pi * R * R;
  s.force_every = 10;
  return s;
}

// Least-squares slope of y over x.
double slope(const std::vector<double>& x, const std::vector<double>& y) {
  double mx = 0, my = 0;
  for (std::size_t n = 0; n < x.size(); ++n) {
    mx += x[n];
    my += y[n];
  }
  mx /= static_cast<double>(x.size());
  my /= static_cast<double>(x.size());
  double sxy = 0, sxx = 0;
  for (std::size_t n = 0; n < x.size(); ++n) {
    sxy += (x[n] - mx) * (y[n] - my);
    sxx += (x[n] - mx) * (x[n] - mx);
  }
  return sxy / sxx;
}

// The profile, pressure gradient, wall shear and inflow of the flow at t_end, over the middle
// z in [1.5 D, L - 1.5 D] (the inlet's and outlet's conditions are exact for Poiseuille flow, but
// the grid's wall is not a circle there either: the middle is what a developed pipe shows).
void measure(const FlowSolver& f, const PipePoiseuilleSetup& p, double U, double centre, PipePoiseuilleResult& r) {
  const StretchedGrid& g = f.grid();
  const double R = p.diameter / 2, z0 = 1.5 * p.diameter, z1 = g.axis(2).hi() - 1.5 * p.diameter;
  const Field pressure = f.pressure();
  const int ia = g.nx() / 2, ja = g.ny() / 2;  // the axis column (its centre is at `centre`)
  if (std::abs(g.xc(ia) - centre) > 1e-9 * R) throw Error("pipe_poiseuille: the axis is not on a centre column");
  std::vector<double> z, pz;
  double axis_sum = 0, err2 = 0;
  long cells = 0;
  for (int k = 0; k < g.nz(); ++k) {
    if (g.zc(k) < z0 || g.zc(k) > z1) continue;
    z.push_back(g.zc(k));
    pz.push_back(p.rho * pressure(ia, ja, k));
    axis_sum += f.u(2)(ia, ja, k);
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) {
        if (!f.fluid(i, j, k)) continue;
        const double r2 = (g.xc(i) - centre) * (g.xc(i) - centre) + (g.yc(j) - centre) * (g.yc(j) - centre);
        const double e = (f.u(2)(i, j, k) - U * (1 - r2 / (R * R))) / U;
        err2 += e * e;
        ++cells;
      }
  }
  if (z.size() < 2) throw Error("pipe_poiseuille: the pipe's middle holds fewer than two cells along z");
  r.centreline_speed = axis_sum / static_cast<double>(z.size());
  r.pressure_gradient = slope(z, pz);
  r.profile_rms = std::sqrt(err2 / static_cast<double>(std::max(1L, cells)));
  // The wall's shear: the traction's axial viscous part per area over the middle's triangles.
  SurfaceClip clip;
  clip.enabled = true;
  for (std::size_t s = 0; s < 6; ++s) clip.no_slip[s] = f.boundary().side[s].type == FlowBcType::NoSlip;
  const SurfaceTraction3D traction(g, *f.immersed(), *f.body_surface(), clip);
  const SurfaceForces F = traction.evaluate(f.u(0), f.u(1), f.u(2), f.p(), f.options().nu, p.rho);
  const auto& s = f.body_surface()->surface();
  double shear = 0, area = 0;
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    double zc = 0;
    for (int v : s.triangles[t]) zc += s.points[static_cast<std::size_t>(v)][2] / 3;
    if (zc < z0 || zc > z1) continue;
    shear += F.viscous[t][2];
    area += f.body_surface()->triangle_area(static_cast<int>(t));
  }
  r.wall_shear = shear / area;
  r.wall_samples = static_cast<long>(traction.samples().size());
  // The discrete inflow through the inlet's fluid faces.
  double q = 0;
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i)
      if (f.fluid(i, j, 0)) q += f.face_velocity()(2, i, j, 0) * g.dx(i) * g.dy(j);
  r.inflow_rate_error = q / (0.5 * std::numbers::pi * R * R * U) - 1;
  r.ghost_cells = static_cast<long>(f.immersed()->ghosts().size());
}

}  // namespace

PipePoiseuilleResult run_pipe_poiseuille(const PipePoiseuilleSetup& p) {
  if (!(p.cells_per_diameter >= 4)) throw Error("pipe_poiseuille: at least 4 cells per diameter");
  const double nu = p.mu / p.rho, U = p.reynolds * nu / p.diameter, R = p.diameter / 2;
  const double h = p.diameter / p.cells_per_diameter;
  PipePoiseuilleResult r;
  double centre = 0;
  const cases::FlowCaseSpec spec = pipe_case(p, U, h, centre);
  const cases::FlowCaseResult run = cases::run_flow_case(
      spec, [&](const StepStats& st, double) {
        if (p.progress) p.progress(st);
      },
      [&](const FlowSolver& f) { measure(f, p, U, centre, r); });
  r.centreline_reference = U;
  r.wall_shear_reference = 2 * p.mu * U / R;
  r.pressure_gradient_reference = -4 * p.mu * U / (R * R);
  // Steadiness: the wall's axial drag over the last fifth of the run.
  double first = 0, last = run.force.back()[0][2];
  for (std::size_t n = 0; n < run.time.size(); ++n)
    if (run.time[n] >= 0.8 * spec.t_end) {
      first = run.force[n][0][2];
      break;
    }
  r.wall_drag_drift = std::abs(last - first) / std::max(std::abs(last), 1e-300);
  r.h = h;
  r.t_end = spec.t_end;
  r.cells = run.cells;
  r.steps = run.steps;
  r.mean_poisson_iterations = run.mean_poisson_iterations;
  r.max_divergence = run.max_divergence;
  r.cpu_seconds = run.cpu_seconds;
  return r;
}

}  // namespace finverse::cfd::validation
