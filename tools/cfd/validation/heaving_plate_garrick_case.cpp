// fin-cfd heaving_plate_garrick: the mean thrust of a thin plate heaving at small amplitude in a
// stream at Re 1000 against Garrick's linear theory (issue 30, item 3b): C_T = C_D(at rest) -
// <C_X(heaving)> per amplitude against 4 pi k^2 (h0/c)^2 |C(k)|^2 (garrick_theory.hpp); set-up
// in heaving_plate_garrick.hpp. Graded: within 10 % at the smallest amplitude, where the linear
// theory's assumptions (small heave-induced angle, attached flow, planar wake) hold best; the
// larger amplitudes show the trend (C_T / h0^2) and are reported.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "cfd/validation/case_support.hpp"
#include "cfd/validation/cases.hpp"
#include "cfd/validation/garrick_theory.hpp"
#include "cfd/validation/heaving_plate_garrick.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/summary.hpp"

namespace finverse::cfd::validation {

namespace {

std::vector<double> parse_amplitudes(const std::string& list) {
  std::vector<double> v;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::size_t used = 0;
    double a = 0;
    try {
      a = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || item.find_first_not_of(" \t", used) != std::string::npos || !(a > 0) || a > 1)
      throw Error("--amplitudes: '" + list + "' is not a comma-separated list of h0/c in (0, 1]");
    v.push_back(a);
  }
  if (v.empty()) throw Error("--amplitudes: empty");
  std::sort(v.begin(), v.end());
  return v;
}

// "0.025" -> "0.025" (the metric names' amplitude tag).
std::string tag(double a) { return fmt("%g", a); }

}  // namespace

int run_heaving_plate_garrick(const CaseOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  const nlohmann::json ref = read_reference(o.reference);
  if (!ref.contains("source") || !ref["source"].is_string())
    throw Error("--reference: " + o.reference + " has no 'source' string");
  const std::string source = ref["source"].get<std::string>();
  HeavingPlateSetup hs;
  if (o.coarse) {
    // The CI variant: 3 periods (2 averaged after the ramp), two amplitudes, on the default grid:
    // c/64 blows up at Re 1000 (the central convection at a cell Reynolds number of 16;
    // docs/studies/garrick_heaving_plate.md).
    hs.periods = 3;
    hs.periods_averaged = 2;
    hs.amplitudes = {0.025, 0.05};
  }
  if (o.reynolds > 0) hs.re = o.reynolds;
  if (o.reduced_frequency > 0) hs.reduced_frequency = o.reduced_frequency;
  if (!o.amplitudes.empty()) hs.amplitudes = parse_amplitudes(o.amplitudes);
  if (o.thickness > 0) hs.thickness = o.thickness;
  if (o.cells_per_chord > 0) hs.cells_per_chord = o.cells_per_chord;
  if (o.periods > 0) hs.periods = o.periods;
  if (o.periods_averaged > 0) hs.periods_averaged = o.periods_averaged;
  if (o.cfl > 0) hs.cfl = o.cfl;
  std::sort(hs.amplitudes.begin(), hs.amplitudes.end());

  const std::size_t runs = hs.amplitudes.size() + 1;
  const long steps_per_run =
      hs.periods * std::max(20L, static_cast<long>(std::ceil(hs.period() / (hs.cfl / hs.cells_per_chord))));
  log::Progress progress("heaving_plate_garrick step", runs * static_cast<std::size_t>(steps_per_run));
  std::size_t done = 0;
  hs.progress = [&](const std::string& run, const StepStats& st) {
    progress.update(++done, run + "  t " + fmt("%.3f", st.time) + "  Poisson " + std::to_string(st.poisson_iterations) +
                                " it");
  };
  const HeavingPlateResult r = run_heaving_plate(hs);
  progress.finish();

  const double k = hs.reduced_frequency, cd_rest = r.rest.mean_cx;
  Summary s("validation", "heaving_plate_garrick",
            "thin plate (t/c " + fmt("%g", hs.thickness) + ", rounded ends) heaving at k = " + fmt("%g", k) +
                ", Re " + fmt("%g", hs.re) + ": mean thrust C_D(at rest) - <C_X> against Garrick's linear theory "
                "4 pi k^2 (h0/c)^2 |C(k)|^2 per amplitude (graded at the smallest)");
  const std::filesystem::path dir = o.out_dir / "heaving_plate_garrick";
  std::filesystem::create_directories(dir);
  const std::complex<double> ck = theodorsen(k);
  s.info("theodorsen_F", ck.real());
  s.info("theodorsen_G", ck.imag());
  s.info("CD_at_rest", cd_rest);
  s.info("CD_at_rest_pressure", r.rest.mean_cx_pressure);
  s.info("CD_at_rest_viscous", r.rest.mean_cx_viscous);
  s.info("CD_at_rest_period_spread", r.rest.cx_period_spread);
  double max_cfl = r.rest.max_cfl;
  for (const HeavingPlateRun& q : r.heaving) {
    const std::string a = tag(q.amplitude);
    if (q.failed) {
      // Reported, and graded as a miss where this amplitude is the graded one.
      log::warn("heaving_plate_garrick h0/c " + a + ": the solver stopped: " + q.error);
      if (q.amplitude == hs.amplitudes.front() && !o.coarse)
        s.at_most("solver_stopped_h0_" + a, 1, 0, "issue 30 item 3b: the graded amplitude must run to the end");
      else
        s.info("solver_stopped_h0_" + a, 1);
      s.info("stopped_at_step_h0_" + a, static_cast<double>(q.cx.size() + 1));
      s.info("max_cfl_h0_" + a, q.max_cfl);
      continue;
    }
    const double ct = cd_rest - q.mean_cx, ct_theory = garrick_heave_thrust_coefficient(k, q.amplitude);
    const double cp_theory = garrick_heave_power_coefficient(k, q.amplitude);
    max_cfl = std::max(max_cfl, q.max_cfl);
    // The smallest amplitude is graded (issue 30 item 3b: within 10 %), unless on the coarse grid.
    if (q.amplitude == hs.amplitudes.front() && !o.coarse)
      s.relative("CT_h0_" + a, ct, ct_theory, 0.10,
                 "issue 30 item 3b: Garrick within 10 % at the smallest amplitude; " + source);
    else
      s.info("CT_h0_" + a, ct);
    s.info("CT_garrick_h0_" + a, ct_theory);
    s.info("CT_over_garrick_h0_" + a, ct / ct_theory);
    // The trend: C_T / (h0/c)^2, constant in the linear theory.
    s.info("CT_over_h0_squared_h0_" + a, ct / (q.amplitude * q.amplitude));
    // The thrust's split: the suction is a pressure force, the friction change a viscous one.
    s.info("CT_pressure_h0_" + a, r.rest.mean_cx_pressure - q.mean_cx_pressure);
    s.info("CT_viscous_h0_" + a, r.rest.mean_cx_viscous - q.mean_cx_viscous);
    s.info("CX_mean_h0_" + a, q.mean_cx);
    s.info("CX_period_spread_h0_" + a, q.cx_period_spread);
    s.info("CP_h0_" + a, q.mean_cp);
    s.info("CP_garrick_h0_" + a, cp_theory);
    s.info("CP_over_garrick_h0_" + a, q.mean_cp / cp_theory);
    s.info("heave_angle_max_h0_" + a, 2 * k * q.amplitude, "rad");  // omega h0 / U
    s.info("solver_seconds_h0_" + a, q.cpu_seconds, "s");
    log::info("heaving_plate_garrick h0/c " + a + ": C_T " + fmt("%.5f", ct) + " (C_D at rest " + fmt("%.5f", cd_rest) +
              " - <C_X> " + fmt("%.5f", q.mean_cx) + "), Garrick " + fmt("%.5f", ct_theory) + ", ratio " +
              fmt("%.3f", ct / ct_theory) + "; C_P " + fmt("%.5f", q.mean_cp) + ", Garrick " + fmt("%.5f", cp_theory) +
              " (" + fmt("%.1f s", q.cpu_seconds) + ")");
  }
  s.info("max_cfl", max_cfl);
  s.info("cells", static_cast<double>(r.cells));
  s.info("steps_per_run", static_cast<double>(r.steps));
  s.info("solver_seconds_at_rest", r.rest.cpu_seconds, "s");

  std::ostringstream csv;
  csv << "t,cx_rest,cy_rest";
  for (const HeavingPlateRun& q : r.heaving) csv << ",cx_h0_" << tag(q.amplitude) << ",cy_h0_" << tag(q.amplitude);
  csv << '\n';
  for (std::size_t n = 0; n < r.time.size(); ++n) {
    std::vector<double> row = {r.time[n], r.rest.cx[n], r.rest.cy[n]};
    for (const HeavingPlateRun& q : r.heaving) {
      row.push_back(n < q.cx.size() ? q.cx[n] : std::nan(""));
      row.push_back(n < q.cy.size() ? q.cy[n] : std::nan(""));
    }
    std::string line;
    for (std::size_t i = 0; i < row.size(); ++i) line += fmt(i ? ",%.9g" : "%.9g", row[i]);
    csv << line << '\n';
  }
  write_text_atomic(dir / "forces.csv", csv.str());
  s.parameters() = {{"coarse", o.coarse},
                    {"re", hs.re},
                    {"reduced_frequency", k},
                    {"amplitudes", hs.amplitudes},
                    {"thickness", hs.thickness},
                    {"cells_per_chord", hs.cells_per_chord},
                    {"periods", hs.periods},
                    {"periods_averaged", hs.periods_averaged},
                    {"cfl", hs.cfl},
                    {"dt", r.dt},
                    {"steps_per_period", r.steps_per_period},
                    {"box_behind", hs.box_behind},
                    {"box_margin", hs.box_margin},
                    {"upstream", hs.upstream},
                    {"downstream", hs.downstream},
                    {"half_height", hs.half_height},
                    {"stretch_ratio", hs.stretch_ratio},
                    {"end_vertices", hs.end_vertices},
                    {"reference", o.reference}};
  return finish(s, dir, seconds_since(t0));
}

}  // namespace finverse::cfd::validation
