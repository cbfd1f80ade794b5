// The fin's prescribed-motion flow and its loads history (see fin_flow_case.hpp).
#include "cfd/io/fin_flow_case.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <limits>
#include <sstream>

#include "cfd/forces/nodal_loads.hpp"
#include "cfd/forces/sheet_loads.hpp"
#include "cfd/io/fin_flow_checkpoint.hpp"
#include "cfd/io/loads_record.hpp"
#include "cfd/io/loads_window.hpp"
#include "core/error.hpp"
#include "core/machine_memory.hpp"

namespace finverse::cfd::io {

namespace {

// Cell counts that are multiples of 8 keep three multigrid halvings.
Axis axis(double lo, double hi, double ulo, double uhi, double h, double ratio) {
  const int n =
      std::max(8, 8 * static_cast<int>(std::lround(Axis::stretched(lo, hi, ulo, uhi, h, ratio).size() / 8.0)));
  return Axis::stretched_count(lo, hi, ulo, uhi, n, ratio);
}

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", v);
  return b;
}

}  // namespace

void swept_box(const FinSurfaceMotion& m, double t0, double t1, int samples, Vec3& lo, Vec3& hi, double& max_speed,
               bool mid_surface) {
  const double inf = std::numeric_limits<double>::infinity();
  lo = {inf, inf, inf};
  hi = {-inf, -inf, -inf};
  max_speed = 0;
  for (int k = 0; k <= samples; ++k) {
    const double t = t0 + (t1 - t0) * k / samples;
    std::vector<Vec3> x, v;
    if (mid_surface) {
      MidSurfaceState ms = m.mid_surface(t);
      x = std::move(ms.x);
      v = std::move(ms.v);
    } else {
      SurfaceState s = m.state(t);
      x = std::move(s.surface.points);
      v = std::move(s.velocity);
    }
    for (std::size_t i = 0; i < x.size(); ++i) {
      for (int d = 0; d < 3; ++d) {
        lo[d] = std::min(lo[d], x[i][d]);
        hi[d] = std::max(hi[d], x[i][d]);
      }
      if (!v.empty()) max_speed = std::max(max_speed, std::hypot(v[i][0], v[i][1], v[i][2]));
    }
  }
}

StretchedGrid fin_flow_grid(const Vec3& lo, const Vec3& hi, double c, double h, const FinFlowOptions& o) {
  if (!(o.core_margin >= 0 && o.wake >= 0)) throw Error("--core-margin, --wake: expected >= 0");
  if (!(o.upstream > o.core_margin && o.lateral > o.core_margin && o.spanwise > o.core_margin))
    throw Error("--upstream, --lateral, --spanwise: the domain must reach beyond the uniform core (--core-margin " +
                num(o.core_margin) + " c)");
  if (!(o.downstream > o.core_margin + o.wake))
    throw Error("--downstream: " + num(o.downstream) + " c, the domain must reach beyond the uniform core and wake (" +
                num(o.core_margin + o.wake) + " c)");
  if (!(h > 0 && o.stretch_ratio >= 1)) throw Error("--cells-per-chord, --stretch-ratio: expected h > 0, ratio >= 1");
  const double m = o.core_margin * c;
  {
    // The uniform core's cells alone, before any axis is built: about 400 bytes a cell (velocity,
    // its history and right-hand sides, pressure, the multigrid hierarchy, the cell kinds).
    const double core =
        (hi[0] - lo[0] + 2 * m + o.wake * c) / h * ((hi[1] - lo[1] + 2 * m) / h) * ((hi[2] - lo[2] + 2 * m) / h);
    std::ostringstream what;
    what << "--cells-per-chord " << c / h << ": at least " << std::setprecision(3) << core << " cells";
    require_memory(400 * core, what.str());
  }
  return StretchedGrid(
      axis(lo[0] - o.upstream * c, hi[0] + o.downstream * c, lo[0] - m, hi[0] + m + o.wake * c, h, o.stretch_ratio),
      axis(lo[1] - o.lateral * c, hi[1] + o.lateral * c, lo[1] - m, hi[1] + m, h, o.stretch_ratio),
      axis(lo[2] - o.spanwise * c, hi[2] + o.spanwise * c, lo[2] - m, hi[2] + m, h, o.stretch_ratio));
}

stage::Loads run_fin_flow(const FinInput& in, const FinFlowOptions& o, FinFlowStats& st,
                          const std::function<void(long, long, const StepStats&)>& progress,
                          const FinCheckpointing& ck) {
  const auto wall0 = std::chrono::steady_clock::now();
  if (ck.every < 0) throw Error("--checkpoint-every: " + std::to_string(ck.every) + ", expected >= 0");
  if (ck.every > 0 && ck.file.empty()) throw Error("--checkpoint-every: no checkpoint file given");
  // A restart with other options or inputs is refused before any work.
  const nlohmann::json config = fin_flow_config(o, in);
  if (!ck.restart.empty()) check_fin_restart(ck.restart, config);
  const FinSurfaceMotion& motion = *in.motion;
  const ThinBody& body = motion.body();
  // Chord and flow parameters.
  double c = o.chord > 0 ? o.chord : in.chord.value_or(0.0);
  if (!(c > 0)) {
    double xlo = std::numeric_limits<double>::infinity(), xhi = -xlo;
    for (const auto& p : in.rest) xlo = std::min(xlo, p[0]), xhi = std::max(xhi, p[0]);
    c = xhi - xlo;
  }
  if (!(c > 0)) throw Error("fin flow: chord: not given and the rest mesh has no x extent");
  if (!(o.reynolds > 0)) throw Error("--reynolds: " + num(o.reynolds) + ", expected > 0");
  if (!(o.rho > 0)) throw Error("--rho: " + num(o.rho) + ", expected > 0");
  const double U = o.speed > 0 ? o.speed : free_stream_speed(o.reynolds, c, o.viscosity);
  if (!(U > 0)) throw Error("--speed / --viscosity: free-stream speed " + num(U) + " m/s, expected > 0");
  const double nu = U * c / o.reynolds;
  if (o.surface != "closed" && o.surface != "sheet")
    throw Error("--surface: '" + o.surface + "', expected closed or sheet");
  const bool sheet = o.surface == "sheet";
  // The sheet has no thickness to resolve: c/16 unless asked.
  const double h = o.cells_per_chord > 0 ? c / o.cells_per_chord
                   : sheet               ? c / 16
                                         : std::min(c / 16, body.thickness / 2);

  // Duration and outputs.
  const double t0 = in.frame_time.front();
  double t1 = in.frame_time.back();  // the last output time
  const bool periodic = in.layout.wrap.has_value();
  if (periodic) {
    if (!(o.periods > 0)) throw Error("--periods: " + num(o.periods) + ", expected > 0");
    t1 = t0 + o.periods * *in.period;
  }
  double interval = o.output_interval;
  if (!(interval > 0)) {
    interval = std::numeric_limits<double>::infinity();
    for (std::size_t k = 1; k < in.frame_time.size(); ++k)
      interval = std::min(interval, in.frame_time[k] - in.frame_time[k - 1]);
    // A period need not be a whole number of frames (500 fps at 4.4 Hz: 113.6): the largest
    // interval no longer than a frame that divides the period, so every period has the same
    // output times and the last one is a whole period.
    if (periodic) interval = *in.period / std::ceil(*in.period / interval - 1e-9);
  }
  const long outputs = std::lround((t1 - t0) / interval);
  if (outputs < 1 || std::abs(outputs * interval - (t1 - t0)) > 1e-6 * interval)
    throw Error("--output-interval: " + num(interval) + " s does not divide the simulated span " + num(t1 - t0) + " s");
  double out_from = t0;  // outputs at times > out_from
  if (periodic && o.output_periods > 0) out_from = std::max(t0, t1 - o.output_periods * *in.period);

  // Grid around the swept body.
  st = {};
  swept_box(motion, t0, periodic ? t0 + *in.layout.wrap : t1, 4 * static_cast<int>(in.frame_time.size()), st.swept_lo,
            st.swept_hi, st.max_body_speed, sheet);
  st.grid = fin_flow_grid(st.swept_lo, st.swept_hi, c, h, o);
  st.h = h;
  st.U = U;
  st.nu = nu;
  st.chord = c;
  st.t_begin = t0;
  st.t_end = t1;
  st.triangles = body.triangles.size();

  // Fixed time step: a whole number m of steps per output interval. The flow around the thin
  // body's edges runs faster than the body (measured: CFL 1.55 for a target of 0.5 on the default
  // fin with U + body speed), hence twice the body's fastest vertex speed in the estimate.
  const double dt_cfl = o.cfl * h / (U + 2 * st.max_body_speed);
  const long m = std::max(1L, static_cast<long>(std::ceil(interval / dt_cfl - 1e-9)));
  st.dt = interval / static_cast<double>(m);
  // The loads of output k are the mean over the steps k m - m/2 .. k m + m/2 (loads_window.hpp): a
  // periodic motion runs half an interval past the last output so its window is whole too.
  const long last_output = outputs * m;
  const bool windowed = o.surface == "sheet" ? o.sheet_loads_mean : !o.sample_loads;
  const long total = last_output + (periodic && windowed ? m / 2 : 0);
  st.t_end = t0 + static_cast<double>(total) * st.dt;
  long first_output = 1;  // in intervals: the first output time after out_from
  while (t0 + static_cast<double>(first_output) * interval <= out_from + 1e-9 * interval) ++first_output;

  FlowBoundary b;
  b[Side::XLo].type = FlowBcType::Inlet;
  b[Side::XLo].speed = U;
  b[Side::XHi].type = FlowBcType::ConvectiveOutlet;
  for (Side s : {Side::YLo, Side::YHi, Side::ZLo, Side::ZHi}) b[s].type = FlowBcType::Slip;
  FlowOptions opt;
  opt.nu = nu;
  opt.dt = st.dt;
  opt.cfl_limit = o.cfl_limit;
  opt.helmholtz_rtol = 1e-8;
  opt.poisson.rtol = o.poisson_rtol;
  opt.cut_cell_continuity_3d = o.cut_cells;
  FlowSolver solver;
  try {
    solver.setup(st.grid, b, opt);
    // On MPI ranks the face velocities and convection on the rank's own lines; the checkpoints and
    // the output callback below gather the rest first (flow_solver.hpp, compute_on_rank_lines).
    solver.compute_on_rank_lines(true);
    if (sheet) {
      SheetForcingOptions so;
      so.kernel = delta_kernel_from_name(o.kernel);
      so.spacing = o.marker_spacing;
      so.band_correction = !o.raw_sheet_force;
      const std::shared_ptr<const FinSurfaceMotion> mo = in.motion;
      solver.immerse_sheet(SheetTopology{3, in.rest.size(), in.mid_triangles}, in.rest, so, [mo](double t) {
        MidSurfaceState ms = mo->mid_surface(t);
        return SheetState{std::move(ms.x), std::move(ms.v)};
      });
    } else {
      solver.immerse(FinSurfaceMotion::as_surface_motion(in.motion));
    }
    solver.initialise([U](double, double, double, double) { return std::array<double, 3>{U, 0, 0}; }, {}, t0);
  } catch (const Error& e) {
    throw Error("fin flow: setting up the body in the " + std::to_string(st.grid.nx()) + " x " +
                std::to_string(st.grid.ny()) + " x " + std::to_string(st.grid.nz()) + " grid at t = " + num(t0) +
                " s: " + e.what());
  }

  LoadsRecord rec(in.rest.size(), in.mid_triangles.size());
  const bool one_step = sheet ? !o.sheet_loads_mean : o.sample_loads;
  LoadsWindow window(m, in.rest.size(), in.mid_triangles.size(), first_output * m, last_output, total, one_step);
  long first = 1;
  std::string last_checkpoint = "; no checkpoint written";  // appended to a failure's message
  if (!ck.restart.empty()) {
    const FinRunCounters c = read_fin_checkpoint(ck.restart, solver, config, rec, window);
    if (c.step > total)
      throw Error(ck.restart.string() + ": cannot restart: the checkpoint is at step " + std::to_string(c.step) +
                  ", beyond this run's " + std::to_string(total) + " steps");
    first = c.step + 1;
    st.first_step = c.step;
    st.steps = c.step;
    st.poisson_iterations = c.poisson_iterations;
    st.max_cfl = c.max_cfl;
    last_checkpoint = "; last checkpoint: " + ck.restart.string() + " (step " + std::to_string(c.step) + ")";
  }
  const auto failure = [&](long n, const std::string& what) {
    // The solver's own messages name the step (or the time level) already.
    const std::string at = what.find("step") != std::string::npos ? ""
                           : what.find("t = ") != std::string::npos
                               ? "step " + std::to_string(n) + ": "
                               : "step " + std::to_string(n) + " (t = " + num(solver.time()) + " s): ";
    return Error("fin flow: " + at + what + last_checkpoint);
  };
  for (long n = first; n <= total; ++n) {
    StepStats s;
    try {
      s = solver.step();
    } catch (const Error& e) {
      throw failure(n, e.what());
    }
    st.max_cfl = std::max(st.max_cfl, s.cfl);
    st.poisson_iterations += s.poisson_iterations;
    st.steps = n;
    if (progress) progress(n, total, s);
    if (window.needs(n)) {
      const double t = solver.time();
      std::vector<Vec3> nodal;
      std::vector<double> jump;
      Vec3 total_force;
      if (sheet) {
        const SheetLoads L = solver.sheet_loads(o.rho);
        nodal = L.nodal;
        total_force = L.total;
        jump = sheet_pressure_jump(*solver.sheet(), solver.sheet_state().position, L);
      } else {
        const SurfaceForces F = solver.surface_forces(o.rho);
        total_force = F.total;
        nodal = nodal_forces(body, F);
        jump = pressure_jump(body, in.mid_triangles, motion.state(t).surface, F);
      }
      if (!(std::isfinite(total_force[0]) && std::isfinite(total_force[1]) && std::isfinite(total_force[2])))
        throw failure(n, "step " + std::to_string(n) + " (t = " + num(t) + " s): the surface force is not finite");
      for (const auto& w : window.add(n, nodal, total_force, jump)) {
        const double tw = t0 + static_cast<double>(w.step / m) * interval;  // exact output time
        rec.add(tw, w.nodal, w.total, w.jump);
        if (ck.at_output) {
          solver.gather_rank_lines();  // (collective: set on every rank of an MPI run)
          ck.at_output(w.step / m, tw, solver);
        }
      }
    }
    if (ck.every > 0 && n % ck.every == 0 && n < total) {
      const auto c0 = std::chrono::steady_clock::now();
      solver.gather_rank_lines();  // (collective: every rank of an MPI run comes here)
      if (ck.write)
        write_fin_checkpoint(ck.file, solver, config, {n, st.poisson_iterations, st.max_cfl}, rec, window);
      st.checkpoint_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - c0).count();
      ++st.checkpoints;
      last_checkpoint = "; last checkpoint: " + ck.file.string() + " (step " + std::to_string(n) + ")";
    }
    if (ck.after_step) {
      try {
        ck.after_step(n, solver);
      } catch (const Error& e) {
        throw failure(n, e.what());
      }
    }
  }
  st.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  st.pressure_setup_seconds = solver.pressure_times().setup_seconds;  // the solver lives for this run
  st.pressure_solve_seconds = solver.pressure_times().solve_seconds;
  return rec.to_stage(o.rho, U, in.reference_area, periodic ? in.period : std::nullopt);
}

std::vector<FinFlowFlag> fin_flow_flags(FinFlowOptions& o) {
  return {{"--reynolds", &o.reynolds, "chord Reynolds number U c / nu"},
          {"--speed", &o.speed, "free-stream speed U [m/s]; 0: U = Re nu / c"},
          {"--viscosity", &o.viscosity, "kinematic viscosity [m2/s] used when --speed is 0"},
          {"--rho", &o.rho, "fluid density [kg/m3]"},
          {"--chord", &o.chord, "chord c [m]; 0: mesh.h5 attribute chord"},
          {"--cells-per-chord", &o.cells_per_chord, "core cell width h = c / N; 0: min(c/16, ibm_thickness/2)"},
          {"--core-margin", &o.core_margin, "uniform core beyond the swept box [c]"},
          {"--wake", &o.wake, "uniform core extension downstream [c]"},
          {"--upstream", &o.upstream, "domain inlet distance from the swept box [c]"},
          {"--downstream", &o.downstream, "domain outlet distance from the swept box [c]"},
          {"--lateral", &o.lateral, "domain half-width beyond the swept box in y [c]"},
          {"--spanwise", &o.spanwise, "domain extent beyond the swept box in z [c]"},
          {"--stretch-ratio", &o.stretch_ratio, "largest neighbouring cell-width ratio"},
          {"--cfl", &o.cfl, "target convective CFL number (sets the fixed time step)"},
          {"--cfl-limit", &o.cfl_limit, "blow-up guard: stop when the CFL number exceeds this"},
          {"--periods", &o.periods, "periodic motion: periods simulated"},
          {"--output-periods", &o.output_periods, "periodic motion: last periods written (0: all)"},
          {"--output-interval", &o.output_interval,
           "time between outputs [s]; 0: the motion's frame spacing (periodic: the largest interval up to it that "
           "divides the period)"},
          {"--poisson-rtol", &o.poisson_rtol, "pressure Poisson relative tolerance"}};
}

}  // namespace finverse::cfd::io
