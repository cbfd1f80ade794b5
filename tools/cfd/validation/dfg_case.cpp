// fin-cfd dfg_2d1 | dfg_2d2 | dfg_2d3: the DFG cylinder benchmarks (Schaefer & Turek 1996; 2D-3 against
// John 2004) with the ghost-cell immersed cylinder (dfg_benchmark.hpp): default grids, force
// history and grading against the published bounds.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "cfd/validation/case_support.hpp"
#include "cfd/validation/cases.hpp"
#include "cfd/validation/dfg_benchmark.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/summary.hpp"

namespace finverse::cfd::validation {

namespace {

int run_dfg_2d(int variant, const CaseOptions& a) {
  const bool coarse = a.coarse;
  const std::filesystem::path& out = a.out_dir;
  const auto t0 = std::chrono::steady_clock::now();
  const nlohmann::json ref = read_reference(a.reference);
  const std::string key = variant == 1 ? "2D-1" : variant == 2 ? "2D-2" : "2D-3";
  if (!ref.contains(key)) throw Error("--reference: " + a.reference + " has no '" + key + "' entry");
  const nlohmann::json& R = ref[key];
  const std::string name = variant == 1 ? "dfg_2d1" : variant == 2 ? "dfg_2d2" : "dfg_2d3";
  DfgSetup ds;
  ds.variant = variant;
  // 2D-1 at D/64 by default (why, and why dp stays 0.0001 under its bound: docs/studies/dfg_2d1.md).
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
  // 2D-2 and 2D-3 (the same Reynolds number at the sine's peak) by default: a D/48 core in a D/24
  // box, cells shrinking towards the channel walls (0.97: the Stokes layers the passing vortices
  // drive there); the grid and time-step studies: docs/studies/dfg_2d2_lift_maximum.md.
  const bool default_grid = variant >= 2 && !coarse && a.cells_per_diameter == 0 && a.core_cells_per_diameter == 0;
  ds.core_cells_per_diameter = default_grid ? 48 : a.core_cells_per_diameter;
  if (default_grid && a.wall_stretch_ratio == 0) ds.wall_stretch_ratio = 0.97;
  const int finest = std::max(ds.cells_per_diameter, ds.core_cells_per_diameter);
  const std::size_t expected =
      static_cast<std::size_t>(std::ceil(ds.t_end / (ds.cfl * 0.1 / finest / 1.8 / (variant == 1 ? 0.3 : 1.5))));
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
  for (const DfgSample& q : r.history) {
    csv << csv_row({q.t, q.cd, q.cl, q.dp, q.cd_pressure, q.cl_pressure, q.cd_cv, q.cl_cv});
  }
  write_text_atomic(dir / "forces.csv", csv.str());

  Summary s("validation", name,
            variant == 1 ? "DFG 2D-1 (Re 20, steady): drag, lift and pressure difference of the ghost-cell immersed "
                           "cylinder against the published bounds"
            : variant == 2
                ? "DFG 2D-2 (Re 100, periodic): maximum drag and lift and Strouhal number of the ghost-cell "
                  "immersed cylinder against the published bounds"
                : "DFG 2D-3 (Um = 1.5 sin(pi t/8), t in [0, 8]): maximum drag and lift, their times and the "
                  "pressure difference at t = 8 of the ghost-cell immersed cylinder against reference values");
  const std::string src = ref.value("source", std::string("Schaefer & Turek 1996"));
  // Goal: within 1% of the midpoint of each published bound interval (inside the bounds is better).
  const auto graded = [&](const std::string& metric, const std::string& field, double value) {
    const auto& bounds = R.at(field).at("bounds");
    const double lo = bounds[0].get<double>(), hi = bounds[1].get<double>();
    const double mid = 0.5 * (lo + hi);
    if (coarse)
      s.info(metric, value);
    else
      s.relative(metric, value, mid, 0.01, src + ", bounds [" + fmt("%g", lo) + ", " + fmt("%g", hi) + "]");
    s.info(metric + "_inside_bounds", value >= lo && value <= hi ? 1.0 : 0.0);
  };
  // 2D-3's reference values (John 2004, not bounds): the maxima within 1%, their times within one
  // percent of the 8 s run; dp at t = 8, a small difference of two pressures, as info.
  const auto against_value = [&](const std::string& metric, const std::string& field, double value, double tol,
                                 double scale) {
    const double ref_value = R.at(field).get<double>();
    if (coarse)
      s.info(metric, value);
    else if (scale > 0)
      s.absolute(metric, value, ref_value, tol * scale, src + " 2D-3 (John 2004)");
    else
      s.relative(metric, value, ref_value, tol, src + " 2D-3 (John 2004)");
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
  s.parameters() = {{"coarse", coarse},
                    {"cells_per_diameter", ds.cells_per_diameter},
                    {"t_end", ds.t_end},
                    {"window", ds.window},
                    {"cfl", ds.cfl},
                    {"ramp_time", ds.ramp_time},
                    {"polygon_vertices", ds.polygon_vertices},
                    {"box_x1", ds.box_x1},
                    {"core_cells_per_diameter", ds.core_cells_per_diameter},
                    {"core_wake", ds.core_wake},
                    {"stretch_ratio", ds.stretch_ratio},
                    {"wall_stretch_ratio", ds.wall_stretch_ratio},
                    {"cut_cell_continuity", ds.cut_cell_continuity},
                    {"viscous_wall_pressure", ds.viscous_wall_pressure},
                    {"wall_extrapolation", a.wall_extrapolation},
                    {"reference", a.reference}};
  log::info(name + ": " +
            (variant == 1 ? "CD " + fmt("%.5f", r.cd) + "  CL " + fmt("%.5f", r.cl) + "  dp " + fmt("%.5f", r.dp)
             : variant == 2
                 ? "CD_max " + fmt("%.5f", r.cd_max) + "  CL_max " + fmt("%.5f", r.cl_max) + "  St " + fmt("%.5f", r.st)
                 : "CD_max " + fmt("%.5f", r.cd_max) + " at " + fmt("%.4f", r.t_cd_max) + " s  CL_max " +
                       fmt("%.5f", r.cl_max) + " at " + fmt("%.4f", r.t_cl_max) + " s  dp(8) " + fmt("%.5f", r.dp)) +
            "  (" + std::to_string(r.steps) + " steps, " + fmt("%.1f s", r.cpu_seconds) + ")");
  return finish(s, dir, seconds_since(t0));
}

}  // namespace

int run_dfg_2d1(const CaseOptions& o) { return run_dfg_2d(1, o); }
int run_dfg_2d2(const CaseOptions& o) { return run_dfg_2d(2, o); }
int run_dfg_2d3(const CaseOptions& o) { return run_dfg_2d(3, o); }

}  // namespace finverse::cfd::validation
