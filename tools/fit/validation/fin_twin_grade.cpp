// Fin twin fit against its known modulus field (see fin_twin_grade.hpp).
#include "fit/validation/fin_twin_grade.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "fit/errors.hpp"

namespace finverse::fit::validation {

double fin_twin_truth_value(const std::string& name, const fem::io::MaterialSpec& truth) {
  if (name == "E_membrane") return truth.membrane.youngs_modulus;
  if (name == "E_rays") return truth.rays.youngs_modulus;
  if (name == "nu") return truth.membrane.poisson_ratio;
  if (name.rfind("E_ray", 0) == 0) {
    try {
      return truth.ray_material(std::stoi(name.substr(5))).youngs_modulus;
    } catch (const std::logic_error&) {
    }
  }
  throw InvalidInput("fin twin: the truth defines no parameter '" + name + "'");
}

Summary grade_fin_twin(const stage::Materials& m, const fem::io::MaterialSpec& truth, const std::string& case_name,
                       const FinTwinGoals& goals) {
  Summary s("validation", case_name,
            "22-parameter fin twin: eq. (2) fit of fin-fem's response with a known modulus field (sec. 4.3, Fig. 11)");
  const std::string src = "issue 31 goal";
  std::vector<double> ray_errors;
  int rays = 0, identified = 0;
  for (size_t i = 0; i < m.names.size(); ++i) {
    const std::string& name = m.names[i];
    const double t = fin_twin_truth_value(name, truth), v = m.best.data[i];
    const bool ok = m.identified.data.empty() || m.identified.data[i] != 0;
    if (name.rfind("E_ray", 0) == 0 && name != "E_rays") {
      ++rays;
      ray_errors.push_back(std::abs(v - t) / std::abs(t));
      if (ok) {
        ++identified;
        s.relative(name, v, t, goals.each_identified_ray, src, "Pa");
      } else {
        s.info(name + " (not identified) relative error", std::abs(v - t) / std::abs(t));
      }
    } else if (name == "E_membrane") {
      // Graded whether identified or not: the goal is on the membrane itself.
      s.relative(name, v, t, goals.membrane, src, "Pa");
      s.info("E_membrane identified (1 = yes)", ok ? 1.0 : 0.0);
    } else {
      s.info(name + " relative error", std::abs(v - t) / std::abs(t));
    }
  }
  if (!ray_errors.empty()) {
    std::vector<double> e = ray_errors;
    std::nth_element(e.begin(), e.begin() + static_cast<std::ptrdiff_t>(e.size() / 2), e.end());
    double median = e[e.size() / 2];
    if (e.size() % 2 == 0) {
      const double lower = *std::max_element(e.begin(), e.begin() + static_cast<std::ptrdiff_t>(e.size() / 2));
      median = 0.5 * (median + lower);
    }
    s.at_most("median ray modulus error", median, goals.median_ray, src);
    s.info("rays identified", identified);
    s.info("rays", rays);
  }
  if (!m.objective.data.empty()) s.info("objective", m.objective.data[0], "m");
  if (!m.evaluations.data.empty()) s.info("evaluations", static_cast<double>(m.evaluations.data[0]));
  return s;
}

}  // namespace finverse::fit::validation
