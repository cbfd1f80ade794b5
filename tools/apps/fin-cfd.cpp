// fin-cfd: the incompressible Navier-Stokes solver's validation cases (DESIGN.md sections 5.1, 6).
//
//   fin-cfd taylor_green [--coarse]     observed order of accuracy in space and in time
//   fin-cfd channel [--checkpoint-every N] [--restart FILE] [--vtk]
//                                       parabolic inlet, convective outlet, no-slip walls: the
//                                       developed profile and dp/dx = -8 nu Um / H^2
//   fin-cfd dfg_2d1 | dfg_2d2 [--cells-per-diameter N] [--t-end T] [--staircase-balance]
//                                       [--zero-wall-pressure-gradient]
//                                       DFG cylinder benchmarks (Schaefer & Turek 1996) with the
//                                       ghost-cell immersed boundary; forces.csv force history
//   fin-cfd dfg_2d3 [--cells-per-diameter N] [--core-cells-per-diameter M]
//                                       DFG 2D-3, the sine inflow over 8 s: maxima and their times
//                                       against John (2004)
//   fin-cfd turek_hron_cfd2 | turek_hron_cfd3 [--cells-per-diameter N] [--core-cells-per-diameter M]
//                                       [--t-end T] [--kick-velocity V (CFD3)] [--staircase-balance]
//                                       [--zero-wall-pressure-gradient]
//                                       Turek-Hron rigid-flag benchmarks (Turek & Hron 2006) with
//                                       the ghost-cell immersed boundary; forces.csv force history
//   fin-cfd ib_couette                  Couette flow between two immersed circles: observed order
//   fin-cfd cylinder_towed              towed cylinder vs fixed cylinder in a stream (moving body)
//   fin-cfd cylinder_oscillating        in-line oscillating cylinder: force spikes from cleared cells
//   fin-cfd sphere_re100 [--cells-per-diameter N] [--t-end T] [--wall-momentum-balance]
//                                       sphere at Re 100 with the 3-D triangulated ghost-cell
//                                       boundary: drag vs Johnson & Patel 1999; forces.csv history
//   fin-cfd dfg_3d1z [--cells-per-diameter N] [--t-end T] [--wall-momentum-balance]
//                                       DFG 3D-1Z (Schaefer & Turek 1996): wall-to-wall cylinder in a
//                                       square channel, triangulated body crossing the z walls
//   fin-cfd fin --mesh mesh.h5 --motion motion.h5 --out loads.h5 ...   and   fin-cfd thin_plate ...
//                                       the fin's prescribed-motion loads (fin_cfd_fin.hpp)
//
// Each writes <out-dir>/<case>/summary.json; exit 1 when a graded metric misses its tolerance.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cfd/io/flow_checkpoint.hpp"
#include "cfd/validation/dfg_3d1z.hpp"
#include "cfd/validation/dfg_benchmark.hpp"
#include "cfd/flow/flow_solver.hpp"
#include "cfd/validation/ib_couette.hpp"
#include "cfd/validation/moving_cylinder.hpp"
#include "cfd/validation/sphere_flow.hpp"
#include "cfd/validation/taylor_green.hpp"
#include "cfd/validation/turek_hron_cfd.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/atomic_file.hpp"
#include "core/log.hpp"
#include "core/summary.hpp"
#include "core/vtk_output.hpp"
#include "fin_cfd_fin.hpp"

namespace {

using namespace finverse;
using namespace finverse::cfd;

int finish(Summary& s, const std::filesystem::path& dir, double wall) {
  s.set_timing(wall, cli::threads_in_use());
  std::filesystem::create_directories(dir);
  s.write(dir / "summary.json");
  log::info("wrote " + (dir / "summary.json").string() + (s.pass() ? " (all metrics pass)" : " (a metric FAILED)"));
  return s.pass() ? kExitOk : kExitDifferent;
}

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

// ---- Taylor-Green --------------------------------------------------------------------------------

int taylor_green(bool coarse, const std::filesystem::path& out, double& wall_out) {
  const auto t0 = std::chrono::steady_clock::now();
  Summary s("validation", "taylor_green",
            "2-D decaying Taylor-Green vortex, periodic box [0,2pi]^2: observed order of accuracy of the "
            "fractional-step solver in space (uniform and smoothly stretched grids) and in time");
  const std::string src = "second-order scheme (Van Kan 1986 fractional step, CN/AB2, Zang et al. 1994 collocated FV)";
  const std::vector<int> ns = coarse ? std::vector<int>{16, 32, 64} : std::vector<int>{32, 64, 128};
  // Space: nu = 0.05 to t = 1 with dt small enough (and tau fixed) that the error is spatial.
  for (double stretch : {0.0, 0.3}) {
    const std::string tag = stretch > 0 ? "stretched" : "uniform";
    std::vector<TaylorGreenResult> r;
    for (int n : ns) {
      TaylorGreenSetup ts;
      ts.n = n;
      ts.dt = 0.0125;
      ts.coupling_time = 0.00625;
      ts.stretch = stretch;
      r.push_back(run_taylor_green(ts));
      log::info("taylor_green " + tag + " n=" + std::to_string(n) + ": u L2 " + fmt("%.4e", r.back().u_l2) +
                ", p L2 " + fmt("%.4e", r.back().p_l2) + ", CPU " + fmt("%.2fs", r.back().cpu_seconds));
      s.info("u_l2_" + tag + "_n" + std::to_string(n), r.back().u_l2, "m/s");
      s.info("p_l2_" + tag + "_n" + std::to_string(n), r.back().p_l2, "m^2/s^2");
      s.info("max_divergence_" + tag + "_n" + std::to_string(n), r.back().max_divergence, "1/s");
      s.info("momentum_drift_" + tag + "_n" + std::to_string(n), r.back().momentum_drift, "m^3/s");
    }
    const std::size_t m = r.size() - 1;
    s.absolute("order_space_velocity_" + tag, std::log2(r[m - 1].u_l2 / r[m].u_l2), 2.0, 0.1, src);
    s.absolute("order_space_pressure_" + tag, std::log2(r[m - 1].p_l2 / r[m].p_l2), 2.0, 0.1, src);
    s.info("order_space_velocity_" + tag + "_coarser_pair", std::log2(r[m - 2].u_l2 / r[m - 1].u_l2));
  }
  // Time: one stretched grid, nu = 0.2 (the Crank-Nicolson error is what is seen), Richardson
  // differences of runs with dt, dt/2, ... so the spatial error cancels.
  {
    std::vector<TaylorGreenResult> r;
    const std::vector<double> dts = coarse ? std::vector<double>{0.1, 0.05, 0.025, 0.0125}
                                           : std::vector<double>{0.1, 0.05, 0.025, 0.0125, 0.00625};
    for (double dt : dts) {
      TaylorGreenSetup ts;
      ts.n = coarse ? 32 : 64;
      ts.nu = 0.2;
      ts.stretch = 0.3;
      ts.dt = dt;
      ts.coupling_time = dts.back() / 2;
      r.push_back(run_taylor_green(ts));
    }
    std::vector<double> diff;
    for (std::size_t k = 0; k + 1 < r.size(); ++k) diff.push_back(velocity_difference(r[k], r[k + 1]));
    for (std::size_t k = 0; k + 1 < diff.size(); ++k) {
      const double order = std::log2(diff[k] / diff[k + 1]);
      log::info("taylor_green time: dt " + fmt("%g", dts[k + 1]) + " order " + fmt("%.3f", order));
      if (k + 2 == diff.size()) s.absolute("order_time_velocity", order, 2.0, 0.1, src);
      else s.info("order_time_velocity_dt" + fmt("%g", dts[k + 1]), order);
    }
  }
  s.parameters() = {{"coarse", coarse}, {"grids", ns}, {"nu_space", 0.05}, {"nu_time", 0.2}, {"t_end", 1.0},
                    {"stretch", 0.3}, {"domain", "[0,2pi]^2 periodic"}};
  wall_out = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return finish(s, out / "taylor_green", wall_out);
}

// ---- channel -------------------------------------------------------------------------------------

struct ChannelArgs {
  bool coarse = false;
  int checkpoint_every = 0;
  std::string checkpoint = "";
  std::string restart;
  bool vtk = false;
};

int channel(const ChannelArgs& a, const std::filesystem::path& out, double& wall_out) {
  const auto t0 = std::chrono::steady_clock::now();
  // Re = Um H / nu = 5; by t_end the slowest start-up mode has decayed by exp(-pi^2 nu t_end / H^2) ~ 5e-5.
  const double nu = 0.2, Um = 1.0, L = 3.0, H = 1.0, t_end = 5.0;
  const int nx = a.coarse ? 48 : 96, ny = a.coarse ? 16 : 32;
  // Walls resolved by a stretched family (one mapping sampled finer with Axis::refined).
  Axis ay = Axis::stretched_count(0, H, 0.3, 0.7, 8, 1.2);
  while (ay.size() < ny) ay = ay.refined();
  const StretchedGrid g(Axis::uniform(0, L, nx), ay);
  FlowBoundary b;
  b[Side::XLo].type = FlowBcType::Inlet;
  b[Side::XLo].profile = InletProfile::Parabolic;
  b[Side::XLo].speed = Um;
  b[Side::XLo].ramp_time = 0.5;
  b[Side::XHi].type = FlowBcType::ConvectiveOutlet;
  FlowOptions opt;
  opt.nu = nu;
  opt.cfl = 0.5;
  opt.dt_max = a.coarse ? 0.01 : 0.005;
  FlowSolver solver;
  solver.setup(g, b, opt);
  solver.initialise({});
  if (!a.restart.empty()) {
    read_checkpoint(a.restart, solver);
    log::info("restarted from " + a.restart + " at step " + std::to_string(solver.steps()) + ", t = " +
              fmt("%.6g s", solver.time()));
  }
  const std::filesystem::path dir = out / "channel";
  std::filesystem::create_directories(dir);
  const std::size_t expected = static_cast<std::size_t>(std::ceil(t_end / opt.dt_max));
  log::Progress progress("channel step", expected);
  long poisson = 0, steps = 0;
  while (solver.time() < t_end - 1e-12) {
    const StepStats st = solver.step();
    poisson += st.poisson_iterations;
    ++steps;
    progress.update(static_cast<std::size_t>(st.step),
                    "t " + fmt("%.4f s", st.time) + "  dt " + fmt("%.3g", st.dt) + "  CFL " + fmt("%.3f", st.cfl) +
                        "  Poisson " + std::to_string(st.poisson_iterations) + " it  div " +
                        fmt("%.1e", st.max_divergence));
    if (a.checkpoint_every > 0 && st.step % a.checkpoint_every == 0)
      write_checkpoint(dir / "checkpoint.h5", solver, "{\"case\":\"channel\"}");
  }
  progress.finish("t " + fmt("%.4f s", solver.time()));

  Summary s("validation", "channel",
            "2-D channel flow, parabolic inlet (ramped), convective outlet, no-slip walls on a stretched grid: "
            "developed Poiseuille profile and pressure gradient");
  const std::string src = "plane Poiseuille flow, u = 4 Um y (H - y) / H^2, dp/dx = -8 rho nu Um / H^2";
  const Field p = solver.pressure();
  const int i1 = nx / 4, i2 = 3 * nx / 4;
  double grad = 0;
  for (int j = 0; j < ny; ++j) grad += (p(i2, j, 0) - p(i1, j, 0)) / (g.xc(i2) - g.xc(i1)) / ny;
  double e = 0, qin = 0, qout = 0;
  for (int j = 0; j < ny; ++j) {
    const double y = g.yc(j);
    for (int i = nx / 3; i < nx; ++i) e = std::max(e, std::abs(solver.u(0)(i, j, 0) - 4 * Um * y * (H - y) / (H * H)));
    qin += solver.face_velocity()(0, 0, j, 0) * g.dy(j);
    qout += solver.face_velocity()(0, nx, j, 0) * g.dy(j);
  }
  s.relative("dpdx", grad, -8 * nu * Um / (H * H), 0.01, src, "Pa/m per kg/m^3");
  // Second order in the max norm (measured 5.3e-3 at ny = 16, 1.5e-3 at ny = 32): the tolerance is
  // the expected error with a margin, so a drop of order shows.
  s.absolute("profile_max_error_over_Um", e / Um, 0.0, a.coarse ? 7.5e-3 : 2.5e-3, src);
  s.absolute("mass_balance", qout - qin, 0.0, 1e-12, "continuity", "m^2/s");
  s.info("max_divergence", solver.max_divergence(), "1/s");
  s.info("steps", static_cast<double>(steps));
  s.info("mean_poisson_iterations", steps > 0 ? static_cast<double>(poisson) / steps : 0.0);
  s.parameters() = {{"coarse", a.coarse}, {"nx", nx}, {"ny", ny}, {"nu", nu}, {"Um", Um}, {"L", L}, {"H", H},
                    {"t_end", t_end}, {"cfl", opt.cfl}, {"dt_max", opt.dt_max}};
  if (a.vtk) {
    vtkio::GridFrame frame;
    for (const StateArray& arr : solver.cell_output()) {
      const std::size_t n = g.cells();
      NdArray<double> v(arr.values.size() == n ? std::vector<std::size_t>{n} : std::vector<std::size_t>{n, 3},
                        arr.values);
      frame.cell_data.push_back({arr.name, v});
    }
    vtkio::write_grid_series(dir / "flow.pvd", {solver.time()}, g.axis(0).faces(), g.axis(1).faces(), {0.0}, {frame});
  }
  wall_out = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return finish(s, dir, wall_out);
}

// The run statistics both 3-D body cases (sphere, DFG 3D-1Z) report.
template <class Result>
void solver_statistics_3d(Summary& s, const Result& r) {
  s.info("steps", static_cast<double>(r.steps));
  s.info("cells", static_cast<double>(r.cells[0]) * r.cells[1] * r.cells[2]);
  s.info("ghost_cells", static_cast<double>(r.ghost_cells));
  s.info("surface_samples", static_cast<double>(r.surface_samples));
  s.info("mean_poisson_iterations", r.mean_poisson_iterations);
  s.info("mean_momentum_iterations", r.mean_momentum_iterations);
  s.info("max_divergence_end", r.max_divergence, "1/s");
  s.info("solver_seconds", r.cpu_seconds, "s");
}

// The --reference file of a validation case (literature numbers, data/reference/*.json).
nlohmann::json read_reference(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error("--reference: cannot read " + path);
  try {
    nlohmann::json ref;
    in >> ref;
    return ref;
  } catch (const std::exception&) {
    throw Error("--reference: " + path + " is not valid JSON");
  }
}

// ---- DFG cylinder benchmarks ---------------------------------------------------------------------

// Options of the immersed-body benchmarks (DFG, Turek-Hron, sphere): grid, duration, reference.
struct BodyCaseArgs {
  int cells_per_diameter = 0;  // 0: the case's default
  double t_end = 0;            // 0: the case's default
  std::string reference;       // the case's data/reference/*.json
  double wake_box = 0;         // DFG, Turek-Hron: uniform box's downstream end (0: the case's default)
  double stretch_ratio = 0;    // DFG, Turek-Hron: stretching ratio outside the box (0: the default)
  int core_cells_per_diameter = 0;  // DFG: a finer core around the body (0: none)
  double core_wake = 0;        // DFG, Turek-Hron: the core's length behind the body [D] (0: the default)
  double cfl = 0;              // DFG, Turek-Hron: target convective CFL number (0: the case's default)
  double wall_stretch_ratio = 0;  // DFG, Turek-Hron: ratio between the box and the channel walls (0: --stretch-ratio)
  bool staircase_balance = false;  // DFG, Turek-Hron: the staircase mass balance instead of the cut-cell one
  bool zero_wall_pressure_gradient = false;  // DFG, Turek-Hron: dp/dn = 0 on the body instead of the wall's momentum balance
  bool wall_momentum_balance = false;  // sphere, DFG 3D-1Z: the wall's momentum balance instead of dp/dn = 0
  std::string wall_extrapolation = "linear";  // DFG 2-D: the surface traction's extrapolation to the wall
};

// Grid and time-step options of the channel benchmarks (DFG, Turek-Hron) on subcommand sc.
void add_channel_grid_options(CLI::App* sc, BodyCaseArgs& a, const std::string& box_help) {
  sc->add_option("--wake-box", a.wake_box, box_help)->check(CLI::PositiveNumber);
  sc->add_option("--stretch-ratio", a.stretch_ratio, "grid: largest cell-width ratio outside the uniform box")
      ->check(CLI::Range(1.0, 1.5));
  sc->add_option("--wall-stretch-ratio", a.wall_stretch_ratio,
                 "grid: the same between the box and the channel walls (default: --stretch-ratio, but 0.97 on "
                 "dfg_2d2's and 0.98 on turek_hron_cfd3's default grids; 1: the box's spacing out to the walls; "
                 "below 1, with a core: cells shrinking towards the walls)")
      ->check(CLI::Range(0.8, 1.5));
  sc->add_option("--core-cells-per-diameter", a.core_cells_per_diameter,
                 "grid: a finer core of h = D / N around the body (boundary layers), joined to the box by "
                 "ratio-1.1 growth (0: none)")
      ->check(CLI::Range(0, 1000));
  sc->add_option("--core-wake", a.core_wake,
                 "grid: the core's length behind the body [diameters] (DFG: behind the cylinder, default 0.75; "
                 "Turek-Hron: behind the flag's tip, default 0.5)")
      ->check(CLI::PositiveNumber);
  // The time step's share of an error: halve the CFL number and compare.
  sc->add_option("--cfl", a.cfl, "time step: target convective CFL number (default 0.5)")->check(CLI::Range(0.01, 1.0));
  sc->add_flag("--staircase-balance", a.staircase_balance,
               "mass balance: close the faces of every non-fluid cell (the staircase balance) instead of the "
               "default cut-cell balance (Seo & Mittal 2011), to compare");
  sc->add_flag("--zero-wall-pressure-gradient", a.zero_wall_pressure_gradient,
               "pressure on the body: dp/dn = 0 (Mittal et al. 2008) instead of the default wall momentum "
               "balance dp/dn = -nu d(omega)/ds, to compare");
}

// The options of BodyCaseArgs on subcommand sc; `t_unit` names the unit of --t-end.
void add_body_case_options(CLI::App* sc, BodyCaseArgs& a, const std::string& t_unit) {
  sc->add_option("--cells-per-diameter", a.cells_per_diameter, "grid: h = D / N in the box around the body")
      ->check(CLI::Range(4, 1000));
  sc->add_option("--t-end", a.t_end, "simulated time [" + t_unit + "]")->check(CLI::PositiveNumber);
  sc->add_option("--reference", a.reference, "reference values (JSON)")->capture_default_str();
}

int dfg(int variant, bool coarse, const BodyCaseArgs& a, const std::filesystem::path& out, double& wall_out) {
  const auto t0 = std::chrono::steady_clock::now();
  const nlohmann::json ref = read_reference(a.reference);
  const std::string key = variant == 1 ? "2D-1" : variant == 2 ? "2D-2" : "2D-3";
  if (!ref.contains(key)) throw Error("--reference: " + a.reference + " has no '" + key + "' entry");
  const nlohmann::json& R = ref[key];
  const std::string name = variant == 1 ? "dfg_2d1" : variant == 2 ? "dfg_2d2" : "dfg_2d3";
  DfgSetup ds;
  ds.variant = variant;
  // 2D-1 by default at D/64 with the wall momentum balance on the cylinder: CD +0.02 %, CL +0.29 %,
  // dp -0.26 % of the bound midpoints (D/48: -0.23 %, -1.91 %, +0.25 %; D/48 with dp/dn = 0:
  // +0.53 %, +0.06 %, +1.02 %). The lift, 1/500 of the drag, is the last to converge. dp, 0.11710,
  // stays 0.0001 under the lower bound 0.1172 (high precision 0.11752), and refining does not lift it
  // there: a D/96 core in a D/48 box (98 560 cells, 659 s against 309 s) gives dp 0.11718, CD
  // +0.06 %, CL -0.31 %. A third probe in the extrapolation to the wall (--wall-extrapolation
  // quadratic) puts dp inside (0.11738) but CD outside (5.5926, +0.23 % of the high-precision value,
  // against +0.03 % here and -0.07 % for the control-volume drag): the default keeps the linear one.
  ds.cells_per_diameter = a.cells_per_diameter > 0 ? a.cells_per_diameter : (coarse ? 12 : variant == 1 ? 64 : 24);
  if (variant == 3 && a.t_end > 0) throw Error("dfg_2d3: --t-end is fixed by the benchmark (8 s)");
  ds.t_end = a.t_end > 0 ? a.t_end : variant == 1 ? (coarse ? 4.0 : 8.0) : variant == 2 ? (coarse ? 2.0 : 10.0) : 8.0;
  ds.window = variant == 2 ? std::min(3.0, 0.4 * ds.t_end) : 0.0;
  if (a.wake_box > 0) ds.box_x1 = a.wake_box;
  if (a.stretch_ratio > 0) ds.stretch_ratio = a.stretch_ratio;
  if (a.cfl > 0) ds.cfl = a.cfl;
  if (a.wall_stretch_ratio > 0) ds.wall_stretch_ratio = a.wall_stretch_ratio;
  if (a.core_wake > 0) ds.core_wake = a.core_wake;
  ds.cut_cell_continuity = !a.staircase_balance;
  ds.viscous_wall_pressure = !a.zero_wall_pressure_gradient;
  ds.wall_extrapolation =
      a.wall_extrapolation == "quadratic" ? WallExtrapolation::Quadratic : WallExtrapolation::Linear;
  // 2D-2 by default: a D/48 core over the boundary layer in a D/24 box, the cells shrinking towards
  // the channel walls (ratio 0.97: the Stokes layers that the passing vortices drive there), and the
  // cut-cell balance and the wall momentum balance (measured: CD_max -0.16 %, St +0.81 % of the
  // bound midpoints, CL_max -1.59 %, lift between -1.0183 and 0.9841; with dp/dn = 0 on the
  // cylinder +0.23 %, +0.80 %, -1.31 %; the former default, staircase balance, walls 1.05 and a D/64
  // core: -0.56 %, +0.88 %, -3.1 %). With dp/dn = 0, a D/96 core added nothing to the lift (CD_max
  // +0.40 %, CL_max -1.26 %, St +0.80 %; lift amplitude 1.0046 against 1.0040) at 4x the cost, nor
  // did half the time step (--cfl 0.25: CD_max +0.29 %, CL_max -1.39 %, St +0.80 %).
  // With today's default (--t-end 7, lift amplitude / CL_max over [6, 7) s, one thread each): this
  // grid 1.0001 / 0.9831; a D/96 core 1.0026 / 0.9854 (1661 s); the core 3 D into the wake
  // 0.9986 / 0.9817; a D/32 box with its spacing out to the walls 0.9983 / 0.9814; walls 1
  // 0.9977 / 0.9807, 0.965 1.0002 / 0.9832; no stretching at all outside the core 0.9982 / 0.9812;
  // a fixed step of 3.6e-4 s 1.0001 / 0.9831. But [6, 7) s is not yet the periodic state on every
  // grid: the lift's per-period maxima still grow there, by about half as much each period (this
  // grid: 0.98314 at 6.8 s, 0.98406 from 9.5 s on), and finer cores start shedding later. With
  // their maxima extrapolated that way: D/64 core 0.9819 (run to 7.8 s, 2144 s; amplitude 0.9990,
  // CD_max 3.2207) and D/96 0.9864 (amplitude 1.0036), against 0.98406 here: no monotone trend, a
  // spread of 0.5 %, all 1.4-1.8 % below the bound midpoint. The walls matter more than the core: a
  // D/64 core with the cells growing towards the walls (ratio 1.05) saturates at only 0.9693. On
  // this same grid DFG 2D-3 (dfg_2d3) meets the high-precision CL_max of John (2004) within +0.38 %
  // and its time within 0.001 s. Half the step (--cfl 0.25, to t = 10) moves this grid's 2D-2
  // numbers little: CL_max 0.98349 (-0.06 %), CL_min -1.01755, CD_max 3.22893 (+0.13 %), St 0.30243.
  // OpenFOAM's do not (tools/scripts/openfoam_dfg.py, pimpleFoam, t_end 7): at 48 cells per cylinder
  // quarter CL_max 1.00642 / 0.98254 / 0.97076 at Courant 0.5 / 0.25 / 0.125 (first order in its
  // step: the change halves with it; at 0.25 CL_min -1.01744, CD_max 3.22792, St 0.29994, within
  // 0.1 % of this grid but for St), at 32 cells 0.99471 / 0.96205 at 0.5 / 0.25. Extrapolated in the
  // step, about 0.959 at 48 cells and 0.929 at 32: the peer's lift maximum falls with its step and
  // rises with its mesh by several % each at these meshes, so neither its 1.008 at 64 cells and
  // Courant 0.5 nor its small-step values tell where the converged value lies. Its step error is
  // PISO's splitting: with 3 PIMPLE outer iterations (converged in the step at Courant 0.5; 32
  // cells: 0.92609 at 0.5, 0.92807 at 0.25) it gives 0.92609 / 0.94618 / 0.95861 at 32 / 40 / 48
  // cells (St 0.29828 / 0.29980 / 0.30051), which extrapolate to 0.987 at second order and to
  // 1.002 at the observed order 1.4: the peer converged in time points at a lift 0.3-2 % above ours.
  // Nor is the deficit the surface evaluation's: with a third probe (--wall-extrapolation quadratic,
  // t_end 7, over [6.3, 7] s) the lift amplitude is 0.9987 against 1.0001 (CL_max 0.98199 against
  // 0.98314), while CD_max rises by 1.1 % (3.2607 against 3.2244) away from the control-volume drag
  // 3.2238, which the linear extrapolation matches within 0.02 %.
  // 2D-3 on the same grid as 2D-2 (the same Reynolds number at the sine's peak).
  const bool default_grid = variant >= 2 && !coarse && a.cells_per_diameter == 0 && a.core_cells_per_diameter == 0;
  ds.core_cells_per_diameter = default_grid ? 48 : a.core_cells_per_diameter;
  if (default_grid && a.wall_stretch_ratio == 0) ds.wall_stretch_ratio = 0.97;
  const int finest = std::max(ds.cells_per_diameter, ds.core_cells_per_diameter);
  const std::size_t expected = static_cast<std::size_t>(std::ceil(ds.t_end / (ds.cfl * 0.1 / finest / 1.8 /
                                                                              (variant == 1 ? 0.3 : 1.5))));
  log::Progress progress(name + " step", expected);
  ds.progress = [&](const StepStats& st) {
    progress.update(static_cast<std::size_t>(st.step),
                    "t " + fmt("%.4f s", st.time) + "  dt " + fmt("%.3g", st.dt) + "  CFL " + fmt("%.3f", st.cfl) +
                        "  Poisson " + std::to_string(st.poisson_iterations) + " it  momentum " +
                        std::to_string(st.helmholtz_iterations) + " it  div " + fmt("%.1e", st.max_divergence));
  };
  const DfgResult r = run_dfg(ds);
  progress.finish("t " + fmt("%.4f s", r.history.back().t));

  const std::filesystem::path dir = out / name;
  std::filesystem::create_directories(dir);
  std::ostringstream csv;
  csv << "t,cd,cl,dp,cd_pressure,cl_pressure,cd_cv,cl_cv\n";
  char line[256];
  for (const DfgSample& q : r.history) {
    std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", q.t, q.cd, q.cl, q.dp, q.cd_pressure,
                  q.cl_pressure, q.cd_cv, q.cl_cv);
    csv << line;
  }
  write_text_atomic(dir / "forces.csv", csv.str());

  Summary s("validation", name,
            variant == 1   ? "DFG 2D-1 (Re 20, steady): drag, lift and pressure difference of the ghost-cell immersed "
                             "cylinder against the published bounds"
            : variant == 2 ? "DFG 2D-2 (Re 100, periodic): maximum drag and lift and Strouhal number of the ghost-cell "
                             "immersed cylinder against the published bounds"
                           : "DFG 2D-3 (Um = 1.5 sin(pi t/8), t in [0, 8]): maximum drag and lift, their times and the "
                             "pressure difference at t = 8 of the ghost-cell immersed cylinder against reference values");
  const std::string src = ref.value("source", std::string("Schaefer & Turek 1996"));
  // Goal: within 1% of the midpoint of each published bound interval (inside the bounds is better).
  const auto graded = [&](const std::string& metric, const std::string& field, double value) {
    const auto& bounds = R.at(field).at("bounds");
    const double lo = bounds[0].get<double>(), hi = bounds[1].get<double>();
    const double mid = 0.5 * (lo + hi);
    if (coarse) s.info(metric, value);
    else s.relative(metric, value, mid, 0.01, src + ", bounds [" + fmt("%g", lo) + ", " + fmt("%g", hi) + "]");
    s.info(metric + "_inside_bounds", value >= lo && value <= hi ? 1.0 : 0.0);
  };
  // 2D-3's reference values (John 2004, not bounds): the maxima within 1%, their times within one
  // percent of the 8 s run; dp at t = 8, a small difference of two pressures, as info.
  const auto against_value = [&](const std::string& metric, const std::string& field, double value, double tol,
                                 double scale) {
    const double ref_value = R.at(field).get<double>();
    if (coarse) s.info(metric, value);
    else if (scale > 0) s.absolute(metric, value, ref_value, tol * scale, src + " 2D-3 (John 2004)");
    else s.relative(metric, value, ref_value, tol, src + " 2D-3 (John 2004)");
  };
  if (variant == 3) {
    against_value("CD_max", "CD_max", r.cd_max, 0.01, 0);
    against_value("CL_max", "CL_max", r.cl_max, 0.01, 0);
    against_value("t_CD_max", "t_CD_max", r.t_cd_max, 0.01, 8.0);
    against_value("t_CL_max", "t_CL_max", r.t_cl_max, 0.01, 8.0);
    s.info("dp_t8", r.dp);
    s.info("dp_t8_reference", R.at("dp_t8").get<double>());
    s.info("CD_max_control_volume", r.cd_max_cv);
    s.info("CL_max_control_volume", r.cl_max_cv);
  } else if (variant == 1) {
    graded("CD", "CD", r.cd);
    graded("CL", "CL", r.cl);
    graded("dp", "dp", r.dp);
    s.info("CD_drift_last_second", r.cd_drift);
  } else {
    graded("CD_max", "CD_max", r.cd_max);
    graded("CL_max", "CL_max", r.cl_max);
    graded("St", "St", r.st);
    // Not among the goals, but the benchmark's fourth quantity: a check of the pressure
    // field itself, away from the body's surface.
    if (std::isfinite(r.dp_half_period)) {
      graded("dp_half_period", "dp_half_period", r.dp_half_period);
      s.info("t_lift_peak", r.t_lift_peak, "s");
    }
    s.info("periods_in_window", r.periods);
    s.info("CD_mean", r.cd_mean);
    s.info("CL_min", r.cl_min);
    s.info("CD_max_control_volume", r.cd_max_cv);
    s.info("CL_max_control_volume", r.cl_max_cv);
  }
  s.info("steps", static_cast<double>(r.steps));
  s.info("cells", static_cast<double>(r.cells));
  s.info("ghost_cells", static_cast<double>(r.ghost_cells));
  s.info("mean_poisson_iterations", r.mean_poisson_iterations);
  s.info("max_poisson_iterations", r.max_poisson_iterations);
  s.info("mean_momentum_iterations_all_components", r.mean_momentum_iterations);
  s.info("solver_seconds", r.cpu_seconds, "s");
  s.parameters() = {{"coarse", coarse}, {"cells_per_diameter", ds.cells_per_diameter}, {"t_end", ds.t_end},
                    {"window", ds.window}, {"cfl", ds.cfl}, {"ramp_time", ds.ramp_time},
                    {"polygon_vertices", ds.polygon_vertices}, {"box_x1", ds.box_x1},
                    {"core_cells_per_diameter", ds.core_cells_per_diameter}, {"core_wake", ds.core_wake},
                    {"stretch_ratio", ds.stretch_ratio}, {"wall_stretch_ratio", ds.wall_stretch_ratio},
                    {"cut_cell_continuity", ds.cut_cell_continuity}, {"viscous_wall_pressure", ds.viscous_wall_pressure},
                    {"wall_extrapolation", a.wall_extrapolation}, {"reference", a.reference}};
  log::info(name + ": " +
            (variant == 1   ? "CD " + fmt("%.5f", r.cd) + "  CL " + fmt("%.5f", r.cl) + "  dp " + fmt("%.5f", r.dp)
             : variant == 2 ? "CD_max " + fmt("%.5f", r.cd_max) + "  CL_max " + fmt("%.5f", r.cl_max) + "  St " +
                                  fmt("%.5f", r.st)
                            : "CD_max " + fmt("%.5f", r.cd_max) + " at " + fmt("%.4f", r.t_cd_max) + " s  CL_max " +
                                  fmt("%.5f", r.cl_max) + " at " + fmt("%.4f", r.t_cl_max) + " s  dp(8) " +
                                  fmt("%.5f", r.dp)) +
            "  (" + std::to_string(r.steps) + " steps, " + fmt("%.1f s", r.cpu_seconds) + ")");
  wall_out = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return finish(s, dir, wall_out);
}

// ---- Turek-Hron CFD2 / CFD3 (rigid flag) ----------------------------------------------------------

int turek_hron(int variant, bool coarse, const BodyCaseArgs& a, double kick_velocity, const std::filesystem::path& out,
               double& wall_out) {
  const auto t0 = std::chrono::steady_clock::now();
  const nlohmann::json ref = read_reference(a.reference);
  const std::string key = variant == 2 ? "CFD2" : "CFD3";
  if (!ref.contains("cases") || !ref["cases"].contains(key))
    throw Error("--reference: " + a.reference + " has no 'cases." + key + "' entry");
  const nlohmann::json& R = ref["cases"][key];
  const std::string name = variant == 2 ? "turek_hron_cfd2" : "turek_hron_cfd3";
  TurekHronSetup ts;
  ts.variant = variant;
  // Default grids (measured against the reference, cut-cell balance and the wall momentum balance;
  // in brackets the older variants, all with dp/dn = 0 on the body):
  //   CFD2: D/24 box + D/48 core: drag -0.11 %, lift +1.24 % (dp/dn = 0: +0.33 %, +1.36 %;
  //         staircase: -0.35 %, +1.4 %; uniform D/32: -2.8 %, +0.7 %); steady to 0.003 N/m per
  //         second by t = 6 s.
  //   CFD3: D/32 box reaching 2 D behind the tip + D/64 core, cells shrinking towards the walls
  //         (0.98, below): drag mean -1.55 %, drag amplitude +1.31 %, lift amplitude -1.71 %,
  //         frequency +1.09 %; control-volume drag mean -0.35 % (dp/dn = 0: -1.27 %, +1.33 %,
  //         -1.72 %, +1.10 %; walls 1.05: -1.4 %, -3.6 %, -8.1 %, +1.1 %; and the staircase
  //         balance: -2.3 %, -9.5 %, -12.5 %, +0.9 %; uniform D/32: -7.4 %, -49 %, -42 %, 0.0 %).
  //   CFD3's lift amplitude (mostly the flag's) depends on where the flag's straight edges fall in
  //   their cells, more than on h: the core's faces are symmetric about y = 0.2, so an edge cell
  //   holds a fluid fraction 1 - frac(0.1 N_core). Measured (t_end 7, window [6, 7), walls 0.98,
  //   box N_core / 2, wake box 2): D/48 (fraction 0.2, the cell's centre inside the flag) 402.7
  //   N/m, 4.432 Hz; D/56 (0.4) 409.8, 4.431; D/44 (0.6, centre in the fluid) 410.9, 4.442; the
  //   default D/64 (0.6) 430.3, 4.444. Within one alignment (D/44 -> D/64) the amplitude rises by
  //   19 N/m, so the default's -1.7 % is a grid error of the flag's edges, not converged, and no
  //   evidence of a lift deficit elsewhere (walls 0.97 instead of 0.98: +0.3 %; half the step:
  //   -0.25 %; wake box 1 -> 2: +0.05 %, all at D/48).
  const bool default_grid = !coarse && a.cells_per_diameter == 0 && a.core_cells_per_diameter == 0;
  ts.cells_per_diameter = a.cells_per_diameter > 0 ? a.cells_per_diameter : coarse ? 12 : variant == 2 ? 24 : 32;
  ts.core_cells_per_diameter = default_grid ? (variant == 2 ? 48 : 64) : a.core_cells_per_diameter;
  if (default_grid && variant == 3) ts.wake_box = 2;
  // CFD3's shedding drives unsteady Stokes layers on the channel walls, sqrt(2 nu / omega) ~ D/12
  // thick, which cells growing by 1.05 from the box do not resolve: cells shrinking towards the walls
  // raise the lift amplitude (D/24 box + D/48 core, cut cells, t in [4.5, 5] s: 397.0 -> 419.8 N/m
  // with ratio 0.97). From a D/32 box a 0.97 series sums to 0.10 m of the 0.11 m to the upper wall,
  // so the default grid takes 0.98.
  if (default_grid && variant == 3 && a.wall_stretch_ratio == 0) ts.wall_stretch_ratio = 0.98;
  // CFD3 from rest saturates only after t ~ 12 s (measured at 32 cells/D); the push on the wake
  // at the end of the ramp (TurekHronSetup::kick_*) starts the shedding at once: with it the lift
  // amplitude is saturated from t ~ 5 s (default grid: 430.26 N/m over [5, 6), 430.29 over [6, 7)).
  if (variant == 3) ts.kick_velocity = kick_velocity >= 0 ? kick_velocity : 2.0;
  ts.t_end = a.t_end > 0 ? a.t_end : variant == 2 ? (coarse ? 2.0 : 6.0) : (coarse ? 1.0 : 7.0);
  ts.window = variant == 3 ? std::min(1.0, 0.4 * ts.t_end) : 0.0;
  if (a.wake_box > 0) ts.wake_box = a.wake_box;
  if (a.stretch_ratio > 0) ts.stretch_ratio = a.stretch_ratio;
  if (a.cfl > 0) ts.cfl = a.cfl;
  if (a.wall_stretch_ratio > 0) ts.wall_stretch_ratio = a.wall_stretch_ratio;
  if (a.core_wake > 0) ts.core_wake = a.core_wake;
  ts.cut_cell_continuity = !a.staircase_balance;
  ts.viscous_wall_pressure = !a.zero_wall_pressure_gradient;
  // Once developed, the fastest flow past the body is about 1.8 Um: dt = cfl h / (1.8 Um).
  const double um = variant == 2 ? 1.5 : 3.0;
  const int finest = std::max(ts.cells_per_diameter, ts.core_cells_per_diameter);
  const std::size_t expected = static_cast<std::size_t>(std::ceil(ts.t_end / (ts.cfl * 0.1 / finest / 1.8 / um)));
  log::Progress progress(name + " step", expected);
  ts.progress = [&](const StepStats& st) {
    progress.update(static_cast<std::size_t>(st.step),
                    "t " + fmt("%.4f s", st.time) + "  dt " + fmt("%.3g", st.dt) + "  CFL " + fmt("%.3f", st.cfl) +
                        "  Poisson " + std::to_string(st.poisson_iterations) + " it  div " +
                        fmt("%.1e", st.max_divergence));
  };
  const TurekHronResult r = run_turek_hron(ts);
  progress.finish("t " + fmt("%.4f s", r.history.back().t));

  const std::filesystem::path dir = out / name;
  std::filesystem::create_directories(dir);
  std::ostringstream csv;
  csv << "t,drag,lift,drag_viscous,lift_viscous,drag_flag,lift_flag,drag_cv,lift_cv\n";
  char line[256];
  for (const TurekHronSample& q : r.history) {
    std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", q.t, q.drag, q.lift,
                  q.drag_viscous, q.lift_viscous, q.drag_flag, q.lift_flag, q.drag_cv, q.lift_cv);
    csv << line;
  }
  write_text_atomic(dir / "forces.csv", csv.str());

  Summary s("validation", name,
            variant == 2 ? "Turek-Hron CFD2 (Re 100, steady, rigid flag): drag and lift [N/m] on cylinder + flag of the "
                           "ghost-cell immersed body"
                         : "Turek-Hron CFD3 (Re 200, periodic, rigid flag): drag and lift [N/m] mean and amplitude and "
                           "the lift frequency of the ghost-cell immersed body");
  const std::string src = ref.value("source", std::string("Turek & Hron 2006"));
  const auto graded = [&](const std::string& metric, double value, double reference, double tol, const std::string& u) {
    if (coarse) s.info(metric, value, u);
    else s.relative(metric, value, reference, tol, src, u);
  };
  if (variant == 2) {
    // Issue 4 goal: drag within 2 %, lift within 5 %.
    graded("drag", r.drag, R.at("drag").get<double>(), 0.02, "N/m");
    graded("lift", r.lift, R.at("lift").get<double>(), 0.05, "N/m");
    s.info("drag_drift_last_second", r.drag_drift, "N/m");
  } else {
    // Drag mean within 2 %, amplitudes and frequency within 3 %. The lift mean (-11.9 N/m) is a
    // small difference of large swings: graded absolutely, to 5 % of the lift amplitude.
    const double dm = R.at("drag")[0].get<double>(), da = R.at("drag")[1].get<double>();
    const double lm = R.at("lift")[0].get<double>(), la = R.at("lift")[1].get<double>();
    graded("drag_mean", r.drag_mean, dm, 0.02, "N/m");
    graded("drag_amplitude", r.drag_amplitude, da, 0.03, "N/m");
    if (coarse) s.info("lift_mean", r.lift_mean, "N/m");
    else s.absolute("lift_mean", r.lift_mean, lm, 0.05 * la, src + "; tolerance 5 % of the lift amplitude", "N/m");
    graded("lift_amplitude", r.lift_amplitude, la, 0.03, "N/m");
    graded("frequency", r.frequency, R.at("freq").get<double>(), 0.03, "Hz");
    s.info("periods_in_window", r.periods);
    s.info("lift_amplitude_previous_window", r.lift_amplitude_previous, "N/m");
    s.info("lift_amplitude_change", r.lift_amplitude_change);
  }
  s.info("steps", static_cast<double>(r.steps));
  s.info("cells", static_cast<double>(r.cells));
  s.info("ghost_cells", static_cast<double>(r.ghost_cells));
  s.info("h", r.h, "m");
  // The independent control-volume force (CFD2: final; CFD3: window mean and amplitude).
  s.info("drag_control_volume", r.drag_cv, "N/m");
  s.info("lift_control_volume", r.lift_cv, "N/m");
  if (variant == 3) {
    s.info("drag_amplitude_control_volume", r.drag_amplitude_cv, "N/m");
    s.info("lift_amplitude_control_volume", r.lift_amplitude_cv, "N/m");
  }
  s.info("mean_poisson_iterations", r.mean_poisson_iterations);
  s.info("max_poisson_iterations", r.max_poisson_iterations);
  s.info("solver_seconds", r.cpu_seconds, "s");
  s.parameters() = {{"coarse", coarse}, {"cells_per_diameter", ts.cells_per_diameter}, {"t_end", ts.t_end},
                    {"window", ts.window}, {"cfl", ts.cfl}, {"ramp_time", ts.ramp_time},
                    {"circle_vertices", ts.circle_vertices}, {"wake_box", ts.wake_box},
                    {"stretch_ratio", ts.stretch_ratio}, {"wall_stretch_ratio", ts.wall_stretch_ratio},
                    {"cut_cell_continuity", ts.cut_cell_continuity}, {"viscous_wall_pressure", ts.viscous_wall_pressure},
                    {"core_cells_per_diameter", ts.core_cells_per_diameter}, {"core_wake", ts.core_wake},
                    {"kick_velocity", ts.kick_velocity}, {"kick_start", ts.kick_start},
                    {"kick_duration", ts.kick_duration}, {"reference", a.reference}};
  log::info(name + ": " +
            (variant == 2 ? "drag " + fmt("%.4f", r.drag) + "  lift " + fmt("%.4f", r.lift)
                          : "drag " + fmt("%.3f", r.drag_mean) + " +- " + fmt("%.3f", r.drag_amplitude) + "  lift " +
                                fmt("%.3f", r.lift_mean) + " +- " + fmt("%.3f", r.lift_amplitude) + "  f " +
                                fmt("%.4f", r.frequency)) +
            "  (" + std::to_string(r.steps) + " steps, " + fmt("%.1f s", r.cpu_seconds) + ")");
  wall_out = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return finish(s, dir, wall_out);
}

// ---- Couette flow between immersed circles --------------------------------------------------------

int ib_couette(bool coarse, const std::filesystem::path& out, double& wall_out) {
  const auto t0 = std::chrono::steady_clock::now();
  Summary s("validation", "ib_couette",
            "circular Couette flow between two immersed concentric circles (inner turning, outer at rest) on a "
            "non-conforming Cartesian grid: observed L2 order of the velocity with the ghost-cell boundary");
  const std::vector<int> ns = coarse ? std::vector<int>{32, 64} : std::vector<int>{32, 64, 128};
  std::vector<IbCouetteResult> r;
  for (int n : ns) {
    IbCouetteSetup cs;
    cs.n = n;
    r.push_back(run_ib_couette(cs));
    log::info("ib_couette n=" + std::to_string(n) + ": u L2 " + fmt("%.4e", r.back().u_l2) + ", max " +
              fmt("%.4e", r.back().u_max) + ", " + std::to_string(r.back().steps) + " steps, Poisson " +
              fmt("%.1f", r.back().mean_poisson_iterations) + " it/step, momentum " +
              fmt("%.1f", r.back().mean_momentum_iterations) + " it/step, " + fmt("%.1fs", r.back().cpu_seconds));
    s.info("u_l2_n" + std::to_string(n), r.back().u_l2, "m/s");
    s.info("u_max_n" + std::to_string(n), r.back().u_max, "m/s");
    s.info("mean_poisson_iterations_n" + std::to_string(n), r.back().mean_poisson_iterations);
    s.info("mean_momentum_iterations_n" + std::to_string(n), r.back().mean_momentum_iterations);
  }
  const std::size_t m = r.size() - 1;
  const double order = std::log2(r[m - 1].u_l2 / r[m].u_l2);
  const std::string src = "exact circular Couette solution u_theta = A r + B / r; issue 4 goal: order >= 1.8";
  // Second order expected; the band [1.8, 2.2] is the floor and the same margin above.
  if (coarse) s.info("order_velocity_l2", order);
  else s.absolute("order_velocity_l2", order, 2.0, 0.2, src);
  s.info("order_velocity_max", std::log2(r[m - 1].u_max / r[m].u_max));
  const IbCouetteSetup d;
  s.parameters() = {{"coarse", coarse}, {"grids", ns}, {"r1", d.r1}, {"r2", d.r2}, {"omega", d.omega}, {"nu", d.nu},
                    {"t_end", d.t_end}, {"box", "[-0.6,0.6]^2"}, {"polygon_vertices", d.polygon_vertices}};
  wall_out = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return finish(s, out / "ib_couette", wall_out);
}

// ---- Moving immersed body: towed and oscillating cylinders -----------------------------------------

int cylinder_towed(bool coarse, bool staircase_balance, const std::filesystem::path& out, double& wall_out) {
  const auto t0 = std::chrono::steady_clock::now();
  TowedCylinderSetup ts = coarse ? TowedCylinderSetup::coarse() : TowedCylinderSetup{};
  ts.cut_cell_continuity = !staircase_balance;
  log::Progress progress("cylinder_towed step", static_cast<std::size_t>(std::ceil(ts.t_end / (ts.cfl / ts.cells_per_diameter))));
  ts.progress = [&](const StepStats& st) {
    progress.update(static_cast<std::size_t>(st.step), "t " + fmt("%.3f", st.time) + "  Poisson " +
                                                          std::to_string(st.poisson_iterations) + " it");
  };
  const TowedCylinderResult r = run_towed_cylinder(ts);
  progress.finish("t " + fmt("%.3f", r.time.back()));
  const std::filesystem::path dir = out / "cylinder_towed";
  std::filesystem::create_directories(dir);
  std::ostringstream csv;
  csv << "t,cd_towed,cd_fixed,cd_fixed_vertex\n";
  char line[128];
  for (std::size_t n = 0; n < r.time.size(); ++n) {
    std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g,%.9g\n", r.time[n], r.cd_towed[n], r.cd_fixed[n], r.cd_fixed_vertex[n]);
    csv << line;
  }
  write_text_atomic(dir / "forces.csv", csv.str());
  log::info("cylinder_towed: CD towed " + fmt("%.5f", r.cd_towed_end) + ", fixed " + fmt("%.5f", r.cd_fixed_end) +
            " (mean of " + std::to_string(ts.fixed_offsets) + " sub-cell positions; vertex-centred " +
            fmt("%.5f", r.cd_fixed_vertex_end) + ")" + " (averaged over " + std::to_string(ts.filter_cells) + " cell crossings), max relative difference over t >= " +
            fmt("%g", ts.t_compare) + ": " + fmt("%.3e", r.max_relative_difference) + " averaged, " +
            fmt("%.3e", r.max_relative_difference_raw) + " raw (" + fmt("%.1f s", r.cpu_seconds) + ")");
  Summary s("validation", "cylinder_towed",
            "cylinder towed at constant speed through fluid at rest against the fixed cylinder in a uniform stream "
            "(same Re, grid spacing and solver; the fixed drag averaged over the cylinder's sub-cell positions, as the "
            "towed one is): Galilean invariance of the moving ghost-cell boundary");
  // Issue 4 goal: the same drag within 1% after start-up (the coarse grid only reports).
  if (coarse) s.info("max_relative_drag_difference", r.max_relative_difference);
  else s.at_most("max_relative_drag_difference", r.max_relative_difference, 0.01, "issue 4: towed = fixed drag within 1%");
  s.info("max_relative_drag_difference_raw", r.max_relative_difference_raw);
  s.info("max_relative_drag_difference_vertex_centred_fixed", r.max_relative_difference_vertex);
  s.info("CD_towed_end", r.cd_towed_end);
  s.info("CD_fixed_end", r.cd_fixed_end);
  s.info("CD_fixed_vertex_centred_end", r.cd_fixed_vertex_end);
  s.info("fixed_position_spread_end", r.fixed_position_spread);
  s.info("steps", static_cast<double>(r.steps));
  s.info("cells_all_runs", static_cast<double>(r.cells));  // towed + fixed_offsets fixed runs
  s.info("solver_seconds", r.cpu_seconds, "s");
  s.parameters() = {{"coarse", coarse}, {"re", ts.re}, {"cells_per_diameter", ts.cells_per_diameter},
                    {"t_end", ts.t_end}, {"t_compare", ts.t_compare}, {"half_height", ts.half_height},
                    {"filter_cells", ts.filter_cells}, {"cfl", ts.cfl}, {"coupling_fraction", ts.coupling_fraction},
                    {"cut_cell_continuity", ts.cut_cell_continuity},
                    {"polygon_vertices", ts.polygon_vertices}, {"fixed_offsets", ts.fixed_offsets}};
  wall_out = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return finish(s, dir, wall_out);
}

int cylinder_oscillating(bool coarse, const std::filesystem::path& out, double& wall_out) {
  const auto t0 = std::chrono::steady_clock::now();
  OscillatingCylinderSetup os = coarse ? OscillatingCylinderSetup::coarse() : OscillatingCylinderSetup{};
  Summary s("validation", "cylinder_oscillating",
            "in-line oscillating cylinder in fluid at rest (KC 5, Re 100, Duetsch et al. 1998): high-frequency content "
            "of the force history with the moving-body treatment (cut-cell mass balance and cleared-cell values), "
            "with the cleared-cell values alone, and with neither");
  const std::filesystem::path dir = out / "cylinder_oscillating";
  std::filesystem::create_directories(dir);
  // Three variants: the full treatment (cut-cell mass balance and cleared-cell values), the
  // staircase mass balance with the cleared-cell values, and neither.
  struct Variant {
    const char* tag;
    bool cut, fresh;
  };
  const Variant variants[] = {{"with_treatment", true, true}, {"staircase_balance", false, true}, {"without_treatment", false, false}};
  std::vector<OscillatingCylinderResult> r;
  for (const Variant& v : variants) {
    os.fresh_cell_treatment = v.fresh;
    os.cut_cell_continuity = v.cut;
    r.push_back(run_oscillating_cylinder(os));
    const OscillatingCylinderResult& q = r.back();
    const std::string tag = v.tag;
    log::info("cylinder_oscillating " + tag + ": energy above 10 f " + fmt("%.3e", q.high_frequency_fraction) +
              ", max |d2F| / max|F| " + fmt("%.3e", q.max_second_difference) + ", Cd " + fmt("%.3f", q.cd_morison) +
              ", Ca " + fmt("%.3f", q.ca_morison) + ", " + std::to_string(q.cleared_cells) + " cleared cells (" +
              fmt("%.1f s", q.cpu_seconds) + ")");
    // Issue 4: a force history without spikes from cells being cleared. The in-line force at KC 5
    // is a smooth Morison-type signal whose harmonics above 10 f carry a negligible share of its
    // energy, so 0.1% above 10 f grades "without spikes" (the staircase balance: about 2% at 16
    // cells per diameter). The coarse grid only reports.
    if (v.cut && v.fresh && !coarse)
      s.at_most("high_frequency_energy_fraction_" + tag, q.high_frequency_fraction, 1e-3,
                "issue 4: no force spikes from freshly cleared cells (energy above 10 f <= 0.1%)");
    else
      s.info("high_frequency_energy_fraction_" + tag, q.high_frequency_fraction);
    s.info("max_second_difference_over_amplitude_" + tag, q.max_second_difference);
    s.info("cd_morison_" + tag, q.cd_morison);
    s.info("ca_morison_" + tag, q.ca_morison);
    s.info("cleared_cells_" + tag, static_cast<double>(q.cleared_cells));
    s.info("max_continuity_residual_" + tag, q.max_continuity_residual);
  }
  // Energy above 10 f without any treatment over that with the full treatment.
  s.info("high_frequency_reduction_factor", r[2].high_frequency_fraction / std::max(r[0].high_frequency_fraction, 1e-300));
  s.info("high_frequency_reduction_factor_cut_cells",
         r[1].high_frequency_fraction / std::max(r[0].high_frequency_fraction, 1e-300));
  std::ostringstream csv;
  csv << "t,fx_with_treatment,fx_staircase_balance,fx_without_treatment\n";
  char line[128];
  for (std::size_t n = 0; n < r[0].time.size(); ++n) {
    std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g,%.9g\n", r[0].time[n], r[0].fx[n], r[1].fx[n], r[2].fx[n]);
    csv << line;
  }
  write_text_atomic(dir / "forces.csv", csv.str());
  s.parameters() = {{"coarse", coarse}, {"kc", os.kc}, {"re", os.re}, {"cells_per_diameter", os.cells_per_diameter},
                    {"steps_per_period", os.steps_per_period}, {"periods", os.periods},
                    {"periods_analysed", os.periods_analysed}, {"half_width", os.half_width},
                    {"polygon_vertices", os.polygon_vertices}};
  wall_out = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return finish(s, dir, wall_out);
}

// ---- Sphere at Re 100 (3-D triangulated immersed boundary) ----------------------------------------

int sphere_re100(bool coarse, const BodyCaseArgs& a, const std::filesystem::path& out, double& wall_out) {
  const auto t0 = std::chrono::steady_clock::now();
  const nlohmann::json ref = read_reference(a.reference);
  if (!ref.contains("Re100") || !ref["Re100"].contains("CD") || !ref["Re100"]["CD"].is_number())
    throw Error("--reference: " + a.reference + " has no numeric 'Re100.CD' entry");
  const double cd_ref = ref["Re100"]["CD"].get<double>();
  SphereFlowSetup ss;
  if (coarse) {
    ss.cells_per_diameter = 6;
    ss.t_end = 8;
    ss.box_x = {-4, 8};
    ss.box_half_width = 4;
    ss.subdivisions = 3;
  }
  if (a.cells_per_diameter > 0) ss.cells_per_diameter = a.cells_per_diameter;
  if (a.t_end > 0) ss.t_end = a.t_end;
  ss.viscous_wall_pressure = a.wall_momentum_balance;
  log::Progress progress("sphere_re100 step",
                         // dt ~ cfl h / (|u| + |v| + |w|), about cfl h / 1.6 near the sphere
                         static_cast<std::size_t>(std::ceil(1.6 * ss.t_end / (ss.cfl / ss.cells_per_diameter))));
  ss.progress = [&](const StepStats& st, double cd) {
    progress.update(static_cast<std::size_t>(st.step), "t " + fmt("%.3f", st.time) + "  CD " + fmt("%.4f", cd) +
                                                          "  Poisson " + std::to_string(st.poisson_iterations) + " it");
  };
  const SphereFlowResult r = run_sphere_flow(ss);
  progress.finish("CD " + fmt("%.4f", r.cd));
  const std::filesystem::path dir = out / "sphere_re100";
  std::filesystem::create_directories(dir);
  std::ostringstream csv;
  csv << "t,cd\n";
  char line[64];
  for (std::size_t n = 0; n < r.time.size(); ++n) {
    std::snprintf(line, sizeof line, "%.9g,%.9g\n", r.time[n], r.cd_history[n]);
    csv << line;
  }
  write_text_atomic(dir / "forces.csv", csv.str());
  log::info("sphere_re100 D/h=" + std::to_string(ss.cells_per_diameter) + " (" + std::to_string(r.cells[0]) + "x" +
            std::to_string(r.cells[1]) + "x" + std::to_string(r.cells[2]) + " cells): CD " + fmt("%.5f", r.cd) +
            " (pressure " + fmt("%.5f", r.cd_pressure) + ", viscous " + fmt("%.5f", r.cd_viscous) + "; control volume " +
            fmt("%.5f", r.cd_control_volume) + "), drift over 5 D/U " +
            fmt("%.2e", r.cd_drift) + ", " + std::to_string(r.steps) + " steps, " + fmt("%.1f s", r.cpu_seconds));
  Summary s("validation", "sphere_re100",
            "steady flow past a sphere at Re 100 (3-D ghost-cell immersed boundary on a closed triangulated surface): "
            "drag coefficient against Johnson & Patel (1999)");
  const std::string src = a.reference + " (Johnson & Patel 1999); issue 4 goal: within 2%";
  if (coarse) s.info("CD", r.cd);
  else s.relative("CD", r.cd, cd_ref, 0.02, src);
  s.info("CD_pressure", r.cd_pressure);
  s.info("CD_viscous", r.cd_viscous);
  s.info("CD_control_volume", r.cd_control_volume);
  s.info("CL_lateral", r.cl);
  s.info("CD_drift_last_5", r.cd_drift);
  solver_statistics_3d(s, r);
  s.parameters() = {{"coarse", coarse}, {"re", ss.re}, {"cells_per_diameter", ss.cells_per_diameter},
                    {"t_end", ss.t_end}, {"cfl", ss.cfl}, {"box_x", ss.box_x}, {"box_half_width", ss.box_half_width},
                    {"core_x", ss.core_x}, {"core_half_width", ss.core_half_width},
                    {"stretch_ratio", ss.stretch_ratio}, {"icosphere_subdivisions", ss.subdivisions},
                    {"triangles", r.triangles}, {"grid", r.cells}, {"reference", a.reference},
                    {"viscous_wall_pressure", ss.viscous_wall_pressure}, {"control_volume", ss.control_volume}};
  wall_out = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return finish(s, dir, wall_out);
}

// ---- DFG 3D-1Z (3-D triangulated body crossing the domain boundary) -------------------------------

int dfg_3d1z(bool coarse, const BodyCaseArgs& a, int span_cells, const std::filesystem::path& out, double& wall_out) {
  const auto t0 = std::chrono::steady_clock::now();
  const nlohmann::json ref = read_reference(a.reference);
  if (!ref.contains("3D-1Z") || !ref["3D-1Z"].contains("cD") || !ref["3D-1Z"]["cD"].is_number() ||
      !ref["3D-1Z"].contains("cL") || !ref["3D-1Z"]["cL"].is_number())
    throw Error("--reference: " + a.reference + " has no numeric '3D-1Z.cD' and '3D-1Z.cL' entries");
  const double cd_ref = ref["3D-1Z"]["cD"].get<double>(), cl_ref = ref["3D-1Z"]["cL"].get<double>();
  Dfg3dSetup ds;
  if (coarse) {  // CI: a coarse grid and a short run, information only (as the other coarse cases);
    // measured at D/6: cD 6.092 at t = 2.9 s, 6.0877 at the steady state (t = 4.8 s)
    ds.cells_per_diameter = 6;
    ds.segments = 64;
    ds.t_end = 2.5;
  }
  if (a.cells_per_diameter > 0) ds.cells_per_diameter = a.cells_per_diameter;
  if (a.t_end > 0) ds.t_end = a.t_end;
  if (span_cells > 0) ds.span_cells = span_cells;
  ds.viscous_wall_pressure = a.wall_momentum_balance;
  log::Progress progress("dfg_3d1z step",
                         // dt ~ cfl h / 0.6 (the fastest flow, beside the cylinder) at most
                         static_cast<std::size_t>(std::ceil(0.6 * ds.t_end / (ds.cfl * 0.1 / ds.cells_per_diameter))));
  ds.progress = [&](const StepStats& st, double cd) {
    progress.update(static_cast<std::size_t>(st.step), "t " + fmt("%.3f s", st.time) + "  cD " + fmt("%.4f", cd) +
                                                          "  CFL " + fmt("%.3f", st.cfl) + "  Poisson " +
                                                          std::to_string(st.poisson_iterations) + " it");
  };
  const Dfg3dResult r = run_dfg_3d1z(ds);
  progress.finish("cD " + fmt("%.4f", r.cd));
  const std::filesystem::path dir = out / "dfg_3d1z";
  std::filesystem::create_directories(dir);
  std::ostringstream csv;
  csv << "t,cd,cl,dp\n";
  char line[128];
  for (const Dfg3dSample& q : r.history) {
    std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g,%.9g\n", q.t, q.cd, q.cl, q.dp);
    csv << line;
  }
  write_text_atomic(dir / "forces.csv", csv.str());
  log::info("dfg_3d1z D/h=" + std::to_string(ds.cells_per_diameter) + " (" + std::to_string(r.cells[0]) + "x" +
            std::to_string(r.cells[1]) + "x" + std::to_string(r.cells[2]) + " cells): cD " + fmt("%.5f", r.cd) +
            " (pressure " + fmt("%.5f", r.cd_pressure) + ", viscous " + fmt("%.5f", r.cd_viscous) + ")  cL " +
            fmt("%.5f", r.cl) + "  dp " + fmt("%.5f", r.dp) + "  drift " + fmt("%.2e", r.cd_drift) + "/s" +
            (r.steady ? " (steady)" : " (t_end reached)") + ", " + std::to_string(r.steps) + " steps, " +
            fmt("%.1f s", r.cpu_seconds));
  Summary s("validation", "dfg_3d1z",
            "DFG 3D-1Z (Re 20, steady): drag of a wall-to-wall cylinder in a square channel (3-D triangulated "
            "ghost-cell body crossing the domain boundary) against Schaefer & Turek (1996)");
  const std::string src = ref.value("source", std::string("Schaefer & Turek 1996"));
  // Issue 4 goal: cD within 2% of the reference; cL and dp are information (published bounds
  // cL 0.008-0.010, dp 0.165-0.175).
  if (coarse) s.info("cD", r.cd);
  else s.relative("cD", r.cd, cd_ref, 0.02, src + " 3D-1Z; issue 4 goal: within 2%");
  s.info("cL", r.cl);
  s.info("cL_reference", cl_ref);
  s.info("dp", r.dp);
  s.info("cD_inside_bounds_6.05_6.25", r.cd >= 6.05 && r.cd <= 6.25 ? 1.0 : 0.0);
  s.info("cL_inside_bounds_0.008_0.010", r.cl >= 0.008 && r.cl <= 0.010 ? 1.0 : 0.0);
  s.info("dp_inside_bounds_0.165_0.175", r.dp >= 0.165 && r.dp <= 0.175 ? 1.0 : 0.0);
  s.info("cD_pressure", r.cd_pressure);
  s.info("cD_viscous", r.cd_viscous);
  s.info("cD_drift_per_second", r.cd_drift, "1/s");
  s.info("steady", r.steady ? 1.0 : 0.0);
  s.info("t_final", r.history.back().t, "s");
  solver_statistics_3d(s, r);
  s.parameters() = {{"coarse", coarse}, {"cells_per_diameter", ds.cells_per_diameter}, {"h", r.h},
                    {"grid", r.cells}, {"span_cells", r.cells[2]}, {"segments", ds.segments}, {"triangles", r.triangles},
                    {"overhang", ds.overhang}, {"stretch_ratio", ds.stretch_ratio}, {"cfl", ds.cfl},
                    {"t_end", ds.t_end}, {"t_min", ds.t_min}, {"steady_window", ds.steady_window},
                    {"steady_tolerance", ds.steady_tolerance}, {"reference", a.reference},
                    {"viscous_wall_pressure", ds.viscous_wall_pressure}};
  wall_out = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return finish(s, dir, wall_out);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fin-cfd: incompressible Navier-Stokes solver (fractional step, collocated, stretched grid)"};
  cli::Standard standard(app, "fin-cfd");
  app.require_subcommand(1);
  std::string out_dir = "results/validation";
  bool coarse = false;
  app.add_option("--out-dir", out_dir, "directory that receives <case>/summary.json")->capture_default_str();
  app.add_flag("--coarse", coarse, "the coarse (CI) variant of the case");
  auto* tg = app.add_subcommand("taylor_green", "order of accuracy in space and time (2-D Taylor-Green vortex)");
  ChannelArgs ch;
  auto* chan = app.add_subcommand("channel", "inlet/outlet channel: Poiseuille profile and pressure gradient");
  chan->add_option("--checkpoint-every", ch.checkpoint_every, "write <out>/channel/checkpoint.h5 every N steps (0: never)")
      ->capture_default_str();
  chan->add_option("--restart", ch.restart, "continue from this checkpoint file")->check(CLI::ExistingFile);
  chan->add_flag("--vtk", ch.vtk, "also write <out>/channel/flow.pvd (ParaView)");
  auto* couette = app.add_subcommand("ib_couette", "Couette flow between two immersed circles: observed order");
  auto* towed = app.add_subcommand("cylinder_towed", "towed cylinder against the fixed cylinder in a stream (Re 20)");
  bool towed_staircase = false;
  towed->add_flag("--staircase-balance", towed_staircase,
                  "the towed body without the cut-cell mass balance (to measure what it changes)");
  auto* oscillating = app.add_subcommand("cylinder_oscillating", "in-line oscillating cylinder (KC 5, Re 100): force spikes");
  BodyCaseArgs dfg_args{0, 0, "data/reference/schaefer_turek.json", 0, 0};
  auto* d1 = app.add_subcommand("dfg_2d1", "DFG 2D-1 cylinder benchmark (Re 20, steady), immersed boundary");
  auto* d2 = app.add_subcommand("dfg_2d2", "DFG 2D-2 cylinder benchmark (Re 100, periodic), immersed boundary");
  auto* d3 = app.add_subcommand("dfg_2d3", "DFG 2D-3 cylinder benchmark (sine inflow over 8 s), immersed boundary");
  for (auto* sc : {d1, d2, d3}) {
    add_body_case_options(sc, dfg_args, "s");
    add_channel_grid_options(sc, dfg_args, "grid: downstream end x of the uniform box [m] (default 0.6)");
    sc->add_option("--wall-extrapolation", dfg_args.wall_extrapolation,
                   "surface traction and dp: extrapolation from the probes at d, 2d to the wall (linear), or with a "
                   "third probe at 3d (quadratic), to compare")
        ->check(CLI::IsMember({"linear", "quadratic"}))
        ->capture_default_str();
  }
  BodyCaseArgs th_args{0, 0, "data/reference/turek_hron.json", 0, 0};
  auto* th2 = app.add_subcommand("turek_hron_cfd2", "Turek-Hron CFD2 (Re 100, steady, rigid flag), immersed boundary");
  auto* th3 = app.add_subcommand("turek_hron_cfd3", "Turek-Hron CFD3 (Re 200, periodic, rigid flag), immersed boundary");
  for (auto* sc : {th2, th3}) {
    add_body_case_options(sc, th_args, "s");
    add_channel_grid_options(sc, th_args, "grid: uniform box's length behind the flag's tip [diameters] (default 1)");
  }
  double th3_kick = -1;
  th3->add_option("--kick-velocity", th3_kick,
                  "start-up: transverse velocity [m/s] a brief push at t = 2 s gives the near wake to start the "
                  "shedding (default 2; 0: none, the instability grows from round-off)")
      ->check(CLI::Range(0.0, 10.0));
  BodyCaseArgs sphere_args{0, 0, "data/reference/sphere.json", 0, 0};
  auto* sphere = app.add_subcommand("sphere_re100", "sphere at Re 100 (3-D triangulated immersed boundary): drag");
  add_body_case_options(sphere, sphere_args, "D/U");
  sphere->add_flag("--wall-momentum-balance", sphere_args.wall_momentum_balance,
                   "pressure on the body: the wall momentum balance dp/dn = -nu n . curl(omega) instead of the "
                   "default dp/dn = 0, to compare (on bodies of about 28 cells per diameter or more; the default "
                   "D/20 keeps dp/dn = 0; at D/32 CD 1.0748 against 1.0919, control volume 1.0830 against 1.0878)");
  BodyCaseArgs dfg3_args{0, 0, "data/reference/schaefer_turek.json"};
  auto* dfg3 = app.add_subcommand("dfg_3d1z", "DFG 3D-1Z cylinder benchmark (Re 20, steady, 3-D), immersed boundary");
  add_body_case_options(dfg3, dfg3_args, "s");
  dfg3->add_flag("--wall-momentum-balance", dfg3_args.wall_momentum_balance,
                 "pressure on the body: the wall momentum balance dp/dn = -nu n . curl(omega) instead of the "
                 "default dp/dn = 0, to compare (on bodies of about 28 cells per diameter or more; the default "
                 "D/12 keeps dp/dn = 0)");
  int dfg3_span_cells = 0;
  dfg3->add_option("--span-cells", dfg3_span_cells, "cells along z (0: mid-span width about h; a multiple of 8)")
      ->check(CLI::Range(0, 4096));
  auto* fin_commands = fin_cfd::add_fin_commands(app);
  return cli::run(app, standard, argc, argv, [&]() -> int {
    if (int rc = 0; fin_cfd::run_fin_commands(*fin_commands, app, coarse, rc)) return rc;
    double wall = 0;
    if (*tg) return taylor_green(coarse, out_dir, wall);
    if (*couette) return ib_couette(coarse, out_dir, wall);
    if (*towed) return cylinder_towed(coarse, towed_staircase, out_dir, wall);
    if (*oscillating) return cylinder_oscillating(coarse, out_dir, wall);
    if (*sphere) return sphere_re100(coarse, sphere_args, out_dir, wall);
    if (*dfg3) return dfg_3d1z(coarse, dfg3_args, dfg3_span_cells, out_dir, wall);
    if (*d1) return dfg(1, coarse, dfg_args, out_dir, wall);
    if (*d2) return dfg(2, coarse, dfg_args, out_dir, wall);
    if (*d3) return dfg(3, coarse, dfg_args, out_dir, wall);
    if (*th2) return turek_hron(2, coarse, th_args, 0, out_dir, wall);
    if (*th3) return turek_hron(3, coarse, th_args, th3_kick, out_dir, wall);
    ch.coarse = coarse;
    return channel(ch, out_dir, wall);
  });
}
