// Fitted moduli against the truth (see modulus_scores.hpp; Fig. 11).
#include "report/modulus_scores.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace finverse::report {

namespace {
bool is_ray(const std::string& n) { return n.rfind("E_ray", 0) == 0 && n != "E_rays"; }
const std::string kSource = "issue 33 scores";
}  // namespace

std::map<std::string, double> truth_parameters(const fem::io::MaterialSpec& spec, const std::vector<std::string>& names) {
  std::map<std::string, double> out;
  for (const auto& n : names) {
    if (n == "E_membrane") out[n] = spec.membrane.youngs_modulus;
    else if (n == "E_rays") out[n] = spec.rays.youngs_modulus;
    else if (n == "nu") out[n] = spec.membrane.poisson_ratio;
    else if (is_ray(n)) {
      try {
        out[n] = spec.ray_material(std::stoi(n.substr(5))).youngs_modulus;
      } catch (const std::logic_error&) {  // not a number after E_ray: no truth for it
      }
    }
  }
  return out;
}

std::map<std::string, double> truth_parameters(const stage::Truth& truth) {
  std::map<std::string, double> out;
  for (std::size_t i = 0; i < truth.material_names.size() && i < truth.material_values.size(); ++i)
    out[truth.material_names[i]] = truth.material_values(i);
  return out;
}

std::vector<ModulusRow> modulus_rows(const stage::Materials& m, const std::map<std::string, double>& truth) {
  std::vector<ModulusRow> rows;
  const bool has_ci = m.ci95.size() == 2 * m.names.size();
  for (std::size_t i = 0; i < m.names.size() && i < m.best.size(); ++i) {
    ModulusRow r;
    r.name = m.names[i];
    r.fitted = m.best(i);
    r.lower = has_ci ? m.ci95(i, 0) : r.fitted;
    r.upper = has_ci ? m.ci95(i, 1) : r.fitted;
    r.identified = m.identified.data.empty() || m.identified(i) != 0;
    if (auto it = truth.find(r.name); it != truth.end()) r.truth = it->second;
    rows.push_back(r);
  }
  return rows;
}

std::vector<Score> modulus_scores(const std::vector<ModulusRow>& rows, const std::string& truth_note) {
  std::vector<double> ray_errors, identified_errors;
  std::optional<double> membrane;
  for (const auto& r : rows) {
    if (!r.truth) continue;
    const double e = relative_difference(r.fitted, *r.truth);
    if (is_ray(r.name)) {
      ray_errors.push_back(e);
      if (r.identified) identified_errors.push_back(e);
    } else if (r.name == "E_membrane") {
      membrane = e;
    }
  }
  std::vector<Score> out;
  const std::string median_name = "fitted ray E vs truth, median relative error";
  const std::string worst_name = "fitted ray E vs truth, worst identified ray";
  const std::string membrane_name = "membrane E vs truth, relative error";
  if (ray_errors.empty()) {
    out.push_back(unavailable(median_name, 0.05, kSource, "no ray modulus with a truth value"));
    out.push_back(unavailable(worst_name, 0.15, kSource, "no ray modulus with a truth value"));
  } else {
    std::sort(ray_errors.begin(), ray_errors.end());
    const std::size_t n = ray_errors.size();
    const double median = n % 2 ? ray_errors[n / 2] : 0.5 * (ray_errors[n / 2 - 1] + ray_errors[n / 2]);
    out.push_back(graded(median_name, median, 0.05, kSource,
                         std::to_string(n) + " rays; " + truth_note));
    if (identified_errors.empty())
      out.push_back(unavailable(worst_name, 0.15, kSource,
                                "the fit identified none of the " + std::to_string(n) + " rays (materials.h5 "
                                "uncertainty/identified)"));
    else
      out.push_back(graded(worst_name, *std::max_element(identified_errors.begin(), identified_errors.end()), 0.15,
                           kSource, std::to_string(identified_errors.size()) + " of " + std::to_string(n) +
                                        " rays identified; " + truth_note));
  }
  if (membrane)
    out.push_back(graded(membrane_name, *membrane, 0.10, kSource, truth_note));
  else
    out.push_back(unavailable(membrane_name, 0.10, kSource, "no membrane modulus with a truth value"));
  return out;
}

}  // namespace finverse::report
