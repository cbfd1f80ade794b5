// fin-cfd cylinder_towed | cylinder_oscillating: the moving ghost-cell boundary on a towed cylinder
// (against the fixed one in a stream) and on an in-line oscillating cylinder (force spikes from
// cleared cells); set-ups in moving_cylinder.hpp.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "cfd/validation/case_support.hpp"
#include "cfd/validation/cases.hpp"
#include "cfd/validation/moving_cylinder.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/summary.hpp"

namespace finverse::cfd::validation {

int run_cylinder_towed(const CaseOptions& o) {
  const bool coarse = o.coarse, staircase_balance = o.staircase_balance;
  const std::filesystem::path& out = o.out_dir;
  const auto t0 = std::chrono::steady_clock::now();
  TowedCylinderSetup ts = coarse ? TowedCylinderSetup::coarse() : TowedCylinderSetup{};
  ts.cut_cell_continuity = !staircase_balance;
  log::Progress progress("cylinder_towed step",
                         static_cast<std::size_t>(std::ceil(ts.t_end / (ts.cfl / ts.cells_per_diameter))));
  ts.progress = [&](const StepStats& st) {
    progress.update(static_cast<std::size_t>(st.step),
                    "t " + fmt("%.3f", st.time) + "  Poisson " + std::to_string(st.poisson_iterations) + " it");
  };
  const TowedCylinderResult r = run_towed_cylinder(ts);
  progress.finish("t " + fmt("%.3f", r.time.back()));
  const std::filesystem::path dir = out / "cylinder_towed";
  std::filesystem::create_directories(dir);
  std::ostringstream csv;
  csv << "t,cd_towed,cd_fixed,cd_fixed_vertex\n";
  for (std::size_t n = 0; n < r.time.size(); ++n) {
    csv << csv_row({r.time[n], r.cd_towed[n], r.cd_fixed[n], r.cd_fixed_vertex[n]});
  }
  write_text_atomic(dir / "forces.csv", csv.str());
  log::info("cylinder_towed: CD towed " + fmt("%.5f", r.cd_towed_end) + ", fixed " + fmt("%.5f", r.cd_fixed_end) +
            " (mean of " + std::to_string(ts.fixed_offsets) + " sub-cell positions; vertex-centred " +
            fmt("%.5f", r.cd_fixed_vertex_end) + ")" + " (averaged over " + std::to_string(ts.filter_cells) +
            " cell crossings), max relative difference over t >= " + fmt("%g", ts.t_compare) + ": " +
            fmt("%.3e", r.max_relative_difference) + " averaged, " + fmt("%.3e", r.max_relative_difference_raw) +
            " raw (" + fmt("%.1f s", r.cpu_seconds) + ")");
  Summary s("validation", "cylinder_towed",
            "cylinder towed at constant speed through fluid at rest against the fixed cylinder in a uniform stream "
            "(same Re, grid spacing and solver; the fixed drag averaged over the cylinder's sub-cell positions, as the "
            "towed one is): Galilean invariance of the moving ghost-cell boundary");
  // Issue 4 goal: the same drag within 1% after start-up (the coarse grid only reports).
  if (coarse)
    s.info("max_relative_drag_difference", r.max_relative_difference);
  else
    s.at_most("max_relative_drag_difference", r.max_relative_difference, 0.01, "issue 4: towed = fixed drag within 1%");
  s.info("max_relative_drag_difference_raw", r.max_relative_difference_raw);
  s.info("max_relative_drag_difference_vertex_centred_fixed", r.max_relative_difference_vertex);
  s.info("CD_towed_end", r.cd_towed_end);
  s.info("CD_fixed_end", r.cd_fixed_end);
  s.info("CD_fixed_vertex_centred_end", r.cd_fixed_vertex_end);
  s.info("fixed_position_spread_end", r.fixed_position_spread);
  s.info("steps", static_cast<double>(r.steps));
  s.info("cells_all_runs", static_cast<double>(r.cells));  // towed + fixed_offsets fixed runs
  s.info("solver_seconds", r.cpu_seconds, "s");
  s.parameters() = {{"coarse", coarse},
                    {"re", ts.re},
                    {"cells_per_diameter", ts.cells_per_diameter},
                    {"t_end", ts.t_end},
                    {"t_compare", ts.t_compare},
                    {"half_height", ts.half_height},
                    {"filter_cells", ts.filter_cells},
                    {"cfl", ts.cfl},
                    {"coupling_fraction", ts.coupling_fraction},
                    {"cut_cell_continuity", ts.cut_cell_continuity},
                    {"polygon_vertices", ts.polygon_vertices},
                    {"fixed_offsets", ts.fixed_offsets}};
  return finish(s, dir, seconds_since(t0));
}

int run_cylinder_oscillating(const CaseOptions& o) {
  const bool coarse = o.coarse;
  const std::filesystem::path& out = o.out_dir;
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
  const Variant variants[] = {
      {"with_treatment", true, true}, {"staircase_balance", false, true}, {"without_treatment", false, false}};
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
  s.info("high_frequency_reduction_factor",
         r[2].high_frequency_fraction / std::max(r[0].high_frequency_fraction, 1e-300));
  s.info("high_frequency_reduction_factor_cut_cells",
         r[1].high_frequency_fraction / std::max(r[0].high_frequency_fraction, 1e-300));
  std::ostringstream csv;
  csv << "t,fx_with_treatment,fx_staircase_balance,fx_without_treatment\n";
  for (std::size_t n = 0; n < r[0].time.size(); ++n) {
    csv << csv_row({r[0].time[n], r[0].fx[n], r[1].fx[n], r[2].fx[n]});
  }
  write_text_atomic(dir / "forces.csv", csv.str());
  s.parameters() = {{"coarse", coarse},
                    {"kc", os.kc},
                    {"re", os.re},
                    {"cells_per_diameter", os.cells_per_diameter},
                    {"steps_per_period", os.steps_per_period},
                    {"periods", os.periods},
                    {"periods_analysed", os.periods_analysed},
                    {"half_width", os.half_width},
                    {"polygon_vertices", os.polygon_vertices}};
  return finish(s, dir, seconds_since(t0));
}

}  // namespace finverse::cfd::validation
