// fin-cfd ib_couette: Couette flow between two immersed circles (ib_couette.hpp): the observed order
// of the ghost-cell boundary.
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "cfd/validation/case_support.hpp"
#include "cfd/validation/cases.hpp"
#include "cfd/validation/ib_couette.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/summary.hpp"

namespace finverse::cfd::validation {

int run_ib_couette(const CaseOptions& o) {
  const bool coarse = o.coarse;
  const auto t0 = std::chrono::steady_clock::now();
  Summary s("validation", "ib_couette",
            "circular Couette flow between two immersed concentric circles (inner turning, outer at rest) on a "
            "non-conforming Cartesian grid: observed L2 order of the velocity with the ghost-cell boundary");
  const std::vector<int> ns = coarse ? std::vector<int>{32, 64} : std::vector<int>{32, 64, 128};
  std::vector<IbCouetteResult> r;
  for (int n : ns) {
    IbCouetteSetup cs;
    cs.n = n;
    r.push_back(run_ib_couette(cs));
    log::info("ib_couette n=" + std::to_string(n) + ": u L2 " + fmt("%.4e", r.back().u_l2) + ", max " +
              fmt("%.4e", r.back().u_max) + ", " + std::to_string(r.back().steps) + " steps, Poisson " +
              fmt("%.1f", r.back().mean_poisson_iterations) + " it/step, momentum " +
              fmt("%.1f", r.back().mean_momentum_iterations) + " it/step, " + fmt("%.1fs", r.back().cpu_seconds));
    s.info("u_l2_n" + std::to_string(n), r.back().u_l2, "m/s");
    s.info("u_max_n" + std::to_string(n), r.back().u_max, "m/s");
    s.info("mean_poisson_iterations_n" + std::to_string(n), r.back().mean_poisson_iterations);
    s.info("mean_momentum_iterations_n" + std::to_string(n), r.back().mean_momentum_iterations);
  }
  const std::size_t m = r.size() - 1;
  const double order = std::log2(r[m - 1].u_l2 / r[m].u_l2);
  const std::string src = "exact circular Couette solution u_theta = A r + B / r; issue 4 goal: order >= 1.8";
  // Second order expected; the band [1.8, 2.2] is the floor and the same margin above.
  if (coarse)
    s.info("order_velocity_l2", order);
  else
    s.absolute("order_velocity_l2", order, 2.0, 0.2, src);
  s.info("order_velocity_max", std::log2(r[m - 1].u_max / r[m].u_max));
  const IbCouetteSetup d;
  s.parameters() = {{"coarse", coarse}, {"grids", ns},           {"r1", d.r1},
                    {"r2", d.r2},       {"omega", d.omega},      {"nu", d.nu},
                    {"t_end", d.t_end}, {"box", "[-0.6,0.6]^2"}, {"polygon_vertices", d.polygon_vertices}};
  return finish(s, o.out_dir / "ib_couette", seconds_since(t0));
}

}  // namespace finverse::cfd::validation
