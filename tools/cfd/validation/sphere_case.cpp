// fin-cfd sphere_re100: steady flow past a sphere at Re 100 with the 3-D triangulated ghost-cell
// boundary (sphere_flow.hpp), drag against Johnson & Patel (1999).
#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "cfd/validation/case_support.hpp"
#include "cfd/validation/cases.hpp"
#include "cfd/validation/sphere_flow.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/summary.hpp"

namespace finverse::cfd::validation {

int run_sphere_re100(const CaseOptions& a) {
  const bool coarse = a.coarse;
  const std::filesystem::path& out = a.out_dir;
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
                                                           "  Poisson " + std::to_string(st.poisson_iterations) +
                                                           " it");
  };
  const SphereFlowResult r = run_sphere_flow(ss);
  progress.finish("CD " + fmt("%.4f", r.cd));
  const std::filesystem::path dir = out / "sphere_re100";
  std::filesystem::create_directories(dir);
  std::ostringstream csv;
  csv << "t,cd\n";
  for (std::size_t n = 0; n < r.time.size(); ++n) {
    csv << csv_row({r.time[n], r.cd_history[n]});
  }
  write_text_atomic(dir / "forces.csv", csv.str());
  log::info("sphere_re100 D/h=" + std::to_string(ss.cells_per_diameter) + " (" + std::to_string(r.cells[0]) + "x" +
            std::to_string(r.cells[1]) + "x" + std::to_string(r.cells[2]) + " cells): CD " + fmt("%.5f", r.cd) +
            " (pressure " + fmt("%.5f", r.cd_pressure) + ", viscous " + fmt("%.5f", r.cd_viscous) +
            "; control volume " + fmt("%.5f", r.cd_control_volume) + "), drift over 5 D/U " + fmt("%.2e", r.cd_drift) +
            ", " + std::to_string(r.steps) + " steps, " + fmt("%.1f s", r.cpu_seconds));
  Summary s("validation", "sphere_re100",
            "steady flow past a sphere at Re 100 (3-D ghost-cell immersed boundary on a closed triangulated surface): "
            "drag coefficient against Johnson & Patel (1999)");
  const std::string src = a.reference + " (Johnson & Patel 1999); issue 4 goal: within 2%";
  if (coarse)
    s.info("CD", r.cd);
  else
    s.relative("CD", r.cd, cd_ref, 0.02, src);
  s.info("CD_pressure", r.cd_pressure);
  s.info("CD_viscous", r.cd_viscous);
  s.info("CD_control_volume", r.cd_control_volume);
  s.info("CL_lateral", r.cl);
  s.info("CD_drift_last_5", r.cd_drift);
  solver_statistics_3d(s, r);
  s.parameters() = {{"coarse", coarse},
                    {"re", ss.re},
                    {"cells_per_diameter", ss.cells_per_diameter},
                    {"t_end", ss.t_end},
                    {"cfl", ss.cfl},
                    {"box_x", ss.box_x},
                    {"box_half_width", ss.box_half_width},
                    {"core_x", ss.core_x},
                    {"core_half_width", ss.core_half_width},
                    {"stretch_ratio", ss.stretch_ratio},
                    {"icosphere_subdivisions", ss.subdivisions},
                    {"triangles", r.triangles},
                    {"grid", r.cells},
                    {"reference", a.reference},
                    {"viscous_wall_pressure", ss.viscous_wall_pressure},
                    {"control_volume", ss.control_volume}};
  return finish(s, dir, seconds_since(t0));
}

}  // namespace finverse::cfd::validation
