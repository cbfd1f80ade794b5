// fin-cfd pipe_poiseuille: Poiseuille flow in a round pipe whose fluid is inside the immersed wall
// (pipe_poiseuille.hpp), graded as issue 49 asks: the centreline speed and the wall shear within
// 2 % of the analytic profile, the pressure drop per length within 3 %.
//   fin-cfd pipe_poiseuille                          (D/22, h about 1 mm, Re 1283)
//   fin-cfd pipe_poiseuille --cells-per-diameter 32  (a finer grid)
#include <chrono>
#include <cmath>
#include <filesystem>
#include <string>

#include "cfd/validation/case_support.hpp"
#include "cfd/validation/cases.hpp"
#include "cfd/validation/pipe_poiseuille.hpp"
#include "core/log.hpp"
#include "core/summary.hpp"

namespace finverse::cfd::validation {

int run_pipe_poiseuille(const CaseOptions& a) {
  const auto t0 = std::chrono::steady_clock::now();
  PipePoiseuilleSetup ps;
  if (a.coarse) {
    ps.cells_per_diameter = 11;
    ps.length_diameters = 4;
    ps.t_end = 0.12;
  }
  if (a.cells_per_diameter > 0) ps.cells_per_diameter = a.cells_per_diameter;
  if (a.t_end > 0) ps.t_end = a.t_end;
  if (a.reynolds > 0) ps.reynolds = a.reynolds;
  const double U = ps.reynolds * ps.mu / (ps.rho * ps.diameter), h = ps.diameter / ps.cells_per_diameter;
  const double t_guess = ps.t_end > 0 ? ps.t_end : 3 * ps.length_diameters * ps.diameter / (0.5 * U);
  log::Progress progress("pipe_poiseuille step", static_cast<std::size_t>(std::ceil(t_guess / (ps.cfl * h / U))));
  ps.progress = [&](const StepStats& st) {
    progress.update(static_cast<std::size_t>(st.step), "t " + fmt("%.4f", st.time) + " s  Poisson " +
                                                           std::to_string(st.poisson_iterations) + " it");
  };
  const PipePoiseuilleResult r = run_pipe_poiseuille(ps);
  progress.finish("centreline " + fmt("%.5f", r.centreline_speed) + " m/s");
  const std::filesystem::path dir = a.out_dir / "pipe_poiseuille";
  std::filesystem::create_directories(dir);
  log::info("pipe_poiseuille D/" + std::to_string(ps.cells_per_diameter) + " (" + std::to_string(r.cells[0]) + "x" +
            std::to_string(r.cells[1]) + "x" + std::to_string(r.cells[2]) + " cells): centreline " +
            fmt("%.5f", r.centreline_speed) + " m/s (exact " + fmt("%.5f", r.centreline_reference) + "), wall shear " +
            fmt("%.5f", r.wall_shear) + " Pa (" + fmt("%.5f", r.wall_shear_reference) + "), dp/dz " +
            fmt("%.3f", r.pressure_gradient) + " Pa/m (" + fmt("%.3f", r.pressure_gradient_reference) +
            "), profile RMS " + fmt("%.2e", r.profile_rms) + ", " + std::to_string(r.steps) + " steps, " +
            fmt("%.1f s", r.cpu_seconds));
  Summary s("validation", "pipe_poiseuille",
            "Poiseuille flow in a round pipe whose fluid is inside the immersed wall (fluid: inside, the inlet's "
            "parabola on the pipe's cross-section), the Hessenthaler flap's inlet pipe at Re 1283");
  const std::string src = "analytic Poiseuille flow; issue 49 goal: within ";
  const auto grade = [&](const std::string& name, double value, double reference, double tol, const char* units) {
    if (a.coarse)
      s.info(name, value, units);
    else
      s.relative(name, value, reference, tol, src + (tol < 0.025 ? "2 %" : "3 %"), units);
  };
  grade("centreline_speed", r.centreline_speed, r.centreline_reference, 0.02, "m/s");
  grade("wall_shear", r.wall_shear, r.wall_shear_reference, 0.02, "Pa");
  grade("pressure_gradient", r.pressure_gradient, r.pressure_gradient_reference, 0.03, "Pa/m");
  s.info("profile_rms_over_U", r.profile_rms);
  s.info("inflow_rate_error", r.inflow_rate_error);
  s.info("wall_drag_drift_last_fifth", r.wall_drag_drift);
  s.info("steps", static_cast<double>(r.steps));
  s.info("cells", static_cast<double>(r.cells[0]) * r.cells[1] * r.cells[2]);
  s.info("ghost_cells", static_cast<double>(r.ghost_cells));
  s.info("wall_samples", static_cast<double>(r.wall_samples));
  s.info("mean_poisson_iterations", r.mean_poisson_iterations);
  s.info("max_divergence_end", r.max_divergence, "1/s");
  s.info("solver_seconds", r.cpu_seconds, "s");
  s.parameters() = {{"coarse", a.coarse},
                    {"diameter_m", ps.diameter},
                    {"rho", ps.rho},
                    {"mu", ps.mu},
                    {"reynolds", ps.reynolds},
                    {"centreline_speed_m_s", U},
                    {"cells_per_diameter", ps.cells_per_diameter},
                    {"h_m", r.h},
                    {"length_diameters", ps.length_diameters},
                    {"t_end_s", r.t_end},
                    {"cfl", ps.cfl},
                    {"grid", r.cells},
                    {"measured_over", "z in [1.5 D, L - 1.5 D]"}};
  return finish(s, dir, seconds_since(t0));
}

}  // namespace finverse::cfd::validation
