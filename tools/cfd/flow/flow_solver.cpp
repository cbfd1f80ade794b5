// FlowSolver set-up, the time loop's order of sub-steps, the shared discrete operators (face
// interpolation, face and cell gradients, divergence) and the checkpoint state; see flow_solver.hpp.
// The sub-steps themselves live one per file (momentum_predictor.cpp, pressure_correction.cpp,
// velocity_update.cpp, time_step_control.cpp, boundary_update.cpp).
#include "cfd/flow/flow_solver.hpp"
#include "cfd/flow/vortex_identification.hpp"

#include <cmath>
#include <cstring>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "cfd/grid/grid_loops.hpp"
#include "core/error.hpp"

namespace finverse::cfd {

void FlowSolver::setup(const StretchedGrid& grid, const FlowBoundary& boundary, const FlowOptions& options) {
  boundary.validate(grid.dim());
  if (!(options.nu > 0)) throw Error("flow solver: nu must be > 0");
  if (!(options.dt > 0) && !(options.cfl > 0 && std::isfinite(options.dt_max) && options.dt_max > 0))
    throw Error("flow solver: need dt > 0, or cfl > 0 with a finite dt_max > 0");
  grid_ = grid;
  bnd_ = boundary;
  opt_ = options;
  beta_ = FaceCoefficients(grid, 1.0);
  for (int c = 0; c < dim(); ++c) {
    BoundaryConditions bc;
    for (int s = 0; s < 6; ++s) {
      const Side side = static_cast<Side>(s);
      bc[side] = s < 2 * dim() ? bnd_.component_type(side, c) : BcType::Neumann;
    }
    helmholtz_[static_cast<std::size_t>(c)].set_system_solver(make_flow_momentum_system());  // the ranks', when installed
    helmholtz_[static_cast<std::size_t>(c)].setup(grid, beta_, bc);
  }
  poisson_.set_system_solver(make_flow_pressure_system());  // the MPI ranks' solve, when installed
  poisson_.setup(grid, beta_, bnd_.pressure_conditions(), opt_.poisson);
  for (int c = 0; c < 3; ++c) {
    const auto C = static_cast<std::size_t>(c);
    const bool on = c < dim();
    u_[C] = on ? Field(grid) : Field();
    ustar_[C] = on ? Field(grid) : Field();
    conv_[C] = on ? Field(grid) : Field();
    conv_old_[C] = on ? Field(grid) : Field();
    work_[C] = on ? Field(grid) : Field();
  }
  p_ = Field(grid);
  phi_ = Field(grid);
  phi_solved_ = Field(grid);
  rhs_ = Field(grid);
  zero_ = Field(grid);
  grad_ = Field(grid);
  bterm_ = Field(grid);
  U_ = FaceField(grid);
  Ustar_ = FaceField(grid);
  own_ = faces_ = all_lines(grid);
  partial_ = false;
  time_ = 0;
  dt_old_ = 0;
  step_ = 0;
  ib_.reset();
  wall_dpdn_.reset();
  wall_dpdn_3d_.reset();
  body_faces_.clear();
  moving_.reset();
  deforming_.reset();
  next_polygon_.reset();
  next_surface_.reset();
  caller_surface_ = false;
  surface_.reset();
  surface_motion_ = nullptr;
  fresh_.clear();
  cut_.reset();
  cut_cells_.clear();
  cut_flux_.clear();
  cut_slot_.clear();
  sheet_.reset();
  sheet_motion_ = nullptr;
  next_sheet_.reset();
  sheet_state_ = {};
  sheet_impulse_.clear();
  sheet_stats_ = {};
}

void FlowSolver::immerse(const Polygon& body) { immerse(std::vector<SolidRegion>{SolidRegion{body, false}}); }

void FlowSolver::immerse(const std::vector<SolidRegion>& regions, const VelocityFunction& wall_velocity) {
  if (dim() != 2) throw Error("flow solver: an immersed polygon needs a 2-D grid");
  ib_.emplace(grid_, regions);
  index_body_faces();
  moving_.reset();
  deforming_.reset();
  next_polygon_.reset();
  caller_surface_ = false;
  cut_.reset();
  surface_.reset();
  surface_motion_ = nullptr;
  fresh_.clear();
  ib_dpdn_.clear();
  wall_dpdn_.reset();
  wall_dpdn_3d_.reset();
  if (opt_.viscous_wall_pressure && !wall_velocity) wall_dpdn_.emplace(grid_, *ib_, regions);
  for (auto& w : ib_wall_) w.clear();
  if (wall_velocity)
    for (const GhostCell& g : ib_->ghosts()) {
      const auto v = wall_velocity(g.boundary.point[0], g.boundary.point[1], grid_.zc(0), 0.0);
      for (int c = 0; c < dim(); ++c) ib_wall_[static_cast<std::size_t>(c)].push_back(v[static_cast<std::size_t>(c)]);
    }
  if (opt_.cut_cell_continuity_fixed)
    place_cut_cells(cut_faces(grid_, regions),
                    {grid_.axis(0).lo(), grid_.axis(0).hi(), grid_.axis(1).lo(), grid_.axis(1).hi(), -1e300, 1e300});
  setup_pressure_operator();
  ib_momentum_.setup(grid_);
}

void FlowSolver::setup_pressure_operator() {
  // restore() re-places a moving body at the step's start, and the step places it again at its
  // end before any pressure solve: the operator of the start's placement is built only if a solve
  // asks for it (solve_pressure_correction). In a coupling every iteration restores, and the
  // build was half of the pressure set-ups (docs/studies/fsi_step_cost.md).
  if (defer_pressure_setup_) {
    pressure_stale_ = true;
    return;
  }
  pressure_stale_ = false;
  if (cut_) {
    poisson_.setup(grid_, cut_->aperture, bnd_.pressure_conditions(), opt_.poisson);
    return;
  }
  FaceCoefficients masked(grid_, 1.0);
  masked.mask_cells([&](int i, int j, int k) { return ib_->solid(i, j, k); });
  poisson_.setup(grid_, masked, bnd_.pressure_conditions(), opt_.poisson);
}

bool FlowSolver::masked_face(int d, int i, int j, int k) const {
  if (!ib_) return false;
  const int n = grid_.n(d);
  const int f = d == 0 ? i : d == 1 ? j : k;
  if (f == 0 || f == n) return false;  // domain boundary: the flux is prescribed there anyway
  int lo[3] = {i, j, k};
  --lo[d];
  return !fluid(i, j, k) || !fluid(lo[0], lo[1], lo[2]);
}

void FlowSolver::impose_body_velocity() {
  for (int c = 0; c < dim(); ++c) {
    Field& u = u_[static_cast<std::size_t>(c)];
    if (moving_) {  // solid cells carry the rigid-body velocity (a cleared cell's last resort)
      for (int j = 0; j < grid_.ny(); ++j)
        for (int i = 0; i < grid_.nx(); ++i)
          if (ib_->kind(i, j) == CellKind::Solid)
            u(i, j, 0) = moving_->velocity(body_state_, grid_.xc(i), grid_.yc(j))[static_cast<std::size_t>(c)];
    } else if (surface_motion_ || deforming_) {  // solid cells: their closest surface point's velocity
      const Field& b = body_velocity_[static_cast<std::size_t>(c)];
      for (int k = 0; k < grid_.nz(); ++k)
        for (int j = 0; j < grid_.ny(); ++j)
          for (int i = 0; i < grid_.nx(); ++i)
            if (ib_->kind(i, j, k) == CellKind::Solid) u(i, j, k) = b(i, j, k);
    } else {
      ib_->fill_solid(u, 0.0);
    }
    ib_->impose_dirichlet(u, ib_wall_[static_cast<std::size_t>(c)]);
  }
}

// Faces between a fluid and a ghost cell carry the interpolated (ghost-extended) velocity, faces
// between two non-fluid cells the body's (zero at rest). The net flux into the fixed body is then
// O(h^2) but not zero; it is removed uniformly per unit area, so that no mass crosses the body
// and the Neumann problem for phi on the fluid cells stays compatible.
void FlowSolver::index_body_faces() {
  body_faces_.clear();
  if (!ib_) return;
  for (int d = 0; d < dim(); ++d) {
    const int n = grid_.n(d);
    for (int k = 0; k < grid_.nz(); ++k)
      for (int j = 0; j < grid_.ny() + (d == 1); ++j)
        for (int i = 0; i < grid_.nx() + (d == 0); ++i) {
          const int f = d == 0 ? i : d == 1 ? j : k;
          if (f == 0 || f == n || !masked_face(d, i, j, k)) continue;
          int lo[3] = {i, j, k};
          --lo[d];
          const bool fl = fluid(lo[0], lo[1], lo[2]), fh = fluid(i, j, k);
          body_faces_.push_back({d, i, j, k, fl ? 1 : fh ? -1 : 0});
        }
  }
}

// A face between a fluid cell and a body cell of a moving triangulated body with the cut-cell
// balance: its stored velocity is the mean over the face, the fluid part (aperture alpha) moving
// with the fluid cell it opens into and the solid part with the wall, alpha u_fluid + (1 - alpha)
// u_B(face centre). Not the interpolation with the ghost cell: that lets the ghost value, a
// reflection carrying the no-slip condition, into the continuity constraint of the open part, and
// on a thin deforming body that loop grew until the run blew up (docs/studies/cut_cell_balance.md).
double FlowSolver::cut_body_face_velocity(const BodyFace& b, const Field& ud) const {
  const int d = b.d;
  int fl[3] = {b.i, b.j, b.k};
  if (b.side > 0) --fl[d];  // the fluid cell: below the face (side +1) or above it (side -1)
  const double alpha = cut_->aperture(d, b.i, b.j, b.k);
  const double u_fluid = ud(fl[0], fl[1], fl[2]);
  if (alpha >= 1) return u_fluid;
  Vec3 x{grid_.xc(b.i), grid_.yc(b.j), grid_.zc(b.k)};
  x[static_cast<std::size_t>(d)] = grid_.axis(d).face(d == 0 ? b.i : d == 1 ? b.j : b.k);
  const double u_wall = surface_->interpolate(surface_state_.velocity, surface_->closest(x))[static_cast<std::size_t>(d)];
  return alpha * u_fluid + (1 - alpha) * u_wall;
}

void FlowSolver::body_face_velocities(FaceField& U, const std::array<Field, 3>& u) const {
  // The faces in the order of a full scan, so the ordered sums below are those of one.
  double net = 0, area = 0;
  for (const BodyFace& b : body_faces_) {
    const int d = b.d, i = b.i, j = b.j, k = b.k;
    if (b.side == 0) {  // inside the body: its own velocity (a cleared cell's first fluxes)
      if (surface_motion_ || deforming_) {
        int lo[3] = {i, j, k};
        --lo[d];
        const Field& v = body_velocity_[static_cast<std::size_t>(d)];
        U(d, i, j, k) = 0.5 * (v(lo[0], lo[1], lo[2]) + v(i, j, k));
        continue;
      }
      U(d, i, j, k) = moving_ ? moving_->velocity(body_state_, d == 0 ? grid_.axis(0).face(i) : grid_.xc(i),
                                                  d == 1 ? grid_.axis(1).face(j) : grid_.yc(j))[static_cast<std::size_t>(d)]
                              : 0.0;
      continue;
    }
    if (cut_ && surface_motion_) {
      U(d, i, j, k) = cut_body_face_velocity(b, u[static_cast<std::size_t>(d)]);
      continue;  // the cut-cell balance carries the body's flux: no net flux to remove
    }
    if (surface_motion_) {
      // The staircase of a moving triangulated body: the closed face moves with the wall, the
      // velocity of the ghost cell's closest surface point. Its interpolation with the ghost cell,
      // a reflection of the fluid at the image point, let the ghost values into the continuity
      // constraint as with the cut cells (cut_body_face_velocity): on fin-mesh's default fin a fluid
      // cell with ghost cells on three sides flipped sign every step and blew up at step 229.
      int g[3] = {i, j, k};
      if (b.side < 0) --g[d];  // the ghost cell: below the face when the fluid is above it
      U(d, i, j, k) = body_velocity_[static_cast<std::size_t>(d)](g[0], g[1], g[2]);
    } else {
      U(d, i, j, k) = face_value(u[static_cast<std::size_t>(d)], d, d, i, j, k, bv_new_);
    }
    const double A = face_area(d, i, j, k);
    net += b.side * U(d, i, j, k) * A;  // out of the fluid, into the body
    area += A;
  }
  // The cut-cell balance carries the body's own flux (continuity_residual): nothing to remove.
  if (!(area > 0) || cut_) return;
  const double shift = net / area;
  for (const BodyFace& b : body_faces_)
    if (b.side != 0) U(b.d, b.i, b.j, b.k) -= b.side * shift;
}

void FlowSolver::initialise(const VelocityFunction& velocity, const std::function<double(double, double, double)>& pressure,
                            double t0) {
  time_ = t0;
  dt_old_ = 0;
  step_ = 0;
  if (moving_ || deforming_) {
    place_body(t0);
    fresh_.clear();
  } else if (surface_motion_) {
    place_surface(t0, caller_surface_ ? surface_state_ : surface_motion_(t0));
    fresh_.clear();
  }
  if (sheet_) {
    if (sheet_motion_) sheet_state_ = sheet_motion_(t0);
    sheet_impulse_.assign(sheet_->size(), Vec3{0, 0, 0});
  }
  for_each_cell(grid_, [&](int i, int j, int k) {
    const auto v = velocity ? velocity(grid_.xc(i), grid_.yc(j), grid_.zc(k), t0) : std::array<double, 3>{0, 0, 0};
    for (int c = 0; c < dim(); ++c) u_[static_cast<std::size_t>(c)](i, j, k) = v[static_cast<std::size_t>(c)];
    p_(i, j, k) = pressure ? pressure(grid_.xc(i), grid_.yc(j), grid_.zc(k)) : 0.0;
  });
  if (ib_) {
    impose_body_velocity();
    ib_->fill_solid(p_, 0.0);
    ib_->impose_neumann(p_, ib_dpdn_);
  }
  for (int c = 0; c < dim(); ++c) {
    conv_old_[static_cast<std::size_t>(c)].fill(0.0);
    copy_interior(u_[static_cast<std::size_t>(c)], ustar_[static_cast<std::size_t>(c)]);
  }
  // A sheet: the initial field takes the sheet's velocity at its markers before the projection,
  // as a closed body's initial field goes around it (not a load: an impulsive start's first step
  // would otherwise stop the stream at the sheet within one step).
  if (sheet_) force_initial_sheet(t0);
  double norm = norm2(p_);
  for (int c = 0; c < dim(); ++c) norm += norm2(u_[static_cast<std::size_t>(c)]);
  if (!std::isfinite(norm)) throw Error("flow solver: the initial velocity or pressure is not finite");
  set_boundary_values(t0, 0.0, true);
  // Project the interpolated initial field: the face predictor with dt = 1 and no pressure, then
  // the same correction as a time step, so that the run starts from discretely solenoidal faces.
  // The faces get the pressure-coupling term they will carry during the run (see face_predictor).
  Field p_saved = p_;
  phi_.fill(0.0);
  const double tau = opt_.coupling_time > 0 ? (opt_.dt > 0 ? coupling_time(opt_.dt) : opt_.coupling_time) : opt_.dt;
  if (!(tau > 0)) p_.fill(0.0);  // dt not known yet: start from the plain interpolation
  face_predictor(1.0, tau > 0 ? tau : 1.0);
  solve_pressure_correction(1.0);
  update_velocity(1.0);
  p_ = p_saved;
  phi_.fill(0.0);
  bv_ = bv_new_;
}

StepStats FlowSolver::step() {
  const double dt = choose_time_step();
  const double t_new = time_ + dt;
  if ((deforming_ && !next_polygon_) || (caller_surface_ && !next_surface_) ||
      (sheet_ && !sheet_motion_ && !next_sheet_))
    throw Error("flow solver: step to t = " + std::to_string(t_new) +
                ": set_body_state (set_sheet_state) must give the body's (sheet's) state at the new time level first");
  set_boundary_values(t_new, dt, false);
  if (deforming_) {  // (built aside first: a bad state leaves the body as it was)
    DeformingPolygon next(*next_polygon_, "flow solver: deforming body at t = " + std::to_string(t_new),
                          deforming_->state().position.size());
    deforming_ = std::move(next);
    next_polygon_.reset();
    kinds_polygon_ = std::move(next_kinds_);
    next_kinds_.reset();
  }
  if (moving_ || deforming_) {
    move_body(t_new);
  } else if (surface_motion_) {
    SurfaceState next = caller_surface_ ? std::move(*next_surface_) : surface_motion_(t_new);
    next_surface_.reset();
    move_surface(t_new, std::move(next));
  }
  std::optional<SheetState> sheet_next;
  if (sheet_) {
    sheet_next = sheet_motion_ ? sheet_motion_(t_new) : std::move(*next_sheet_);
    next_sheet_.reset();
  }
  choose_rank_lines();
  predict_momentum(dt);
  if (sheet_) force_sheet(dt, std::move(*sheet_next));
  face_predictor(dt, coupling_time(dt));
  if (repeating_) copy_interior(solved_phi_, phi_);  // (after the face predictor, which reads phi^n)
  PoissonSolveStats ps = solve_pressure_correction(dt);
  if (warm_start_repeats_) copy_interior(phi_, solved_phi_);
  update_velocity(dt);
  // A sheet's further forcing and projection passes (SheetForcingOptions::projections): the
  // pressure increments add up in p, the face velocities carry the earlier corrections.
  for (int pass = 1; sheet_ && pass < sheet_opt_.projections; ++pass) {
    for (int c = 0; c < dim(); ++c) copy_interior(u_[static_cast<std::size_t>(c)], ustar_[static_cast<std::size_t>(c)]);
    add_sheet_impulse(dt);
    face_predictor(dt, coupling_time(dt));
    const PoissonSolveStats more = solve_pressure_correction(dt);
    ps.iterations += more.iterations;
    update_velocity(dt);
  }
  for (int c = 0; c < dim(); ++c) std::swap(conv_old_[static_cast<std::size_t>(c)], conv_[static_cast<std::size_t>(c)]);
  bv_ = bv_new_;
  time_ = t_new;
  dt_old_ = dt;
  ++step_;
  solved_step_ = warm_start_repeats_ ? step_ : -1;
  repeating_ = false;
  const double cfl_now = cfl(dt);
  check_health(dt, cfl_now);
  StepStats st;
  st.step = step_;
  st.time = time_;
  st.dt = dt;
  st.cfl = cfl_now;
  st.poisson_iterations = ps.iterations;
  st.poisson_residual = ps.relative_residual;
  st.helmholtz_iterations = last_helmholtz_iterations_;
  st.max_divergence = max_divergence();
  return st;
}

// ---- shared discrete operators -------------------------------------------------------------

std::size_t FlowSolver::side_index(Side s, int i, int j, int k) const {
  const auto z = [](int v) { return static_cast<std::size_t>(v); };
  switch (side_axis(s)) {
    case 0: return z(j) + z(grid_.ny()) * z(k);
    case 1: return z(i) + z(grid_.nx()) * z(k);
    default: return z(i) + z(grid_.nx()) * z(j);
  }
}

// face_value on the box's boundary (the interior case is inline in flow_solver.hpp): across a
// periodic pair, the interpolation between the last and the first cell; on a non-periodic side, the
// Dirichlet value, or the cell value for a zero normal derivative.
double FlowSolver::boundary_face_value(const Field& q, int c, int d, int i, int j, int k,
                                       const std::array<BoundaryValues, 3>& bv) const {
  const Axis& ax = grid_.axis(d);
  const int n = ax.size();
  int idx[3] = {i, j, k};
  const int f = idx[d];
  int lo[3] = {i, j, k}, hi[3] = {i, j, k};
  if (bnd_.periodic(d)) {
    lo[d] = n - 1;
    hi[d] = 0;
  } else {
    const Side s = static_cast<Side>(2 * d + (f == n ? 1 : 0));
    const auto& v = bv[static_cast<std::size_t>(c)][s];
    if (!v.empty()) return v[side_index(s, i, j, k)];
    idx[d] = f == n ? n - 1 : 0;
    return q(idx[0], idx[1], idx[2]);
  }
  const double hl = ax.width(lo[d]), hr = ax.width(hi[d]);
  const double wl = hr / (hl + hr);
  return wl * q(lo[0], lo[1], lo[2]) + (1 - wl) * q(hi[0], hi[1], hi[2]);
}

// face_gradient on the box's boundary: across a periodic pair, between the last and the first
// cell; zero on non-periodic sides, where the pressure correction satisfies a homogeneous Neumann
// condition (the boundary fluxes are prescribed).
double FlowSolver::boundary_face_gradient(const Field& q, int d, int i, int j, int k) const {
  if (!bnd_.periodic(d)) return 0.0;
  const Axis& ax = grid_.axis(d);
  const int n = ax.size();
  int lo[3] = {i, j, k}, hi[3] = {i, j, k};
  lo[d] = n - 1;
  hi[d] = 0;
  const double dist = 0.5 * (ax.width(0) + ax.width(n - 1));
  return (q(hi[0], hi[1], hi[2]) - q(lo[0], lo[1], lo[2])) / dist;
}

// Cell-centred gradient: the mean of the two face gradients (the centre is midway between its
// faces, so this is their linear interpolation). Next to a non-periodic boundary the boundary
// face's gradient is not a property of the flow (it is the Neumann condition of the correction),
// so the cell value is extrapolated linearly from the two nearest interior faces instead.
double FlowSolver::cell_gradient_at(const Field& q, int d, int i, int j, int k) const {
  const Axis& ax = grid_.axis(d);
  const int n = ax.size();
  const int idx[3] = {i, j, k};
  const int m = idx[d];
  int f1[3] = {i, j, k};
  if (bnd_.periodic(d) || (m > 0 && m < n - 1)) {
    f1[d] = m + 1;
    return 0.5 * (face_gradient(q, d, i, j, k) + face_gradient(q, d, f1[0], f1[1], f1[2]));
  }
  if (n == 1) return 0;
  // Boundary cell: interior faces a (nearest) and b (next).
  const int fa = m == 0 ? 1 : n - 1;
  f1[d] = fa;
  const double ga = face_gradient(q, d, f1[0], f1[1], f1[2]);
  if (n == 2) return ga;
  const int fb = m == 0 ? 2 : n - 2;
  int f2[3] = {i, j, k};
  f2[d] = fb;
  const double gb = face_gradient(q, d, f2[0], f2[1], f2[2]);
  return ga + (ax.centre(m) - ax.face(fa)) * (gb - ga) / (ax.face(fb) - ax.face(fa));
}

// The same gradient a grid line at a time: away from the boundary cells each interior cell is the
// expression of cell_gradient_at with its neighbours read at a fixed stride, which the compiler
// vectorises (per cell, the generic path costs two index computations and two branches per face;
// it was 6 % of the fin's time step). Same operations in the same order, so the same bits.
void FlowSolver::cell_gradient(const Field& q, int d, Field& out, const LineRange& lines) const {
  const Axis& ax = grid_.axis(d);
  const int n = ax.size(), nx = grid_.nx();
  std::vector<double> dist(static_cast<std::size_t>(n) + 1, 0.0);
  for (int f = 1; f < n; ++f) dist[static_cast<std::size_t>(f)] = ax.centre_distance(f);
  const std::ptrdiff_t stride = d == 0 ? 1 : d == 1 ? q.stride_y() : q.stride_z();
  for_each_line(grid_, lines, [&](int j, int k) {
    const double* a = &q(0, j, k);
    double* o = &out(0, j, k);
    if (d == 0) {
      for (int i = 1; i < n - 1; ++i) {
        const auto I = static_cast<std::size_t>(i);
        o[i] = 0.5 * ((a[i] - a[i - 1]) / dist[I] + (a[i + 1] - a[i]) / dist[I + 1]);
      }
      o[0] = cell_gradient_at(q, d, 0, j, k);
      if (n > 1) o[n - 1] = cell_gradient_at(q, d, n - 1, j, k);
      return;
    }
    const int m = d == 1 ? j : k;
    if (m == 0 || m == n - 1) {
      for (int i = 0; i < nx; ++i) o[i] = cell_gradient_at(q, d, i, j, k);
      return;
    }
    const double dl = dist[static_cast<std::size_t>(m)], dr = dist[static_cast<std::size_t>(m) + 1];
    for (int i = 0; i < nx; ++i) o[i] = 0.5 * ((a[i] - a[i - stride]) / dl + (a[i + stride] - a[i]) / dr);
  });
  // A fluid centre within half a spacing of the wall: its closed face counts as zero gradient
  // (ghost_cells.hpp, near_wall_faces), its other face as computed (zero where closed too). Not
  // with the cut-cell balance: its pressure equation sees the faces' open fractions, not a closed
  // face, and the moving fin's loads rest on that form (cut_cell_balance.md).
  if (!opt_.near_wall_closed_faces || !ib_ || cut_) return;
  for (const NearWallFace& w : ib_->near_wall_faces()) {
    const auto [i, j, k] = w.cell;
    const int m = w.cell[static_cast<std::size_t>(d)];
    if (w.axis != d || m == 0 || m == n - 1 || !lines.contains(j, k)) continue;
    int f[3] = {i, j, k};
    if (w.side < 0) ++f[d];  // the closed face is the lower one: the other is the upper
    out(i, j, k) = masked_face(d, f[0], f[1], f[2]) ? 0.0 : 0.5 * face_gradient(q, d, f[0], f[1], f[2]);
  }
}

double FlowSolver::divergence(const FaceField& U, int i, int j, int k) const {
  double s = 0;
  for (int d = 0; d < dim(); ++d) {
    int h[3] = {i, j, k};
    ++h[d];
    s += (U(d, h[0], h[1], h[2]) - U(d, i, j, k)) * face_area(d, i, j, k);
  }
  return s / grid_.volume(i, j, k);
}

// Brown, Cortez & Minion (2001): with Crank-Nicolson, p^{n+1/2} = p^{n-1/2} + phi - (nu dt/2) L phi
// is the second-order pressure at the half step. Only for output: fed back into the predictor, the
// extra term destabilises the scheme next to walls (phi's homogeneous Neumann condition is not the
// pressure's, so L phi is O(1/h) there); the scheme's own p is Van Kan's.
Field FlowSolver::pressure() const {
  Field out = p_;
  if (step_ == 0) return out;
  Field phi = phi_, lap(grid_);
  poisson_.op().apply(phi, lap);  // A phi = -V L phi
  const double c = 0.5 * opt_.nu * dt_old_;
  for_each_cell(grid_, [&](int i, int j, int k) { out(i, j, k) += c * lap(i, j, k) / grid_.volume(i, j, k); });
  return out;
}

// ---- output and checkpoint state -------------------------------------------------------------

std::vector<StateArray> FlowSolver::cell_output() const {
  require_whole("cell_output");
  const std::size_t n = grid_.cells();
  const Field ph = pressure();
  StateArray vel{"velocity", std::vector<double>(3 * n, 0.0)}, pres{"pressure", std::vector<double>(n)},
      div{"divergence", std::vector<double>(n)};
  for_each_cell(grid_, [&](int i, int j, int k) {
    const std::size_t m = static_cast<std::size_t>(i) +
                          static_cast<std::size_t>(grid_.nx()) *
                              (static_cast<std::size_t>(j) + static_cast<std::size_t>(grid_.ny()) * static_cast<std::size_t>(k));
    for (int c = 0; c < dim(); ++c) vel.values[3 * m + static_cast<std::size_t>(c)] = u_[static_cast<std::size_t>(c)](i, j, k);
    pres.values[m] = ph(i, j, k);
    div.values[m] = divergence(U_, i, j, k);
  });
  // Vorticity and lambda_2 from fluid cells only: inside an immersed body the velocity is the
  // ghost-cell extrapolation, not flow.
  VortexFields vf = vortex_fields(grid_, {&u_[0], &u_[1], dim() == 3 ? &u_[2] : nullptr},
                                  [this](int i, int j, int k) { return fluid(i, j, k); });
  return {vel, pres, div, {"vorticity", std::move(vf.vorticity)}, {"lambda2", std::move(vf.lambda2)}};
}

namespace {
std::size_t raw_size(const Field& f) {
  const std::size_t gz = f.dim() == 3 ? static_cast<std::size_t>(f.ghost()) : 0;
  return static_cast<std::size_t>(f.stride_z()) * (static_cast<std::size_t>(f.nz()) + 2 * gz);
}
StateArray raw(const std::string& name, const Field& f) {
  return {name, std::vector<double>(f.data(), f.data() + raw_size(f))};
}
void unraw(const StateArray& a, Field& f) {
  if (a.values.size() != raw_size(f)) throw Error("flow solver restore: array '" + a.name + "' has the wrong size");
  std::memcpy(f.data(), a.values.data(), a.values.size() * sizeof(double));
}
const char* comp_name(int c) { return c == 0 ? "x" : c == 1 ? "y" : "z"; }

// A body's vertex state as one array: positions, velocities, accelerations (empty ones as zero),
// and back (like: the state whose vertex count and connectivity the array must match).
template <class P>
void append(std::vector<double>& out, const std::vector<P>& q, std::size_t n) {
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t c = 0; c < std::tuple_size_v<P>; ++c) out.push_back(q.empty() ? 0.0 : q[k][c]);
}
template <class P>
std::vector<P> take(const std::vector<double>& in, std::size_t& at, std::size_t n) {
  std::vector<P> q(n);
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t c = 0; c < std::tuple_size_v<P>; ++c) q[k][c] = in[at++];
  return q;
}
std::vector<double> polygon_state_values(const PolygonState& s) {
  std::vector<double> out;
  const std::size_t n = s.position.size();
  append(out, s.position, n);
  append(out, s.velocity, n);
  append(out, s.acceleration, n);
  return out;
}
PolygonState polygon_state_from(const std::vector<double>& in, const PolygonState& like) {
  const std::size_t n = like.position.size();
  std::size_t at = 0;
  PolygonState s;
  s.position = take<std::array<double, 2>>(in, at, n);
  s.velocity = take<std::array<double, 2>>(in, at, n);
  s.acceleration = take<std::array<double, 2>>(in, at, n);
  return s;
}
std::vector<double> surface_state_values(const SurfaceState& s) {
  std::vector<double> out;
  const std::size_t n = s.surface.points.size();
  append(out, s.surface.points, n);
  append(out, s.velocity, n);
  append(out, s.acceleration, n);
  return out;
}
SurfaceState surface_state_from(const std::vector<double>& in, const SurfaceState& like) {
  const std::size_t n = like.surface.points.size();
  std::size_t at = 0;
  SurfaceState s;
  s.surface.triangles = like.surface.triangles;
  s.surface.points = take<Vec3>(in, at, n);
  s.velocity = take<Vec3>(in, at, n);
  s.acceleration = take<Vec3>(in, at, n);
  return s;
}
}  // namespace

std::vector<StateArray> FlowSolver::state() const {
  require_whole("state");
  std::vector<StateArray> s;
  s.push_back({"scalars", {static_cast<double>(step_), time_, dt_old_}});
  s.push_back(raw("p", p_));
  s.push_back(raw("phi", phi_));
  for (int c = 0; c < dim(); ++c) {
    const auto C = static_cast<std::size_t>(c);
    s.push_back(raw(std::string("u_") + comp_name(c), u_[C]));
    s.push_back(raw(std::string("convection_") + comp_name(c), conv_old_[C]));
    s.push_back({std::string("face_velocity_") + comp_name(c), U_.values(c)});
    for (int side = 0; side < 2 * dim(); ++side)
      s.push_back({std::string("boundary_") + comp_name(c) + "_" + std::to_string(side),
                   bv_[C].value[static_cast<std::size_t>(side)]});
  }
  // A moving triangulated body: the solid-cell velocities are re-evaluated on placement, but a
  // ghost cell keeps the value from when it was last solid, and a face between two ghost cells
  // carries it (body_face_velocities), so the field is part of the state.
  if (surface_motion_)
    for (int c = 0; c < 3; ++c)
      s.push_back(raw(std::string("body_velocity_") + comp_name(c), body_velocity_[static_cast<std::size_t>(c)]));
  // A deforming body whose state the caller sets: its vertex state at time() (the geometry of the
  // next step's t^n, from which restore() re-places it).
  if (deforming_) s.push_back({"body_vertices", polygon_state_values(deforming_->state())});
  // ... and the polygon its cell kinds came from (set_body_state's kinds_at), if another: a flag,
  // then the stored (counter-clockwise) vertices, as many as the body has.
  if (deforming_) {
    std::vector<double> k{kinds_polygon_ ? 1.0 : 0.0};
    for (const auto& v : (kinds_polygon_ ? *kinds_polygon_ : deforming_->polygon()).vertices()) k.insert(k.end(), {v[0], v[1]});
    s.push_back({"body_kinds", std::move(k)});
  }
  if (caller_surface_) s.push_back({"body_vertices", surface_state_values(surface_state_)});
  // A sheet: its node state at time() (positions, velocities) and the last step's impulses (its loads).
  if (sheet_) {
    std::vector<double> nodes;
    append(nodes, sheet_state_.position, sheet_->topology().nodes);
    append(nodes, sheet_state_.velocity, sheet_->topology().nodes);
    s.push_back({"sheet_nodes", std::move(nodes)});
    std::vector<double> g;
    append(g, sheet_impulse_, sheet_->size());
    s.push_back({"sheet_impulse", std::move(g)});
  }
  return s;
}

void FlowSolver::warm_start_repeated_steps(bool on) {
  warm_start_repeats_ = on;
  repeating_ = false;
  solved_step_ = -1;
  for (int c = 0; c < dim(); ++c) solved_ustar_[static_cast<std::size_t>(c)] = on ? Field(grid_) : Field();
  solved_phi_ = on ? Field(grid_) : Field();
}

void FlowSolver::restore(const std::vector<StateArray>& s) {
  partial_ = false;  // every field that a rank's lines leave partial is replaced whole below
  const std::vector<StateArray> expected = state();
  if (s.size() != expected.size()) throw Error("flow solver restore: checkpoint does not match this set-up");
  for (std::size_t a = 0; a < s.size(); ++a)
    if (s[a].name != expected[a].name || s[a].values.size() != expected[a].values.size())
      throw Error("flow solver restore: array '" + expected[a].name + "' missing or of the wrong size");
  step_ = static_cast<long>(s[0].values[0]);
  repeating_ = warm_start_repeats_ && solved_step_ == step_ + 1;
  time_ = s[0].values[1];
  dt_old_ = s[0].values[2];
  std::size_t a = 1;
  unraw(s[a++], p_);
  unraw(s[a++], phi_);
  for (int c = 0; c < dim(); ++c) {
    const auto C = static_cast<std::size_t>(c);
    unraw(s[a++], u_[C]);
    unraw(s[a++], conv_old_[C]);
    U_.values(c) = s[a++].values;
    for (int side = 0; side < 2 * dim(); ++side) bv_[C].value[static_cast<std::size_t>(side)] = s[a++].values;
  }
  // The geometry: a function of time, or the deforming body's saved state; a state set for the
  // next step is dropped (a coupling iteration sets its own after restoring).
  next_polygon_.reset();
  next_surface_.reset();
  // (a placement that throws must not leave the set-ups deferred)
  struct Deferred {
    bool& on;
    ~Deferred() { on = false; }
  } deferred{defer_pressure_setup_ = true};
  if (moving_) {
    place_body(time_);
    fresh_.clear();
  } else if (deforming_) {
    const std::vector<double>& k = s.back().values;
    kinds_polygon_.reset();
    next_kinds_.reset();
    if (k[0] != 0) {
      std::vector<std::array<double, 2>> v;
      for (std::size_t m = 1; m + 1 < k.size(); m += 2) v.push_back({k[m], k[m + 1]});
      kinds_polygon_ = Polygon(std::move(v));
    }
    DeformingPolygon saved(polygon_state_from(s[s.size() - 2].values, deforming_->state()),
                           "flow solver restore: deforming body at t = " + std::to_string(time_),
                           deforming_->state().position.size());
    deforming_ = std::move(saved);
    place_body(time_);
    fresh_.clear();
  } else if (surface_motion_) {
    place_surface(time_, caller_surface_ ? surface_state_from(s.back().values, surface_state_) : surface_motion_(time_));
    fresh_.clear();
    for (int c = 0; c < 3; ++c) unraw(s[a++], body_velocity_[static_cast<std::size_t>(c)]);
  }
  if (sheet_) {
    next_sheet_.reset();
    const std::size_t n = sheet_->topology().nodes;
    std::size_t at = 0;
    const std::vector<double>& nodes = s[s.size() - 2].values;
    sheet_state_.position = take<Vec3>(nodes, at, n);
    sheet_state_.velocity = take<Vec3>(nodes, at, n);
    at = 0;
    sheet_impulse_ = take<Vec3>(s.back().values, at, sheet_->size());
  }
}

}  // namespace finverse::cfd
