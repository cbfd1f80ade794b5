// fin-cfd taylor_green: observed order of accuracy in space (uniform and stretched grids) and in
// time of the fractional-step solver on the decaying Taylor-Green vortex (taylor_green.hpp).
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "cfd/validation/case_support.hpp"
#include "cfd/validation/cases.hpp"
#include "cfd/validation/taylor_green.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/summary.hpp"

namespace finverse::cfd::validation {

int run_taylor_green(const CaseOptions& o) {
  const bool coarse = o.coarse;
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
      log::info("taylor_green " + tag + " n=" + std::to_string(n) + ": u L2 " + fmt("%.4e", r.back().u_l2) + ", p L2 " +
                fmt("%.4e", r.back().p_l2) + ", CPU " + fmt("%.2fs", r.back().cpu_seconds));
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
    const std::vector<double> dts =
        coarse ? std::vector<double>{0.1, 0.05, 0.025, 0.0125} : std::vector<double>{0.1, 0.05, 0.025, 0.0125, 0.00625};
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
      if (k + 2 == diff.size())
        s.absolute("order_time_velocity", order, 2.0, 0.1, src);
      else
        s.info("order_time_velocity_dt" + fmt("%g", dts[k + 1]), order);
    }
  }
  s.parameters() = {{"coarse", coarse},
                    {"grids", ns},
                    {"nu_space", 0.05},
                    {"nu_time", 0.2},
                    {"t_end", 1.0},
                    {"stretch", 0.3},
                    {"domain", "[0,2pi]^2 periodic"}};
  return finish(s, o.out_dir / "taylor_green", seconds_since(t0));
}

}  // namespace finverse::cfd::validation
