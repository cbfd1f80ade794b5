// fin-cfd dfg_3d1z: DFG 3D-1Z (Schaefer & Turek 1996), a wall-to-wall cylinder in a square channel
// with the 3-D triangulated ghost-cell body crossing the domain boundary (dfg_3d1z.hpp).
#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "cfd/validation/case_support.hpp"
#include "cfd/validation/cases.hpp"
#include "cfd/validation/dfg_3d1z.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/summary.hpp"

namespace finverse::cfd::validation {

int run_dfg_3d1z(const CaseOptions& a) {
  const bool coarse = a.coarse;
  const int span_cells = a.span_cells;
  const std::filesystem::path& out = a.out_dir;
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
  for (const Dfg3dSample& q : r.history) {
    csv << csv_row({q.t, q.cd, q.cl, q.dp});
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
  if (coarse)
    s.info("cD", r.cd);
  else
    s.relative("cD", r.cd, cd_ref, 0.02, src + " 3D-1Z; issue 4 goal: within 2%");
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
  s.parameters() = {{"coarse", coarse},
                    {"cells_per_diameter", ds.cells_per_diameter},
                    {"h", r.h},
                    {"grid", r.cells},
                    {"span_cells", r.cells[2]},
                    {"segments", ds.segments},
                    {"triangles", r.triangles},
                    {"overhang", ds.overhang},
                    {"stretch_ratio", ds.stretch_ratio},
                    {"cfl", ds.cfl},
                    {"t_end", ds.t_end},
                    {"t_min", ds.t_min},
                    {"steady_window", ds.steady_window},
                    {"steady_tolerance", ds.steady_tolerance},
                    {"reference", a.reference},
                    {"viscous_wall_pressure", ds.viscous_wall_pressure}};
  return finish(s, dir, seconds_since(t0));
}

}  // namespace finverse::cfd::validation
