// fin-cfd turek_hron_cfd2 | turek_hron_cfd3: the Turek & Hron (2006) benchmarks with the flag held
// rigid (turek_hron_cfd.hpp): default grids, force history and grading against the reference.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "cfd/validation/case_support.hpp"
#include "cfd/validation/cases.hpp"
#include "cfd/validation/turek_hron_cfd.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/summary.hpp"

namespace finverse::cfd::validation {

namespace {

int run_turek_hron(int variant, const CaseOptions& a) {
  const bool coarse = a.coarse;
  const std::filesystem::path& out = a.out_dir;
  const auto t0 = std::chrono::steady_clock::now();
  const nlohmann::json ref = read_reference(a.reference);
  const std::string key = variant == 2 ? "CFD2" : "CFD3";
  if (!ref.contains("cases") || !ref["cases"].contains(key))
    throw Error("--reference: " + a.reference + " has no 'cases." + key + "' entry");
  const nlohmann::json& R = ref["cases"][key];
  const std::string name = variant == 2 ? "turek_hron_cfd2" : "turek_hron_cfd3";
  TurekHronSetup ts;
  ts.variant = variant;
  // Default grids: CFD2 a D/24 box + D/48 core, CFD3 a D/32 box reaching 2 D behind the tip + a D/64
  // core; what each choice changes: docs/studies/turek_hron_cfd3_grid.md.
  const bool default_grid = !coarse && a.cells_per_diameter == 0 && a.core_cells_per_diameter == 0;
  ts.cells_per_diameter = a.cells_per_diameter > 0 ? a.cells_per_diameter : coarse ? 12 : variant == 2 ? 24 : 32;
  ts.core_cells_per_diameter = default_grid ? (variant == 2 ? 48 : 64) : a.core_cells_per_diameter;
  if (default_grid && variant == 3) ts.wake_box = 2;
  // CFD3's shedding drives Stokes layers on the channel walls (~D/12 thick) that cells growing
  // from the box do not resolve; from a D/32 box 0.98 is the steepest shrinking that fits.
  if (default_grid && variant == 3 && a.wall_stretch_ratio == 0) ts.wall_stretch_ratio = 0.98;
  // CFD3 from rest saturates only after t ~ 12 s; the push on the wake at the end of the ramp
  // starts the shedding at once (saturated from t ~ 5 s; same study).
  if (variant == 3) ts.kick_velocity = a.kick_velocity >= 0 ? a.kick_velocity : 2.0;
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
    progress.update(static_cast<std::size_t>(st.step), "t " + fmt("%.4f s", st.time) + "  dt " + fmt("%.3g", st.dt) +
                                                           "  CFL " + fmt("%.3f", st.cfl) + "  Poisson " +
                                                           std::to_string(st.poisson_iterations) + " it  div " +
                                                           fmt("%.1e", st.max_divergence));
  };
  const TurekHronResult r = run_turek_hron(ts);
  progress.finish("t " + fmt("%.4f s", r.history.back().t));

  const std::filesystem::path dir = out / name;
  std::filesystem::create_directories(dir);
  std::ostringstream csv;
  csv << "t,drag,lift,drag_viscous,lift_viscous,drag_flag,lift_flag,drag_cv,lift_cv\n";
  for (const TurekHronSample& q : r.history) {
    csv << csv_row(
        {q.t, q.drag, q.lift, q.drag_viscous, q.lift_viscous, q.drag_flag, q.lift_flag, q.drag_cv, q.lift_cv});
  }
  write_text_atomic(dir / "forces.csv", csv.str());

  Summary s("validation", name,
            variant == 2
                ? "Turek-Hron CFD2 (Re 100, steady, rigid flag): drag and lift [N/m] on cylinder + flag of the "
                  "ghost-cell immersed body"
                : "Turek-Hron CFD3 (Re 200, periodic, rigid flag): drag and lift [N/m] mean and amplitude and "
                  "the lift frequency of the ghost-cell immersed body");
  const std::string src = ref.value("source", std::string("Turek & Hron 2006"));
  const auto graded = [&](const std::string& metric, double value, double reference, double tol, const std::string& u) {
    if (coarse)
      s.info(metric, value, u);
    else
      s.relative(metric, value, reference, tol, src, u);
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
    if (coarse)
      s.info("lift_mean", r.lift_mean, "N/m");
    else
      s.absolute("lift_mean", r.lift_mean, lm, 0.05 * la, src + "; tolerance 5 % of the lift amplitude", "N/m");
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
  s.parameters() = {{"coarse", coarse},
                    {"cells_per_diameter", ts.cells_per_diameter},
                    {"t_end", ts.t_end},
                    {"window", ts.window},
                    {"cfl", ts.cfl},
                    {"ramp_time", ts.ramp_time},
                    {"circle_vertices", ts.circle_vertices},
                    {"wake_box", ts.wake_box},
                    {"stretch_ratio", ts.stretch_ratio},
                    {"wall_stretch_ratio", ts.wall_stretch_ratio},
                    {"cut_cell_continuity", ts.cut_cell_continuity},
                    {"viscous_wall_pressure", ts.viscous_wall_pressure},
                    {"core_cells_per_diameter", ts.core_cells_per_diameter},
                    {"core_wake", ts.core_wake},
                    {"kick_velocity", ts.kick_velocity},
                    {"kick_start", ts.kick_start},
                    {"kick_duration", ts.kick_duration},
                    {"reference", a.reference}};
  log::info(name + ": " +
            (variant == 2 ? "drag " + fmt("%.4f", r.drag) + "  lift " + fmt("%.4f", r.lift)
                          : "drag " + fmt("%.3f", r.drag_mean) + " +- " + fmt("%.3f", r.drag_amplitude) + "  lift " +
                                fmt("%.3f", r.lift_mean) + " +- " + fmt("%.3f", r.lift_amplitude) + "  f " +
                                fmt("%.4f", r.frequency)) +
            "  (" + std::to_string(r.steps) + " steps, " + fmt("%.1f s", r.cpu_seconds) + ")");
  return finish(s, dir, seconds_since(t0));
}

}  // namespace

int run_turek_hron_cfd2(const CaseOptions& o) { return run_turek_hron(2, o); }
int run_turek_hron_cfd3(const CaseOptions& o) { return run_turek_hron(3, o); }

}  // namespace finverse::cfd::validation
