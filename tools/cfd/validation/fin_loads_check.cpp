// The fin run's nodal-load check and coefficient report; see fin_loads_check.hpp.
#include "cfd/validation/fin_loads_check.hpp"

#include <algorithm>
#include <cmath>

#include "cfd/io/loads_record.hpp"
#include "cfd/validation/case_support.hpp"
#include "cfd/validation/load_smoothness.hpp"
#include "core/log.hpp"

namespace finverse::cfd::validation {

Summary fin_loads_summary(const std::string& name, const std::string& inputs, const stage::Loads& back,
                          const io::FinFlowStats& st, double body_thickness, const nlohmann::json& parameters) {
  const auto err = io::nodal_sum_relative_error(back);
  const double worst = err.empty() ? 0.0 : *std::max_element(err.begin(), err.end());
  const std::size_t nt = back.time.size();
  double ct = 0, cy = 0, cz = 0, ct_max = -1e300, cy_amp = 0;
  for (std::size_t k = 0; k < nt; ++k) {
    ct += back.thrust(k) / nt;
    cy += back.lateral(k) / nt;
    cz += back.vertical(k) / nt;
    ct_max = std::max(ct_max, back.thrust(k));
    cy_amp = std::max(cy_amp, std::abs(back.lateral(k)));
  }
  Summary s("validation", name,
            "fin-cfd fin on " + inputs +
                ": the nodal loads of loads.h5 sum to the force integrated from the surface traction at every output "
                "time; force coefficients for information");
  s.at_most("max_relative_nodal_sum_error", worst, 0.005,
            "issue 4: nodal loads sum to the integrated force within 0.5%");
  // Issue 30's smoothness goals, over the last period (load_smoothness.hpp); a record too short
  // or not periodic reports none.
  if (const auto q = load_smoothness(back)) {
    const std::string src = "issue 30: over the last period of " + std::to_string(q->outputs) + " outputs, ";
    s.at_most("CT_energy_above_10th_harmonic", q->thrust_energy_fraction, 0.01, src + "at most 1% of C_T's energy");
    s.at_most("CL_energy_above_10th_harmonic", q->lateral_energy_fraction, 0.01, src + "at most 1% of C_L's energy");
    s.at_most("nodal_force_rms_above_10th_harmonic", q->nodal_rms_ratio, 0.05,
              src + "rms above the 10th harmonic at most 5% of the smooth part's");
    s.at_most("pressure_jump_rms_above_10th_harmonic", q->jump_rms_ratio, 0.05,
              src + "rms above the 10th harmonic at most 5% of the smooth part's");
    s.at_most("nodal_force_increment_ratio", q->nodal_increment_ratio, 1.5,
              src + "raw load increments between outputs within 1.5x of the smooth loads'");
    s.info("CT_increment_ratio", q->thrust_increment_ratio);
    log::info("loads smoothness over the last period (" + std::to_string(q->outputs) + " outputs): energy above the " +
              "10th harmonic C_T " + fmt("%.4f", q->thrust_energy_fraction) + ", C_L " +
              fmt("%.4f", q->lateral_energy_fraction) + "; rms ratio nodal " + fmt("%.4f", q->nodal_rms_ratio) +
              ", pressure jump " + fmt("%.4f", q->jump_rms_ratio) + "; increment ratio nodal " +
              fmt("%.3f", q->nodal_increment_ratio) + ", C_T " + fmt("%.3f", q->thrust_increment_ratio));
  }
  s.info("CT_mean", ct);
  s.info("CT_max", ct_max);
  s.info("CY_mean", cy);
  s.info("CY_max_abs", cy_amp);
  s.info("CZ_mean", cz);
  s.info("output_times", static_cast<double>(nt));
  s.info("steps", static_cast<double>(st.steps));
  s.info("cells", static_cast<double>(st.grid.cells()));
  s.info("body_thickness_over_h", body_thickness / st.h);
  s.info("max_cfl", st.max_cfl);
  s.info("mean_poisson_iterations", st.steps ? static_cast<double>(st.poisson_iterations) / st.steps : 0.0);
  s.info("solver_seconds", st.wall_seconds, "s");
  s.info("pressure_setup_seconds", st.pressure_setup_seconds, "s");
  s.info("pressure_solve_seconds", st.pressure_solve_seconds, "s");
  s.parameters() = parameters;
  log::info("nodal loads vs integrated force: max relative difference " + fmt("%.3e", worst) + " over " +
            std::to_string(nt) + " output times; C_T mean " + fmt("%.4f", ct) + ", C_Y mean " + fmt("%.4f", cy));
  return s;
}

}  // namespace finverse::cfd::validation
