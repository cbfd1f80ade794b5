// The Hessenthaler (2017) Phase I experiment in 3-D: the steady partitioned fixed point on the
// time-mean load; see hessenthaler_phase1_fsi.hpp.
#include "fsi/validation/hessenthaler_phase1_fsi.hpp"
#include "fsi/validation/flow_planes.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>


#include "cfd/cases/case_file.hpp"
#include "cfd/cases/flow_case.hpp"
#include "cfd/flow/flow_solver.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "core/printf_format.hpp"
#include "fem/static_solver.hpp"

namespace finverse::fsi::validation {

namespace fv = fem::validation;

double centreline_rms(const std::vector<std::array<double, 2>>& sim, const std::vector<std::array<double, 2>>& measured) {
  if (sim.size() < 2) throw Error("centreline_rms: the simulated centreline needs two points");
  double sum = 0;
  for (const auto& [z, y] : measured) {
    double ys = sim.back()[1];
    for (std::size_t k = 0; k + 1 < sim.size(); ++k)
      if (z >= sim[k][0] && z <= sim[k + 1][0]) {
        const double dz = sim[k + 1][0] - sim[k][0];
        const double a = dz > 0 ? (z - sim[k][0]) / dz : 0;
        ys = (1 - a) * sim[k][1] + a * sim[k + 1][1];
        break;
      }
    if (z < sim.front()[0]) ys = sim.front()[1];
    sum += (ys - y) * (ys - y);
  }
  return std::sqrt(sum / static_cast<double>(measured.size()));
}

namespace {

// The flap's frame (along +x from the clamp, width along y from 0 to b, buoyancy along +z) in
// the flow's (the clamp's centre at the origin, the flap along +z, its width along x, the
// buoyancy along +y): a rotation (a cyclic permutation of the axes) and a shift of b / 2.
cfd::Vec3 to_flow(const fem::Vec3& p, double width) { return {p.y() - 0.5 * width, p.z(), p.x()}; }
fem::Vec3 force_to_flap(const cfd::Vec3& f) { return fem::Vec3(f[2], f[0], f[1]); }

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// One iterate: the load averaged over its window with the sheet held, and what the structure
// made of it.
struct Window {
  double start = 0, end = 0, span = 0;
  Eigen::VectorXd load;  // time integral of the nodal loads [N s], 3 per node
  std::array<double, 3> force{0, 0, 0};
  double fy2 = 0;
  double tip_in = 0, tip_out = 0;  // S(f) and S(F) [m]
  double residual = 0;             // max node distance between S(F) and the held shape [m]

  void add(double dt, const cfd::SheetLoads& L) {
    if (load.size() == 0) load = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(3 * L.nodal.size()));
    for (std::size_t i = 0; i < L.nodal.size(); ++i)
      for (int d = 0; d < 3; ++d) load[static_cast<Eigen::Index>(3 * i + static_cast<std::size_t>(d))] += dt * L.nodal[i][d];
    span += dt;
    for (int d = 0; d < 3; ++d) force[d] += dt * L.total[d];
    fy2 += dt * L.total[1] * L.total[1];
  }
  double force_mean(int d) const { return force[d] / span; }
  double force_y_std() const {
    const double m = force_mean(1);
    return std::sqrt(std::max(0.0, fy2 / span - m * m));
  }
};

// The run as named steps: set_up, develop (the flow's start with the flap held), couple (hold,
// average, relax, move; iterate by iterate), summary.
class PhaseIRun {
 public:
  explicit PhaseIRun(const HessenthalerPhaseIOptions& o) : o_(o), t0_(std::chrono::steady_clock::now()) {}

  Summary run() {
    set_up();
    develop();
    couple();
    if (!o_.planes_file.empty()) {
      std::vector<FlowPlane> planes;
      for (double z : o_.plane_z) planes.push_back(sample_flow_plane(flow_, z));
      write_flow_planes(o_.planes_file, planes);
      say("wrote " + o_.planes_file.string());
    }
    if (!o_.loads_file.empty()) write_loads();
    return summary();
  }

 private:
  // The flap, the flow case (its grid, inflows and walls), the sheet at the start shape.
  void set_up() {
    flap_ = fv::read_hessenthaler_flap(o_.reference);
    if (!(o_.youngs_modulus > 0)) throw Error("flap phase I: --youngs-modulus must be > 0 (fin-fit flap)");
    if (!(o_.window_time > 0) || !(o_.move_speed > 0) || o_.max_iterations < 1 || !(o_.omega > 0))
      throw Error("flap phase I: --window-time, --move-speed and --omega must be > 0, --max-iterations >= 1");
    measured_ = fv::read_mri_centreline(o_.centreline);
    const cfd::cases::CaseFile c = cfd::cases::read_case_file(o_.flow_case, false);
    if (c.kind != "flow") throw Error(o_.flow_case.string() + ": expected case: flow (the junction's walls and inflows)");
    spec_ = c.flow;
    if (spec_.dim != 3) throw Error(o_.flow_case.string() + ": the flap's flow must be 3-D");
    for (const auto& b : spec_.bodies)
      if (b.sheet || (b.motion && b.motion->moves()))
        throw Error(o_.flow_case.string() + ": body " + b.name +
                    ": the flap's flow takes fixed closed bodies only (the flap is added as a sheet)");
    if (o_.h > 0) {
      spec_.h = o_.h;
      spec_.dt_max = 0;
    }
    if (!(o_.viscosity_factor > 0) || !(o_.inflow_factor > 0))
      throw Error("flap phase I: --viscosity-factor and --inflow-factor must be > 0");
    spec_.nu *= o_.viscosity_factor;
    for (auto& side : spec_.sides) {
      for (double& v : side.velocity) v *= o_.inflow_factor;
      for (auto& pipe : side.pipes) pipe.speed *= o_.inflow_factor;
    }
    grid_.emplace(cfd::cases::flow_case_grid(spec_));
    const cfd::FlowOptions flow_options = cfd::cases::flow_case_options(spec_);
    dt_max_ = flow_options.dt_max;
    flow_.setup(*grid_, cfd::cases::flow_case_boundary(spec_), flow_options);
    std::vector<std::size_t> first;
    flow_.immerse(cfd::cases::merged_bodies(spec_.bodies, first, nullptr));
    // The structure: its mid-surface is the sheet, node for node.
    const fv::FlapShellModel shell = fv::flap_shell_model(flap_, o_.youngs_modulus, o_.mesh);
    n_ = shell.grid.nodes.size();
    rows_ = shell.rows;
    std::vector<cfd::Vec3> rest;
    for (const fem::Vec3& p : shell.model.reference_positions()) rest.push_back(to_flow(p, flap_.width));
    x_ = stack(rest);
    check_inside_walls(x_, "at rest");
    if (!o_.start_straight) x_ = solve_structure(Eigen::VectorXd::Zero(static_cast<Eigen::Index>(3 * n_)));
    check_inside_walls(x_, "in its start shape");
    final_ = x_;
    cfd::SheetForcingOptions so = spec_.sheet;
    // The load less the inertia of the fluid band the kernel moves with the sheet: the steady load
    // is the same, and the relaxation's own jolts (each leg's change of velocity, times the band's
    // mass, over dt) stay out of the filter. The structure here has no mass to go negative.
    so.band_correction = true;
    // No motion function: the run sets the sheet's state before every step.
    flow_.immerse_sheet(cfd::SheetTopology{3, n_, shell.grid.triangles}, rest, so, {});
    flow_.initialise([](double, double, double, double) { return std::array<double, 3>{0, 0, 0}; });
    say("set up: " + std::to_string(grid_->nx()) + " x " + std::to_string(grid_->ny()) + " x " +
        std::to_string(grid_->nz()) + " cells, h " + num(spec_.h * 1e3) + " mm, flap " +
        std::to_string(o_.mesh.along) + " x " + std::to_string(o_.mesh.across) + " shell cells, " +
        std::to_string(flow_.sheet()->size()) + " markers; start tip " + num(tip(x_) * 1e3) + " mm");
  }

  // A flap that sticks through a wall (the reference's geometry too big for the junction): a node
  // beyond the clamp row in a solid cell deeper than the ghost layer.
  void check_inside_walls(const Eigen::VectorXd& x, const char* when) const {
    const cfd::GhostCellSet* walls = flow_.immersed();
    if (!walls) return;
    const auto cell = [&](int d, double v) {
      const auto& f = grid_->axis(d).faces();
      return static_cast<int>(std::upper_bound(f.begin(), f.end(), v) - f.begin()) - 1;
    };
    std::vector<bool> clamp(n_, false);
    for (const auto& [node, w] : rows_.front()) clamp[static_cast<std::size_t>(node)] = true;
    for (std::size_t i = 0; i < n_; ++i) {
      if (clamp[i]) continue;
      const auto k = static_cast<Eigen::Index>(3 * i);
      const int c[3] = {cell(0, x[k]), cell(1, x[k + 1]), cell(2, x[k + 2])};
      const bool inside = c[0] >= 0 && c[0] < grid_->nx() && c[1] >= 0 && c[1] < grid_->ny() && c[2] >= 0 &&
                          c[2] < grid_->nz();
      if (!inside || walls->kind(c[0], c[1], c[2]) == cfd::CellKind::Solid)
        throw Error(o_.reference.string() + ": the flap (" + num(flap_.length * 1e3) + " x " +
                    num(flap_.width * 1e3) + " mm) sticks through the walls of " + o_.flow_case.string() + " " +
                    when + ": its node at (" + num(x[k] * 1e3) + ", " + num(x[k + 1] * 1e3) + ", " +
                    num(x[k + 2] * 1e3) + ") mm is in the solid");
    }
  }

  // The flow's start: the inflow ramps up with the flap held at its start shape.
  void develop() { hold(o_.develop_time - flow_.time(), nullptr); }

  // The coupling as a root search on the tip t. The held shape x(t) is the structure under its
  // buoyancy and a transverse tip load mu (the one-parameter family of the first bending mode,
  // which the flap's steady deflection is); held there, the flow settles and its load F is averaged
  // over a window, and phi(t) = tip(S(F)) - t is how far the structure's answer to that load is from
  // the held tip. The root (phi = 0, bracketed, then the Illinois variant of regula falsi) is the
  // steady state; its S(F) is the flap's shape. Why not a fixed point on the whole nodal load
  // (IQN-ILS, Aitken): the load's map is so steep (the tip's compliance ~70 m/N against a jet's
  // edge) that 5 % of the first load flips the flap to the other side, and the secants of a
  // 500-dimensional iterate stalled 25 mm from the answer (docs/studies/hessenthaler_flap.md).
  void couple() {
    double mu = 0;
    struct Point {
      double t, phi;
    };
    std::optional<Point> a, b;
    double t = tip(x_);
    for (int k = 1; k <= o_.max_iterations; ++k) {
      if (k > 1) {
        const double mu_next = tip_load_for(t, mu);
        move_to(tip_load(mu), tip_load(mu_next));
        mu = mu_next;
      }
      const Window w = evaluate();
      const Point p{w.tip_in, w.tip_out - w.tip_in};
      if (std::abs(p.phi) < o_.tolerance) {
        converged_ = true;
        return;
      }
      if (k == o_.max_iterations) return;
      // The next tip: towards the answer until the sign of phi changes, then regula falsi.
      if (!a) {
        a = p;
        t = p.t + o_.omega * p.phi;
      } else if (!b) {
        if ((p.phi > 0) == (a->phi > 0)) {
          const double slope = (p.phi - a->phi) / (p.t - a->t);
          a = p;  // still on one side: a secant step, or the relaxed step where it points away
          t = slope < 0 ? p.t - p.phi / slope : p.t + o_.omega * p.phi;
        } else {
          b = p;
        }
      } else if ((p.phi > 0) == (b->phi > 0)) {
        a->phi *= 0.5;  // Illinois: the stale end's weight halved
        b = p;
      } else {
        a = b;
        b = p;
      }
      if (!b) continue;
      // A root bracketed closer than the tolerance is found, whatever phi still says at its ends:
      // the flow's load at one shape differs with its history and its slow development (the
      // mismatch left at the root is reported).
      if (std::abs(b->t - a->t) < o_.tolerance) {
        converged_ = true;
        return;
      }
      t = b->t - b->phi * (b->t - a->t) / (b->phi - a->phi);
    }
  }

  // One evaluation at the held shape: settle, average the load over the window, the structure's
  // answer to it.
  Window evaluate() {
    hold(o_.settle_time, nullptr);
    Window w;
    w.start = flow_.time();
    hold(o_.window_time, &w);
    w.end = flow_.time();
    const Eigen::VectorXd x_out = solve_structure(w.load / w.span);
    w.tip_in = tip(x_);
    w.tip_out = tip(x_out);
    w.residual = max_node_distance(x_out, x_);
    final_ = x_out;
    windows_.push_back(w);
    report(w);
    return w;
  }

  // The nodal load (flow frame) of a transverse tip load mu [N] along +y, spread over the tip row.
  Eigen::VectorXd tip_load(double mu) const {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(3 * n_));
    for (const auto& [node, w] : rows_.back()) f[3 * node + 1] = mu * w;
    return f;
  }
  // The tip load that holds the tip at t (secant from mu0; the tip is monotonic in mu).
  double tip_load_for(double t, double mu0) {
    double m0 = mu0, t0 = tip(solve_structure(tip_load(m0)));
    double m1 = m0 + (t - t0) / 70.0, t1 = tip(solve_structure(tip_load(m1)));  // ~70 m/N: a first guess
    for (int i = 0; i < 40 && std::abs(t1 - t) > 1e-7; ++i) {
      const double m2 = m1 - (t1 - t) * (m1 - m0) / (t1 - t0);
      m0 = m1, t0 = t1;
      m1 = m2, t1 = tip(solve_structure(tip_load(m1)));
    }
    if (std::abs(t1 - t) > 1e-6)
      throw Error("flap phase I: no tip load holds the tip at " + num(t * 1e3) + " mm (reached " + num(t1 * 1e3) +
                  " mm)");
    return m1;
  }

  // The flow steps on for `span` seconds with the sheet held; into the window w its loads.
  void hold(double span, Window* w) {
    const double t_end = flow_.time() + span;
    while (flow_.time() < t_end - 1e-12) {
      const cfd::StepStats st = step(x_, Eigen::VectorXd::Zero(x_.size()));
      if (!w) continue;
      const cfd::SheetLoads L = flow_.sheet_loads(spec_.rho);
      w->add(st.dt, L);
    }
  }

  // The sheet moves from S(f_from) to S(f_to) in a smooth step (zero velocity at both ends)
  // through equilibrium shapes S(f) at loads evenly between, each at most a cell apart (a blend of
  // two distant bent shapes would shorten the sheet and crowd its markers), no faster on average
  // than move_speed.
  void move_to(const Eigen::VectorXd& f_from, const Eigen::VectorXd& f_to) {
    const Eigen::VectorXd x_to = solve_structure(f_to);
    const double distance = max_node_distance(x_, x_to);
    const int stages = std::max(1, static_cast<int>(std::ceil(distance / spec_.h)));
    std::vector<Eigen::VectorXd> path{x_};
    for (int j = 1; j < stages; ++j) path.push_back(solve_structure(f_from + (f_to - f_from) * (double(j) / stages)));
    path.push_back(x_to);
    const double t0 = flow_.time(), duration = std::max(o_.move_time, distance / o_.move_speed);
    const auto at = [&](double t, Eigen::VectorXd& x, Eigen::VectorXd& v) {
      const double tau = std::clamp((t - t0) / duration, 0.0, 1.0);
      const double s = tau * tau * (3 - 2 * tau) * stages, ds = 6 * tau * (1 - tau) / duration * stages;
      const int j = std::min(static_cast<int>(s), stages - 1);
      x = path[static_cast<std::size_t>(j)] + (s - j) * (path[static_cast<std::size_t>(j + 1)] - path[static_cast<std::size_t>(j)]);
      v = ds * (path[static_cast<std::size_t>(j + 1)] - path[static_cast<std::size_t>(j)]);
    };
    Eigen::VectorXd x, v;
    while (flow_.time() < t0 + duration - 1e-12) {
      at(flow_.time() + flow_.next_dt(), x, v);
      step(x, v);
    }
    x_ = x_to;
  }

  // One flow step to the sheet's state x, v at the new time level.
  cfd::StepStats step(const Eigen::VectorXd& x, const Eigen::VectorXd& v) {
    cfd::SheetState next;
    next.position.resize(n_);
    next.velocity.resize(n_);
    for (std::size_t i = 0; i < n_; ++i)
      for (int d = 0; d < 3; ++d) {
        const auto k = static_cast<Eigen::Index>(3 * i + static_cast<std::size_t>(d));
        next.position[i][d] = x[k];
        next.velocity[i][d] = v[k];
      }
    flow_.set_sheet_state(std::move(next));
    const cfd::StepStats st = flow_.step();
    ++steps_;
    // A flow blowing up under the adaptive step only shrinks dt (its CFL stays at the target):
    // a step 100 times below the case's dt_max means velocities 100 times the inflow's.
    if (st.dt < 1e-2 * dt_max_)
      throw Error("flap phase I: step " + std::to_string(steps_) + " (t = " + num(st.time) + " s): dt " + num(st.dt) +
                  " s, 1 % of the case's " + num(dt_max_) + " s: the flow is blowing up (" + fastest() + ")");
    if (steps_ % 100 == 0)
      say("step " + std::to_string(steps_) + "  t " + num(st.time) + " s  CFL " + num(st.cfl) + "  Poisson " +
          std::to_string(st.poisson_iterations) + " it  " + fastest() + "  tip " + num(tip(x) * 1e3) +
          " mm  wall " + num(seconds_since(t0_)) + " s");
    return st;
  }

  // The static nonlinear flap under its net buoyancy and the nodal flow loads f (dead loads in the
  // flow's frame, 3 per node), from the straight reference in load steps; its nodes in the flow's
  // frame.
  Eigen::VectorXd solve_structure(const Eigen::VectorXd& f) {
    ++structure_solves_;
    fv::FlapShellModel shell = fv::flap_shell_model(flap_, o_.youngs_modulus, o_.mesh);
    fem::Model& model = shell.model;
    // The buoyancy lumped on the nodes as fin-fit flap does: a row's share of the length (half
    // at the tip), split across the width by the row's weights; along the flap frame's +z.
    const double q = flap_.buoyancy_per_length(), ds = flap_.length / o_.mesh.along;
    for (std::size_t i = 1; i < rows_.size(); ++i)
      for (const auto& [node, w] : rows_[i])
        model.add_nodal_load(node, 2, q * ds * (i + 1 == rows_.size() ? 0.5 : 1.0) * w);
    for (std::size_t i = 0; i < n_; ++i) {
      const auto k = static_cast<Eigen::Index>(3 * i);
      const fem::Vec3 load = force_to_flap({f[k], f[k + 1], f[k + 2]});
      for (int d = 0; d < 3; ++d)
        if (load[d] != 0) model.add_nodal_load(static_cast<int>(i), d, load[d]);
    }
    fem::StaticOptions so;
    so.steps = 8;
    fem::StaticSolver solver(model, so);
    fem::NodalState state = model.reference_state();
    solver.solve(state, 0.0, 1.0);
    std::vector<cfd::Vec3> x;
    for (const fem::Vec3& p : state.position) x.push_back(to_flow(p, flap_.width));
    return stack(x);
  }

  static double max_node_distance(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    double m = 0;
    for (Eigen::Index i = 0; i < a.size() / 3; ++i) m = std::max(m, (a.segment<3>(3 * i) - b.segment<3>(3 * i)).norm());
    return m;
  }

  // The fastest cell-centred velocity and where it is: the first sign of a flow going wrong.
  std::string fastest() const {
    double best = -1;
    std::array<double, 3> at{0, 0, 0};
    const cfd::StretchedGrid& g = *grid_;
    for (int k = 0; k < g.nz(); ++k)
      for (int j = 0; j < g.ny(); ++j)
        for (int i = 0; i < g.nx(); ++i) {
          const double u = flow_.u(0)(i, j, k), v = flow_.u(1)(i, j, k), w = flow_.u(2)(i, j, k);
          const double speed = std::sqrt(u * u + v * v + w * w);
          if (speed > best) best = speed, at = {g.xc(i), g.yc(j), g.zc(k)};
        }
    return "|u|max " + num(best) + " m/s at (" + num(at[0] * 1e3) + ", " + num(at[1] * 1e3) + ", " +
           num(at[2] * 1e3) + ") mm";
  }

  void report(const Window& w) const {
    const double elapsed = seconds_since(t0_);
    const auto k = static_cast<int>(windows_.size());
    say("iterate " + std::to_string(k) + "/" + std::to_string(o_.max_iterations) + "  t " + num(w.start) + "-" +
        num(w.end) + " s  tip held " + num(w.tip_in * 1e3) + " mm, answer " + num(w.tip_out * 1e3) + " mm (tolerance " +
        num(o_.tolerance * 1e3) + "; shapes " + num(w.residual * 1e3) + " mm apart)  F_y " +
        num(w.force_mean(1)) + " N (std " + num(w.force_y_std()) + ")  wall " + num(elapsed) + " s, at most " +
        num(elapsed / k * (o_.max_iterations - k)) + " s left");
  }

  Eigen::VectorXd stack(const std::vector<cfd::Vec3>& x) const {
    Eigen::VectorXd v(static_cast<Eigen::Index>(3 * x.size()));
    for (std::size_t i = 0; i < x.size(); ++i)
      for (int d = 0; d < 3; ++d) v[static_cast<Eigen::Index>(3 * i + static_cast<std::size_t>(d))] = x[i][d];
    return v;
  }
  // The width's mean of row i: (z, y) in the flow's frame.
  std::array<double, 2> row_centre(const Eigen::VectorXd& x, std::size_t i) const {
    std::array<double, 2> zy{0, 0};
    for (const auto& [node, w] : rows_[i]) zy[0] += w * x[3 * node + 2], zy[1] += w * x[3 * node + 1];
    return zy;
  }
  double tip(const Eigen::VectorXd& x) const { return row_centre(x, rows_.size() - 1)[1] - row_centre(x, 0)[1]; }
  std::vector<std::array<double, 2>> centreline(const Eigen::VectorXd& x) const {
    std::vector<std::array<double, 2>> c;
    for (std::size_t i = 0; i < rows_.size(); ++i) c.push_back(row_centre(x, i));
    return c;
  }
  static std::string num(double v) { return printf_format("%.4g", v); }
  void say(const std::string& line) const {
    if (o_.progress) o_.progress(line);
  }

  Summary summary() const;
  void write_loads() const;

  const HessenthalerPhaseIOptions& o_;
  std::chrono::steady_clock::time_point t0_;
  fv::HessenthalerFlap flap_;
  std::vector<std::array<double, 2>> measured_;
  cfd::cases::FlowCaseSpec spec_;
  std::optional<cfd::StretchedGrid> grid_;
  cfd::FlowSolver flow_;
  std::size_t n_ = 0;
  std::vector<std::vector<std::pair<int, double>>> rows_;
  Eigen::VectorXd x_, final_;  // the sheet's held shape S(f); the structure's answer to the last load
  long steps_ = 0, structure_solves_ = 0;
  double dt_max_ = 0;
  bool converged_ = false;
  std::vector<Window> windows_;
};

Summary PhaseIRun::summary() const {
  Summary s("validation", "flap_phase1",
            "Hessenthaler 2017 Phase I in 3-D: the flap (shell strip, fitted E) as a sheet in the junction's flow, "
            "steady partitioned fixed point on the held sheet's time-mean load");
  // The steady state's estimate is the held shape at the root; the structure's answer to the
  // load there shows what the flow's history and slow development leave unresolved.
  const auto line = centreline(x_);
  s.absolute("tip_deflection", tip(x_), flap_.tip_deflection_phase_I, 1e-3,
             "Hessenthaler et al. 2017, MRI, Phase I steady (16.41 mm); others within 1 mm", "m");
  s.at_most("centreline_rms", centreline_rms(line, measured_), 1e-3,
            "the 59 MRI centreline points (phaseI_centreline.csv), y at their z; issue 49 goal < 1 mm", "m");
  s.info("answer_tip", tip(final_), "m");
  s.info("answer_centreline_rms", centreline_rms(centreline(final_), measured_), "m");
  s.absolute("steady_state_reached", converged_ ? 1 : 0, 1, 0,
             "the root of tip(S(F)) - t bracketed within the tolerance, or the answer's tip within it");
  const Window* last = windows_.empty() ? nullptr : &windows_.back();
  s.info("iterations", static_cast<double>(windows_.size()));
  s.info("last_tip_mismatch", last ? last->tip_out - last->tip_in : 0, "m");
  s.info("last_shape_distance", last ? last->residual : 0, "m");
  s.info("flap_force_y", last ? last->force_mean(1) : 0, "N");
  s.info("flap_force_y_std", last ? last->force_y_std() : 0, "N");
  s.info("cells", static_cast<double>(grid_->nx()) * grid_->ny() * grid_->nz());
  s.info("flow_steps", static_cast<double>(steps_));
  s.info("structure_solves", static_cast<double>(structure_solves_));
  s.info("simulated_time", flow_.time(), "s");
  s.info("wall_seconds", seconds_since(t0_), "s");
  s.set_timing(seconds_since(t0_), cli::threads_in_use());
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  s.info("peak_memory", static_cast<double>(ru.ru_maxrss) / 1024.0, "MB");
  auto& p = s.parameters();
  p["flow_case"] = o_.flow_case.string();
  p["h_m"] = spec_.h;
  p["cells"] = {grid_->nx(), grid_->ny(), grid_->nz()};
  p["youngs_modulus_pa"] = o_.youngs_modulus;
  p["poisson_ratio"] = flap_.poisson_ratio;
  p["flap_mesh"] = {o_.mesh.along, o_.mesh.across};
  p["markers"] = flow_.sheet()->size();
  p["coupling"] = {{"develop_time_s", o_.develop_time}, {"settle_time_s", o_.settle_time},
                   {"window_time_s", o_.window_time}, {"move_time_s", o_.move_time},
                   {"move_speed_m_s", o_.move_speed}, {"first_step", o_.omega},
                   {"max_iterations", o_.max_iterations}, {"tolerance_m", o_.tolerance}};
  p["viscosity_factor"] = o_.viscosity_factor;
  p["inflow_factor"] = o_.inflow_factor;
  p["start"] = o_.start_straight ? "straight" : "no-flow buoyancy shape";
  p["geometry"] = {
      "the flap's mid-surface, a zero-thickness sheet, clamped with its centre at the origin on the junction's "
      "floor (z = 0), straight along +z at rest, its 11 mm width along x",
      "the net buoyancy (rho_f - rho_s) g along +y (gravity along -y), the faster inlet (0.630 m/s) on +y "
      "(junction_flow.yaml)",
      "the flow without hydrostatics: the buoyancy is the structure's dead load"};
  nlohmann::json h = nlohmann::json::array();
  for (const Window& w : windows_)
    h.push_back({{"t", {w.start, w.end}}, {"tip_held_m", w.tip_in}, {"tip_answer_m", w.tip_out},
                 {"shape_distance_m", w.residual},
                 {"force_n", {w.force_mean(0), w.force_mean(1), w.force_mean(2)}}, {"force_y_std_n", w.force_y_std()}});
  p["iterates"] = h;
  nlohmann::json c = nlohmann::json::array();
  for (const auto& zy : line) c.push_back(zy);
  p["centreline_zy_m"] = c;
  return s;
}

// Every evaluation's held tip and mean nodal load in the structure's frame: what fin-loop flap
// needs to rebuild the flow's load near the root as a function of the tip.
void PhaseIRun::write_loads() const {
  const std::size_t m = windows_.size();
  std::vector<double> tips, loads;
  for (const Window& w : windows_) {
    tips.push_back(w.tip_in);
    for (std::size_t i = 0; i < n_; ++i) {
      const auto k = static_cast<Eigen::Index>(3 * i);
      const fem::Vec3 f = force_to_flap({w.load[k] / w.span, w.load[k + 1] / w.span, w.load[k + 2] / w.span});
      for (int d = 0; d < 3; ++d) loads.push_back(f[d]);
    }
  }
  if (o_.loads_file.has_parent_path()) std::filesystem::create_directories(o_.loads_file.parent_path());
  auto file = h5::File::create(o_.loads_file);
  file.set_attr(".", "schema", std::string("finverse/flap-loads"));
  file.set_attr(".", "schema_version", std::int64_t{1});
  file.set_attr(".", "youngs_modulus_pa", o_.youngs_modulus);
  file.set_attr(".", "h_m", spec_.h);
  file.set_attr(".", "viscosity_factor", o_.viscosity_factor);
  file.set_attr(".", "inflow_factor", o_.inflow_factor);
  file.set_attr(".", "flap_along", std::int64_t{o_.mesh.along});
  file.set_attr(".", "flap_across", std::int64_t{o_.mesh.across});
  file.set_attr(".", "tip_at_root_m", tip(x_));
  file.set_attr(".", "converged", std::int64_t{converged_ ? 1 : 0});
  file.write("tip_held", NdArray<double>({m}, tips), h5::WriteOptions{"m", false});
  file.write("nodal_load", NdArray<double>({m, 3 * n_}, loads), h5::WriteOptions{"N", true});
  file.commit();
  say("wrote " + o_.loads_file.string());
}

}  // namespace

Summary run_hessenthaler_phase1(const HessenthalerPhaseIOptions& options) {
  PhaseIRun run(options);
  return run.run();
}

}  // namespace finverse::fsi::validation
