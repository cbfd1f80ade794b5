// fin-cfd sheet_towed_plate: a plate towed through fluid at rest against the same plate fixed in a
// stream, the zero-thickness sheet and the closed two-cell body side by side (towed_plate.hpp;
// issue 44, goal 2; docs/studies/thin_surface.md).
//
//   fin-cfd sheet_towed_plate                       c/32, both treatments (about a minute)
//   fin-cfd sheet_towed_plate --cells-per-chord 64  the grid study's finer point
//   fin-cfd --coarse sheet_towed_plate              the CI variant (c/16, reported only)
#include <chrono>
#include <filesystem>
#include <sstream>

#include "cfd/validation/case_support.hpp"
#include "cfd/validation/cases.hpp"
#include "cfd/validation/towed_plate.hpp"
#include "core/atomic_file.hpp"
#include "core/log.hpp"
#include "core/summary.hpp"

namespace finverse::cfd::validation {

int run_sheet_towed_plate(const CaseOptions& o) {
  const auto t0 = std::chrono::steady_clock::now();
  TowedPlateSetup s = o.coarse ? TowedPlateSetup::coarse() : TowedPlateSetup{};
  if (o.cells_per_chord > 0) s.cells_per_chord = o.cells_per_chord;
  if (o.cfl > 0) s.cfl = o.cfl;
  if (!o.kernel.empty()) s.sheet.kernel = delta_kernel_from_name(o.kernel);
  if (o.marker_spacing > 0) s.sheet.spacing = o.marker_spacing;
  if (o.projections > 0) s.sheet.projections = o.projections;
  s.sheet.band_correction = !o.raw_sheet_force;
  log::info("sheet_towed_plate: c/" + std::to_string(s.cells_per_chord) + ", Re " + fmt("%g", s.re) + ", " +
            fmt("%g", s.incidence_deg) + " deg, kernel " + delta_kernel_name(s.sheet.kernel) + ", 4 runs");
  const TowedPlateResult r = run_towed_plate(s);
  const std::filesystem::path dir = o.out_dir / "sheet_towed_plate";
  std::filesystem::create_directories(dir);
  std::ostringstream csv;
  csv << "t,cd_fixed_sheet,cl_fixed_sheet,cd_towed_sheet,cl_towed_sheet,cd_fixed_closed,cl_fixed_closed,"
         "cd_towed_closed,cl_towed_closed\n";
  const auto at = [](const std::vector<double>& v, std::size_t n) { return n < v.size() ? v[n] : 0.0; };
  for (std::size_t n = 0; n < r.time.size(); ++n)
    csv << csv_row({r.time[n], r.sheet.cd_fixed[n], r.sheet.cl_fixed[n], r.sheet.cd_towed[n], r.sheet.cl_towed[n],
                    at(r.closed.cd_fixed, n), at(r.closed.cl_fixed, n), at(r.closed.cd_towed, n),
                    at(r.closed.cl_towed, n)});
  write_text_atomic(dir / "forces.csv", csv.str());
  for (const auto& [name, p] : {std::pair{"sheet", &r.sheet}, std::pair{"closed", &r.closed}})
    if (!p->cd_fixed.empty())
      log::info(std::string(name) + ": towed vs fixed max difference " + fmt("%.4f", p->max_difference) +
                " of the force; largest one-step departure towed " + fmt("%.4f", p->max_departure_towed) + ", fixed " +
                fmt("%.4f", p->max_departure_fixed) + "; fixed C_D " + fmt("%.4f", p->cd_fixed_end) + ", C_L " +
                fmt("%.4f", p->cl_fixed_end) + " (" + fmt("%.1f s", p->seconds) + ")");
  Summary sm("validation", "sheet_towed_plate",
             "flat plate at 10 degrees, Re 100, towed at constant speed through fluid at rest against the same "
             "plate fixed in a uniform stream, periodic box: force histories (C_D, C_L after every step, raw) of "
             "the zero-thickness sheet and of the closed two-cell body");
  const std::string src = "issue 44 goal 2: towed = fixed force history ";
  if (o.coarse) {
    sm.info("sheet_max_relative_difference", r.sheet.max_difference);
    sm.info("sheet_max_one_step_departure_towed", r.sheet.max_departure_towed);
  } else {
    sm.at_most("sheet_max_relative_difference", r.sheet.max_difference, 0.005, src + "within 0.5 %");
    sm.at_most("sheet_max_one_step_departure_towed", r.sheet.max_departure_towed, 0.005,
               src + "with no impulse: no step departs from its neighbours' mean by 0.5 % of the force");
  }
  sm.info("sheet_max_one_step_departure_fixed", r.sheet.max_departure_fixed);
  sm.info("sheet_CD_fixed_end", r.sheet.cd_fixed_end);
  sm.info("sheet_CL_fixed_end", r.sheet.cl_fixed_end);
  sm.info("sheet_seconds", r.sheet.seconds, "s");
  if (!r.closed.cd_fixed.empty()) {
    sm.info("closed_max_relative_difference", r.closed.max_difference);
    sm.info("closed_max_one_step_departure_towed", r.closed.max_departure_towed);
    sm.info("closed_max_one_step_departure_fixed", r.closed.max_departure_fixed);
    sm.info("closed_CD_fixed_end", r.closed.cd_fixed_end);
    sm.info("closed_CL_fixed_end", r.closed.cl_fixed_end);
    sm.info("closed_seconds", r.closed.seconds, "s");
  }
  sm.info("steps", static_cast<double>(r.steps));
  sm.info("cells", static_cast<double>(r.cells));
  sm.info("markers", static_cast<double>(r.markers));
  sm.parameters() = {{"coarse", o.coarse},
                     {"re", s.re},
                     {"incidence_deg", s.incidence_deg},
                     {"cells_per_chord", s.cells_per_chord},
                     {"cfl", s.cfl},
                     {"t_end", s.t_end},
                     {"t_compare", s.t_compare},
                     {"kernel", delta_kernel_name(s.sheet.kernel)},
                     {"marker_spacing", s.sheet.spacing},
                     {"projections", s.sheet.projections},
                     {"band_correction", s.sheet.band_correction}};
  return finish(sm, dir, seconds_since(t0));
}

}  // namespace finverse::cfd::validation
