// fin-cfd: the incompressible Navier-Stokes solver's validation cases (DESIGN.md sections 5.1, 6).
//
//   fin-cfd taylor_green [--coarse]     observed order of accuracy in space and in time
//   fin-cfd channel [--checkpoint-every N] [--restart FILE] [--vtk]
//                                       parabolic inlet, convective outlet, no-slip walls: the
//                                       developed profile and dp/dx = -8 nu Um / H^2
//
// Each writes <out-dir>/<case>/summary.json; exit 1 when a graded metric misses its tolerance.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cfd/checkpoint.hpp"
#include "cfd/flow_solver.hpp"
#include "cfd/taylor_green.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/summary.hpp"
#include "core/vtk_output.hpp"

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
  return cli::run(app, standard, argc, argv, [&]() -> int {
    double wall = 0;
    if (*tg) return taylor_green(coarse, out_dir, wall);
    ch.coarse = coarse;
    return channel(ch, out_dir, wall);
  });
}
