// Incompressible Navier-Stokes solver on the stretched Cartesian grid (DESIGN.md section 5.1; seed
// paper section 2.3), 2-D and 3-D:
//
//     du/dt + div(u u) = -grad p + nu lap u + f,     div u = 0     (p is kinematic, p / rho).
//
// Cell-centred collocated u, v, (w), p plus face-normal velocities U for continuity (Zang, Street &
// Koseff 1994, J. Comput. Phys. 114:18), advanced by the second-order incremental pressure-correction
// (fractional-step) method of Van Kan (1986, SIAM J. Sci. Stat. Comput. 7:870):
//
//   1. predictor (momentum_predictor.cpp):
//        (u* - u^n)/dt = -[(1 + r/2) N^n - (r/2) N^{n-1}] - Gc p^n + nu/2 L(u* + u^n) + f^{n+1/2},
//      N = div(U u) conservative with face velocities U^n, r = dt/dt_old (Adams-Bashforth 2 with
//      variable steps; explicit Euler on the first step), Crank-Nicolson diffusion solved
//      implicitly (helmholtz_solver.hpp);
//   2. pressure correction (pressure_correction.cpp): the face predictor
//        U* = I(u*) + tau (I Gc - Gf) q, q = p^n or an extrapolation of it (tau = dt: the classical
//      U* = I(u* + dt Gc p^n) - dt Gf p^n; the face velocity feels the compact face gradient, so
//      no pressure checkerboard), then  Df Gf phi = Df U* / dt  by MG-PCG (poisson_solver.hpp),
//      warm started from the previous phi;
//   3. update (velocity_update.cpp): U = U* - dt Gf phi (discretely divergence-free to the Poisson
//      tolerance), u = u* - dt Gc phi, p^{n+1/2} = p^{n-1/2} + phi;
//   4. time-step control and health (time_step_control.cpp): fixed dt or a target CFL number, and a
//      one-line finverse::Error naming the step when the velocity is not finite or the CFL number
//      exceeds its limit.
// Immersed body (immerse(), Mittal et al. 2008 ghost-cell method; ghost_cells.hpp): the momentum
// system gets the ghost rows (immersed_momentum_solver.hpp); the pressure-correction Poisson
// equation stays symmetric: the faces of every non-fluid cell are closed with the face mask (zero
// correction flux), the face velocity on a fluid/ghost face is the interpolation of the
// ghost-extended u* (a second-order flux; their net over the body is removed, so no mass crosses
// the body), and phi and p get ghost values by the Neumann condition dp/dn = 0 at the boundary
// intercept, so the cell-centred pressure gradient next to the body is the sharp one (with
// viscous_wall_pressure, p's ghosts impose the wall's own momentum balance dp/dn = -nu d(omega)/ds
// instead, wall_pressure_gradient.hpp, in 3-D -nu n . curl(omega), wall_pressure_gradient_3d.hpp;
// phi keeps dp/dn = 0). At a
// steady state phi = 0 and the solution is the fixed point of the sharp discrete momentum and
// continuity equations; the masked correction only shapes the path to it.
// Moving rigid body (immerse(MovingBody), rigid_motion.hpp; Mittal et al. 2008 section 2.4): at the
// start of every step the body is placed at t^{n+1} and the cells re-classified; the ghost cells
// impose u_B = U + Omega x r at their boundary intercepts, the pressure ghosts dp/dn = -a_B . n.
// The new ghost values enter the implicit part of the step only: the explicit terms (convection
// N^n, the Crank-Nicolson half nu/2 L u^n) act on the state at t^n, so a ghost cell of the new
// geometry that was a fluid or ghost cell at t^n keeps its u^n (its fluid value, or the ghost value
// that imposed u_B at the body's t^n position). Re-imposing it for the t^{n+1} position moves the
// wall by U dt within those terms, an O(U dt / h) error of the near-wall shear (measured on a towed
// cylinder: docs/studies/cut_cell_balance.md).
// Cut-cell mass balance of a moving body (Seo & Mittal 2011, J. Comput. Phys. 230:7347; cut_faces.hpp):
// with the staircase balance above, the fluid volume and the position of the body's mass source
// jump by a cell whenever a cell is cleared or covered, and the pressure answers each jump with an
// impulse (the spurious force oscillations of sharp-interface methods; Lee, Kim, Choi & Yang 2011,
// J. Comput. Phys. 230:2677). With cut_cell_continuity (cut_cell_continuity_3d for a triangulated
// body) every cell with fluid on one of its faces takes part in the pressure correction, its faces
// weighted by their fluid apertures alpha_f (beta = alpha_f in the Poisson operator), and its
// balance carries the body's flux G_c through the piece of the body inside it exactly
// (cut_cell_balance.cpp):
//     sum_f alpha_f A_f U*_f - G_c = dt sum_f alpha_f A_f (Gf phi)_f,
// so the operator and the source change continuously with the body's position. A face between two
// fluid cells counts as whole (alpha = 1) even where the body cuts it: the momentum equations'
// cell-centred gradient spans it in full, and a projection with another weight there is no
// projection (a heaving box plate in a stream blew up). The faces with fluid get the correction with
// the solved phi (also in ghost cells), weighted by alpha: they store the mean velocity over the
// whole face, the solid part moving with the wall; then phi and p get their ghost values from the
// Neumann condition as before, for the cell-centred gradients of the momentum equations, which stay
// those of the ghost-cell method.
// A freshly cleared cell (solid at t^n, fluid at t^{n+1}) has no fluid history: its u^n (and p^n)
// is interpolated from its neighbours and its own boundary intercept with the same substituted
// bilinear stencil as an image point (ghost_cells.hpp), carrying the no-slip (Neumann) datum, and
// its old convective term N^{n-1}, which it never had, is replaced by N^n (Adams-Bashforth falls
// back to explicit Euler in that cell for one step). Without this (fresh_cell_treatment = false)
// the cell starts from its stale ghost value, a jump that shows as spikes in the force history.
// Triangulated body (3-D, issue 4; immerse(TriangulatedSurface) fixed, immerse(SurfaceMotion)
// moving or deforming; surface_geometry.hpp, ghost_cells.hpp): the same method with trilinear
// image-point stencils. A moving surface is re-placed at t^{n+1} at the start of every step (its
// hierarchy rebuilt, the cells re-classified); the ghost cells impose the vertex velocity
// interpolated linearly over the intercept's triangle, the pressure ghosts dp/dn = -a . n with the
// interpolated vertex acceleration, solid cells carry the velocity of their closest surface point,
// and freshly cleared cells get the same treatment as in 2-D (moving_surface.cpp).
// surface_forces() integrates the traction on the true surface per triangle
// (surface_traction_3d.hpp).
// Deforming body whose surface the caller sets (FSI, issue 32; seed paper section 2.3):
// immerse_deforming(reference) once, then before every step() set_body_state(next) with the
// body's vertex state at the new time level t^{n+1} = time() + next_dt(); the step places it
// there exactly as a moving body (2-D: deforming_polygon.hpp, the wall velocity and acceleration
// linear along each edge, solid cells with the velocity of their closest surface point, the
// cut-cell flux integrated over the clipped edges; 3-D: the triangulated body of immerse(
// SurfaceMotion)). A coupling iteration is restore(saved), set_body_state(iterate), step():
// state() holds the body's vertex state at time(), and restore() re-places the body from it.
// edge_traction() gives the 2-D traction samples by edge for the structure's loads.
// Boundary values for the new time level (inlet ramps, convective outlet, mass balance) are set in
// boundary_update.cpp; diagnostics (divergence, energy, momentum, CFL) in flow_diagnostics.cpp.
//
// Every reduction is ordered (field.hpp), so a run is bitwise reproducible for any thread count,
// and state()/restore() capture everything the future of a run depends on, so a restart from a
// checkpoint continues bitwise as the uninterrupted run.
#pragma once

#include <array>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cfd/poisson/poisson_boundary.hpp"
#include "cfd/immersed/cut_faces.hpp"
#include "cfd/immersed/deforming_polygon.hpp"
#include "cfd/grid/face_field.hpp"
#include "cfd/grid/field.hpp"
#include "cfd/grid/line_range.hpp"
#include "cfd/flow/velocity_boundary.hpp"
#include "cfd/immersed/ghost_cells.hpp"
#include "cfd/immersed/immersed_momentum_solver.hpp"
#include "cfd/forces/surface_traction.hpp"
#include "cfd/forces/wall_pressure_gradient.hpp"
#include "cfd/forces/wall_pressure_gradient_3d.hpp"
#include "cfd/grid/stretched_grid.hpp"
#include "cfd/flow/helmholtz_solver.hpp"
#include "cfd/poisson/poisson_solver.hpp"
#include "cfd/immersed/rigid_motion.hpp"
#include "cfd/immersed/sheet_forcing.hpp"
#include "cfd/immersed/sheet_markers.hpp"
#include "cfd/immersed/surface_geometry.hpp"
#include "cfd/immersed/triangulated_surface.hpp"

namespace finverse::cfd {

struct FlowOptions {
  double nu = 1e-3;   // kinematic viscosity [m^2/s]
  double dt = 0;      // > 0: fixed time step; 0: from the target CFL number
  double cfl = 0.5;   // target convective CFL number when dt == 0
  double dt_max = std::numeric_limits<double>::infinity();  // needed when dt == 0
  double max_dt_growth = 1.2;  // per step, when dt == 0 (keeps AB2 with variable steps smooth)
  double cfl_limit = 2.0;      // blow-up guard
  // Pressure-coupling time tau of the face predictor (pressure_correction.cpp). 0: tau = dt every
  // step (the classical form; the solution then carries an O(dt h^2) term). > 0: a fixed tau,
  // clamped to dt/2, with the pressure extrapolated to the new time level, which makes the error
  // O(h^2) + O(dt^2) with no mixed term: what a temporal convergence study at a fixed grid needs.
  double coupling_time = 0;
  bool convection = true;      // false: unsteady Stokes flow
  double helmholtz_rtol = 1e-12;
  int helmholtz_max_iterations = 1000;
  PoissonSolverOptions poisson = [] {
    PoissonSolverOptions o;
    o.rtol = 1e-10;
    return o;
  }();
  // Moving body: give freshly cleared cells interpolated values (false only to measure the spikes
  // that the treatment removes).
  bool fresh_cell_treatment = true;
  // Moving 2-D body (immerse(MovingBody), immerse_deforming(PolygonState)): the cut-cell mass
  // balance of Seo & Mittal 2011 in the pressure correction (see the header comment); false: the
  // staircase mass balance of the fixed bodies (only to measure the spurious force oscillations
  // that it removes).
  bool cut_cell_continuity = true;
  // The same for a moving triangulated body (immerse(SurfaceMotion)). Off here, so the solver's own
  // tests keep the balance they were written for; fin-cfd fin turns it on (FinFlowOptions).
  // Body cells that the surface splits into two fluid parts (split_cells: a plate thinner than the
  // cell) stay closed, so that no balance joins the fluid on the two sides of the plate; rim cells,
  // whose fluid wraps around the edge, stay open. The body faces keep the fluid cell's velocity on
  // their fluid part (cut_body_face_velocity), the staircase's closed faces the wall's
  // (body_face_velocities). Why each, with the force noise measured: docs/studies/cut_cell_balance.md.
  bool cut_cell_continuity_3d = false;
  // Moving triangulated body (immerse(SurfaceMotion)): the axes (x, y, z) along which it may reach
  // through both sides of the domain, which must then be slip walls. A slip wall is a symmetry
  // plane, so a body and flow that do not vary along the axis (a plate of constant section spanning
  // a slab between two slip walls) are the 2-D flow of the section with no periodic boundary
  // needed. The placement then checks only the other axes, the cut-cell balance integrates only
  // the surface inside the domain, and surface_forces() only the traction on it (SurfaceClip).
  // Off by default: a body leaving the domain is an error.
  std::array<bool, 3> surface_crosses{};
  // The same for fixed 2-D bodies (immerse(Polygon), immerse(regions)). Off here, so the solver's
  // own tests and the immersed-Couette order study keep the balance they were validated with; the
  // channel benchmarks (DFG, Turek-Hron) turn it on (DfgSetup, TurekHronSetup::cut_cell_continuity).
  // What it changes on each benchmark: docs/studies/cut_cell_balance.md.
  bool cut_cell_continuity_fixed = false;
  // Fixed 2-D bodies at rest: the pressure ghosts impose the wall's momentum balance
  // dp/dn = -nu d(omega)/ds (wall_pressure_gradient.hpp) instead of dp/dn = 0. Off here for the
  // same reason as cut_cell_continuity_fixed; the channel benchmarks turn it on (what it changes
  // there: docs/studies/wall_momentum_balance.md).
  bool viscous_wall_pressure = false;
  // 3-D fixed closed bodies without the cut-cell balance: the cell-centred gradients count a fluid
  // centre's closed face as zero gradient where the wall lies within half a spacing of the centre
  // (GhostCellSet::near_wall_faces), which cures the odd-even growth of such cells in the flap's
  // junction. Off by default: it moves the sphere's drag at D/20 from -0.6 % to -2.0 %
  // (docs/studies/pipe_flow.md, "Fluid centres at the wall").
  bool near_wall_closed_faces = false;
  // Body force per unit mass, evaluated at cell centres at t^{n+1/2}.
  VelocityFunction body_force;
};

struct StepStats {
  long step = 0;
  double time = 0, dt = 0, cfl = 0;
  int poisson_iterations = 0;
  double poisson_residual = 0;
  int helmholtz_iterations = 0;  // summed over the components
  double max_divergence = 0;     // max |Df U| after the step [1/s]
};

// One named array of the solver state (checkpoints).
struct StateArray {
  std::string name;
  std::vector<double> values;
};

// Bounding box {x0, x1, y0, y1, z0, z1} of a polygon (z: everything).
std::array<double, 6> polygon_box(const Polygon& p);

class FlowSolver {
 public:
  void setup(const StretchedGrid& grid, const FlowBoundary& boundary, const FlowOptions& options);

  // A fixed closed body (2-D); after setup, before initialise. Throws finverse::Error when the body
  // is too close to the domain boundary.
  void immerse(const Polygon& body);
  // Fixed solid regions whose walls may move tangentially (geometry at rest): the no-slip velocity
  // at a boundary intercept is wall_velocity(x, y, z, t) there (empty: zero). Fixed in time.
  void immerse(const std::vector<SolidRegion>& regions, const VelocityFunction& wall_velocity = {});
  // A rigidly moving closed body (2-D); after setup, before initialise (see the header comment).
  void immerse(const MovingBody& body);
  const MovingBody* moving_body() const { return moving_ ? &*moving_ : nullptr; }
  const RigidState& body_state() const { return body_state_; }  // at time()
  const Polygon& body_polygon() const { return body_now_; }     // moving body at time()
  // A fixed closed triangulated body (3-D); after setup, before initialise. Throws finverse::Error
  // when the surface is not watertight or consistently oriented, or too close to the domain
  // boundary.
  void immerse(const TriangulatedSurface& body);
  // A moving or deforming closed triangulated body (3-D): motion(t) gives the vertex positions,
  // velocities and accelerations at t (fixed connectivity); after setup, before initialise. It is
  // evaluated at once at time() (0 after setup), again at t0 by initialise and at every new time
  // level. The body must stay at least about three cells thick (ghost_cells.hpp) and keep its
  // volume: the net flux through the body's faces is removed (body_face_velocities), which is
  // exact only for a volume-preserving motion (rigid motion, bending of a closed thin body). A
  // placement at which the body's bounding box is not strictly inside the domain, or too close to
  // its boundary for the ghost cells, throws a one-line finverse::Error naming the time (except
  // along the axes of FlowOptions::surface_crosses).
  void immerse(const SurfaceMotion& motion);
  // The triangulated body at time() (null without one) and its state (motion(time()); for a fixed
  // body the surface with no velocity).
  const SurfaceGeometry* body_surface() const { return surface_ ? &*surface_ : nullptr; }
  const SurfaceState& surface_state() const { return surface_state_; }
  // Hydrodynamic force per triangle of the triangulated body at time() from the traction on the
  // true surface (surface_traction_3d.hpp), with the density rho [kg/m^3] (the solver's pressure is
  // kinematic). Builds the sampling stencils on every call (O(samples)); throws without a body.
  // With FlowOptions::surface_crosses, only the part inside the domain carries traction.
  SurfaceForces surface_forces(double rho = 1.0) const;
  // A deforming closed body whose surface the caller sets (FSI): its vertex state at time() (2-D:
  // a polygon of fixed vertex count and order; 3-D: a closed triangulated surface of fixed
  // connectivity, with the conditions of immerse(SurfaceMotion)); after setup, before initialise.
  void immerse_deforming(const PolygonState& reference);
  void immerse_deforming(const SurfaceState& reference);
  // The body's vertex state at the new time level t^{n+1} = time() + next_dt(), required before
  // every step() (the step consumes it). Throws a one-line finverse::Error naming t^{n+1} when the
  // vertex count (connectivity) changes or a value is not finite; the step throws, naming the time,
  // when the body leaves the domain or turns inside out.
  // kinds_at (2-D, optional): the cells' kinds (fluid / ghost / solid) of that placement are those
  // of this polygon instead of next's; the ghost geometry, the apertures and the wall data follow
  // next. A coupling step passes its first iterate for all its iterations, so that the flow's
  // response is continuous in next (a cell centre crossing the wall does not flip the cell's kind
  // between iterations; ghost_cells.hpp); the kinds are part of state().
  void set_body_state(const PolygonState& next, const PolygonState* kinds_at = nullptr);
  void set_body_state(const SurfaceState& next);
  // The time step the next step() takes (a function of the state at time()).
  double next_dt() const { return choose_time_step(); }
  // The 2-D deforming body at time() (null without one); the net flux int u_B . n dl of its last
  // placement, d(area)/dt, which the cut-cell balance removes (spread over the boundary by length)
  // so that the pressure equation stays compatible (exact for an area-preserving motion).
  const DeformingPolygon* deforming_body() const { return deforming_ ? &*deforming_ : nullptr; }
  double deforming_net_flux() const { return deforming_net_flux_; }
  // Traction samples of the 2-D deforming body at time(), by the caller's edges, with the density
  // rho (surface_traction.hpp, the wall velocity linear along each edge).
  EdgeTraction edge_traction(double rho = 1.0) const;
  // A zero-thickness immersed surface (sheet_forcing.hpp, sheet_step.cpp): the sheet's topology and
  // rest node positions (markers about options.spacing core cells apart, fixed in material
  // coordinates), after setup, before initialise; another immersed body must be fixed (immerse(), first). Its node
  // state at every new time level comes from `motion` (a fixed sheet: a motion that returns the
  // rest state), or, without one, from set_sheet_state() before every step() (coupled runs). No cell changes kind:
  // every cell is fluid, and after the momentum predictor the markers' forces make u* equal to the sheet's velocity at
  // every marker.
  void immerse_sheet(const SheetTopology& topology, const std::vector<Vec3>& rest, const SheetForcingOptions& options,
                     SheetMotion motion = {});
  // The sheet's node state at t^{n+1} = time() + next_dt() (a sheet without a motion function).
  void set_sheet_state(SheetState next);
  const SheetMarkers* sheet() const { return sheet_ ? &*sheet_ : nullptr; }
  const SheetState& sheet_state() const { return sheet_state_; }  // at time()
  // The force of the fluid on the sheet during the last step (rho times minus the markers'
  // impulses), per marker and per node; zero before the first step.
  // With SheetForcingOptions::band_correction, less the inertia of the fluid band that the kernel
  // moves with the sheet (sheet_band_correction in sheet_step.cpp).
  SheetLoads sheet_loads(double rho = 1.0) const;
  const SheetSolveStats& sheet_solve_stats() const { return sheet_stats_; }
  // Cells that were cleared at the start of the last step (i, j, k; k = 0 in 2-D).
  const std::vector<std::array<int, 3>>& freshly_cleared() const { return fresh_; }
  const GhostCellSet* immersed() const { return ib_ ? &*ib_ : nullptr; }
  bool fluid(int i, int j, int k) const { return !ib_ || ib_->kind(i, j, k) == CellKind::Fluid; }

  // Initial velocity (made discretely divergence-free by a projection) and pressure at time t0.
  void initialise(const VelocityFunction& velocity,
                  const std::function<double(double, double, double)>& pressure = {}, double t0 = 0);

  StepStats step();

  // On whole-flow MPI ranks (a rank share installed, the systems on the ranks) with no closed body:
  // compute the face velocities and the convective term on the rank's own lines only, the lines
  // whose right-hand sides its systems read (rank_lines.cpp; docs/studies/flow_mpi.md, "The
  // right-hand sides and the face velocities ..."). After such a step the face velocities and the stored
  // convective term are valid there and on the domain's boundary faces only, until
  // gather_rank_lines() (collective: every rank calls it) makes them whole again; state(),
  // cell_output() and face_velocity() refuse until then. Off by default; no effect on one process.
  void compute_on_rank_lines(bool on) { rank_lines_wanted_ = on; }
  void gather_rank_lines();
  bool fields_partial() const { return partial_; }

  // Output: cell-centred velocity component c, kinematic pressure, face velocities.
  const Field& u(int c) const { return u_[static_cast<std::size_t>(c)]; }
  // Kinematic pressure of the scheme (Van Kan's p^{n+1/2}, first order at t - dt/2), and the
  // output pressure: second order at t - dt/2 (Brown, Cortez & Minion 2001, J. Comput. Phys.
  // 168:464, p + phi - (nu dt/2) L phi).
  const Field& p() const { return p_; }
  Field pressure() const;
  const FaceField& face_velocity() const {
    require_whole("face_velocity");
    return U_;
  }
  const StretchedGrid& grid() const { return grid_; }
  const FlowOptions& options() const { return opt_; }
  // The pressure solver's set-up and solve time so far (threaded or on ranks).
  const PoissonTimes& pressure_times() const { return poisson_.times(); }
  const FlowBoundary& boundary() const { return bnd_; }
  int dim() const { return grid_.dim(); }
  double time() const { return time_; }
  long steps() const { return step_; }
  double last_dt() const { return dt_old_; }

  // Cell-centred output arrays (interior cells, x fastest): "velocity" [n, 3], "pressure" [n]
  // (kinematic), "divergence" [n] (of the face velocities), "vorticity" [n, 3] and "lambda2" [n]
  // (Jeong & Hussain's vortex criterion, vortex_identification.hpp; zero in solid cells).
  std::vector<StateArray> cell_output() const;

  // Diagnostics (flow_diagnostics.cpp), all deterministic.
  double max_divergence() const;     // max over cells of |sum_f U_f A_f| / V (cut cells: their balance)
  double kinetic_energy() const;     // sum V |u|^2 / 2
  double momentum(int c) const;      // sum V u_c
  double cfl(double dt) const;       // dt max sum_d |u_d| / h_d

  // Checkpointing: every array the next steps depend on, and its inverse (same setup required).
  std::vector<StateArray> state() const;
  void restore(const std::vector<StateArray>& state);

  // A partitioned coupling repeats each step from its restored start with an updated interface
  // (implicit_coupling.hpp). With this on, a repeat of the step just computed starts its momentum
  // and pressure-correction solves from that step's solutions instead of from u^n and phi^n: the
  // iterates differ by the coupling's correction, so the solves need fewer iterations. The result
  // depends on the previous iterate only within the solvers' tolerances. A restart from a
  // checkpoint, or any step computed for the first time, starts as before (bitwise).
  void warm_start_repeated_steps(bool on);

 private:
  // rank_lines.cpp: the lines this step computes its face velocities (faces_) and convective term
  // (own_) on; throws std::logic_error naming `what` while the fields are partial.
  void choose_rank_lines();
  void require_whole(const char* what) const;

  // time_step_control.cpp
  double choose_time_step() const;
  // Throws on a blown-up field or a CFL number `cfl_now` (= cfl(dt), computed once per step by
  // the caller, which reports it too) above the limit.
  void check_health(double dt, double cfl_now) const;
  // boundary_update.cpp
  void set_boundary_values(double t, double dt, bool initial);
  // momentum_predictor.cpp
  void convective_term(std::array<Field, 3>& out) const;
  void predict_momentum(double dt);
  // pressure_correction.cpp
  void face_predictor(double dt, double tau);
  double coupling_time(double dt) const;
  PoissonSolveStats solve_pressure_correction(double dt);
  // velocity_update.cpp
  void update_velocity(double dt);
  // Shared kernels (flow_solver.cpp). The face kernels run several times per cell and step in the
  // convective, viscous and projection loops: their interior case is inline (below the class), the
  // boundary faces go to the out-of-line part.
  double face_area(int d, int i, int j, int k) const;
  double face_value(const Field& q, int c, int d, int i, int j, int k, const std::array<BoundaryValues, 3>& bv) const;
  double boundary_face_value(const Field& q, int c, int d, int i, int j, int k,
                             const std::array<BoundaryValues, 3>& bv) const;
  double face_gradient(const Field& q, int d, int i, int j, int k) const;
  double boundary_face_gradient(const Field& q, int d, int i, int j, int k) const;
  void cell_gradient(const Field& q, int d, Field& out) const { cell_gradient(q, d, out, all_lines(grid_)); }
  // The same on `lines` only (out elsewhere untouched).
  void cell_gradient(const Field& q, int d, Field& out, const LineRange& lines) const;
  double cell_gradient_at(const Field& q, int d, int i, int j, int k) const;
  double divergence(const FaceField& U, int i, int j, int k) const;
  // The divergence of the continuity constraint: the cut-cell balance (per unit cell volume) in the
  // cut cells of a moving body with cut_cell_continuity, divergence() elsewhere.
  double continuity_residual(const FaceField& U, int i, int j, int k) const;
  bool cut_cell_mode() const { return cut_.has_value(); }
  std::size_t side_index(Side s, int i, int j, int k) const;
  // Face (d; i, j, k) between two cells of which at least one is not fluid (closed for phi).
  bool masked_face(int d, int i, int j, int k) const;
  // Immersed boundary: ghost values of the velocity (Dirichlet) and of a pressure-like field
  // (homogeneous Neumann); face velocities on the body's faces with zero net flux.
  void impose_body_velocity();
  // Moving body (rigid or deforming 2-D): geometry, ghost data and pressure operator at time t; the
  // step to t. A deforming body is placed at its current state deforming_.
  void place_body(double t);
  // The wall velocity and acceleration of the moving 2-D body at a point of body_now_.closest().
  std::array<double, 2> wall_velocity_2d(const SurfacePoint& b) const;
  std::array<double, 2> wall_acceleration_2d(const SurfacePoint& b) const;
  // Cut-cell balance (cut_cell_balance.cpp): the apertures of the current geometry, the cut cells
  // among those of the body's bounding box {x0, x1, y0, y1, z0, z1} and their body fluxes G_c (a
  // moving polygon's from the rigid motion, plus piece_flux, the fluxes of a triangulated body's
  // pieces by cell); wall_velocity(d, x): component d of the wall's velocity near x (empty: at rest);
  // split: the cells the surface splits (split_cells), whose body cells stay closed; without it
  // (a polygon) every body cell with fluid cells on two opposite sides stays closed.
  void place_cut_cells(CutFaces faces, const std::array<double, 6>& box,
                       const std::vector<std::pair<std::array<int, 3>, double>>& piece_flux = {},
                       const std::function<double(int, const Vec3&)>& wall_velocity = {},
                       const std::vector<std::array<int, 3>>* split = nullptr);
  bool cut_cell(int i, int j, int k) const;
  // The pressure operator of the current geometry: faces weighted by their apertures with the
  // cut-cell balance, else every face of a non-fluid cell closed (the multigrid is rebuilt).
  void setup_pressure_operator();
  // The cut-cell balance of cut cell n (sum_f alpha_f A_f U_f - G_c) with the fluid parts' face
  // velocities U(d, i, j, k).
  double cut_balance(std::size_t n, const std::function<double(int, int, int, int)>& U) const;
  void move_body(double t);
  void body_face_velocities(FaceField& U, const std::array<Field, 3>& u) const;
  // The masked interior faces of the current geometry in the order (d, k, j, i) of a full scan,
  // collected once per geometry change (after every ib_.emplace) so that body_face_velocities
  // loops over the body's faces only; `side`: +1 lower cell fluid, -1 upper cell fluid, 0 both
  // non-fluid.
  void index_body_faces();
  struct BodyFace {
    int d, i, j, k, side;
  };
  std::vector<BodyFace> body_faces_;
  // The predicted velocity of a body face of a moving triangulated body in cut-cell mode.
  double cut_body_face_velocity(const BodyFace& b, const Field& ud) const;
  // Moving triangulated body (moving_surface.cpp).
  // The surface placed at time t with state st (of motion(t), or the caller's).
  void place_surface(double t, SurfaceState st);
  void place_surface_cut_cells();  // cut-cell balance of the placed surface (moving_surface.cpp)
  void move_surface(double t, SurfaceState st);
  // A freshly cleared cell's data (cleared_cells.cpp): stencils at P = x + offset n, the wall
  // velocity and dp/dn at its boundary intercept, d / (d + offset), offset.
  struct ClearedCell {
    PointStencil vel, pres;
    std::array<double, 3> ub{};
    double dpdn = 0, fraction = 0, offset = 0;
  };
  // Values of the cleared cells (fresh_, with their data cells[n]) iterated together with the
  // ghost values, then the pressure-like ghosts and the cleared cells' face fluxes; ghost cells of
  // the new geometry that were not solid in `old` (the classification at t^n) get their u^n back.
  void settle_cleared_cells(const GhostCellSet& old, const std::vector<ClearedCell>& cells);

  // Zero-thickness sheet (sheet_step.cpp): forcing after the momentum predictor.
  void force_sheet(double dt, SheetState next);
  void add_sheet_impulse(double dt);
  std::vector<Vec3> sheet_band_correction() const;
  void force_initial_sheet(double t0);
  std::vector<Vec3> sheet_marker_position_;
  std::optional<RegularizedStencils> sheet_stencils_;  // of the last placement
  std::vector<Vec3> sheet_marker_velocity_;
  std::vector<Vec3> sheet_marker_acceleration_;  // over the last step
  std::optional<SheetMarkers> sheet_;
  SheetForcingOptions sheet_opt_;
  SheetMotion sheet_motion_;
  std::optional<SheetState> next_sheet_;
  SheetState sheet_state_;
  std::vector<Vec3> sheet_impulse_;  // per marker: g, the impulse per unit density given to the fluid
  SheetSolveStats sheet_stats_;

  StretchedGrid grid_;
  FlowBoundary bnd_;
  FlowOptions opt_;
  FaceCoefficients beta_;
  std::array<HelmholtzSolver, 3> helmholtz_;
  PoissonSolver poisson_;
  std::optional<GhostCellSet> ib_;
  std::array<std::vector<double>, 3> ib_wall_;  // per component, per ghost cell: u_B (empty: 0)
  ImmersedMomentumSolver ib_momentum_;
  std::optional<WallPressureGradient> wall_dpdn_;  // viscous_wall_pressure on a fixed 2-D body
  std::optional<WallPressureGradient3D> wall_dpdn_3d_;  // ... on a fixed triangulated body
  std::vector<double> ib_dpdn_;  // per ghost cell: dp/dn at the intercept (empty: 0)
  std::optional<MovingBody> moving_;
  RigidState body_state_;
  // Deforming body whose state the caller sets: 2-D at time(), and the state for the next step
  // (2-D or 3-D); caller_surface_: the 3-D body takes its states from set_body_state.
  std::optional<DeformingPolygon> deforming_;
  std::optional<PolygonState> next_polygon_;
  // The polygon whose cell kinds the placement at time() uses (set_body_state's kinds_at; empty:
  // the body's own), and the one for the next step.
  std::optional<Polygon> kinds_polygon_, next_kinds_;
  std::optional<SurfaceState> next_surface_;
  bool caller_surface_ = false;
  double deforming_net_flux_ = 0;
  Polygon body_now_ = Polygon::circle(0, 0, 1, 3);
  // Cut-cell mass balance (cut_cell_continuity): the apertures of the current placement, the cells
  // whose balance differs from the plain divergence (not fluid, or a face not all fluid, and some
  // fluid on a face), and phi as solved, before its Neumann ghost values.
  std::optional<CutFaces> cut_;
  std::vector<std::array<int, 3>> cut_cells_;
  std::vector<double> cut_flux_;  // G_c per cut cell
  std::vector<int> cut_slot_;     // per cell: its index in cut_cells_, or -1
  double cut_residual_max_ = 0;   // max over the cut cells of |balance| / V after the last update
  Field phi_solved_;
  std::vector<std::array<int, 3>> fresh_;
  std::optional<SurfaceGeometry> surface_;
  SurfaceMotion surface_motion_;
  SurfaceState surface_state_;
  std::array<Field, 3> body_velocity_;  // moving triangulated body: the velocity of solid cells

  std::array<Field, 3> u_, ustar_, conv_, conv_old_, work_;
  Field p_, phi_, rhs_, zero_, grad_, bterm_;
  FaceField U_, Ustar_;
  // Per component: boundary values at t^n and t^{n+1} (Dirichlet: the velocity on the face;
  // Neumann: empty = zero normal derivative).
  std::array<BoundaryValues, 3> bv_, bv_new_;
  double time_ = 0, dt_old_ = 0;
  long step_ = 0;
  int last_helmholtz_iterations_ = 0;
  // warm_start_repeated_steps: the last computed step's index and its first u* and phi solutions,
  // and whether the step now being computed repeats it (set by restore()).
  bool warm_start_repeats_ = false, repeating_ = false;
  // restore()'s placement defers the pressure operator's set-up (setup_pressure_operator).
  bool defer_pressure_setup_ = false, pressure_stale_ = false;
  long solved_step_ = -1;
  std::array<Field, 3> solved_ustar_;
  Field solved_phi_;
  // compute_on_rank_lines: wanted, whether the fields are partial now, and this step's lines.
  bool rank_lines_wanted_ = false, partial_ = false;
  LineRange own_, faces_;
};

inline double FlowSolver::face_area(int d, int i, int j, int k) const { return grid_.face_area(d, i, j, k); }

// Linear interpolation to the face between the centres of its two cells (second order on smooth
// stretched grids: the weight accounts for the face not being midway between the centres).
inline double FlowSolver::face_value(const Field& q, int c, int d, int i, int j, int k,
                                     const std::array<BoundaryValues, 3>& bv) const {
  const Axis& ax = grid_.axis(d);
  const int f = d == 0 ? i : d == 1 ? j : k;
  if (f <= 0 || f >= ax.size()) return boundary_face_value(q, c, d, i, j, k, bv);
  const int li = i - (d == 0), lj = j - (d == 1), lk = k - (d == 2);
  const double wl = ax.lower_weight(f);
  return wl * q(li, lj, lk) + (1 - wl) * q(i, j, k);
}

// Compact gradient across the face.
inline double FlowSolver::face_gradient(const Field& q, int d, int i, int j, int k) const {
  const Axis& ax = grid_.axis(d);
  const int f = d == 0 ? i : d == 1 ? j : k;
  if (f <= 0 || f >= ax.size()) return boundary_face_gradient(q, d, i, j, k);
  const double dist = ax.centre_distance(f);
  return (q(i, j, k) - q(i - (d == 0), j - (d == 1), k - (d == 2))) / dist;
}

}  // namespace finverse::cfd
