// The fin twin through tracking noise, graded over its seeds (see fin_twin_noise_grade.hpp).
#include "fit/validation/fin_twin_noise_grade.hpp"

#include <algorithm>
#include <cmath>

#include "fit/errors.hpp"
#include "fit/validation/fin_twin_grade.hpp"

namespace finverse::fit::validation {

namespace {

bool is_ray(const std::string& name) { return name.rfind("E_ray", 0) == 0 && name != "E_rays"; }

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

void check_fits(const std::vector<stage::Materials>& fits, const std::vector<std::string>& sources) {
  if (fits.empty()) throw InvalidInput("fin twin noise: no materials.h5 given");
  for (size_t k = 0; k < fits.size(); ++k) {
    const auto& m = fits[k];
    if (m.names != fits.front().names)
      throw InvalidInput(sources[k] + ": names other parameters than " + sources.front());
    if (m.ci95.data.size() != 2 * m.names.size() || m.identified.data.size() != m.names.size())
      throw InvalidInput(sources[k] + ": has no 95 % intervals (fit it with the polish)");
  }
}

}  // namespace

Summary grade_fin_twin_noise(const std::vector<stage::Materials>& fits, const std::vector<std::string>& sources,
                             const fem::io::MaterialSpec& truth, const std::string& case_name,
                             const FinTwinNoiseGoals& goals) {
  check_fits(fits, sources);
  Summary s("validation", case_name,
            "22-parameter fin twin fitted through fin-track's noise: 95 % interval coverage, rays identified and "
            "ray modulus errors over the noise seeds");
  const std::string src = "issue 45 goal 6";
  const auto& names = fits.front().names;
  const double seeds = static_cast<double>(fits.size());
  std::vector<double> ray_errors;
  int held = 0, covered = 0, all_covered = 0, rays = 0, rays_identified = 0;
  for (size_t i = 0; i < names.size(); ++i) {
    const double t = fin_twin_truth_value(names[i], truth);
    int in = 0, identified = 0;
    double abs_error = 0;
    for (const auto& m : fits) {
      const bool inside = m.ci95(i, 0) <= t && t <= m.ci95(i, 1);
      const bool ok = m.identified.data[i] != 0;
      const double e = std::abs(m.best.data[i] - t) / std::abs(t);
      in += inside, identified += ok, abs_error += e / seeds;
      all_covered += inside;
      if (ok) ++held, covered += inside;
      if (is_ray(names[i])) ray_errors.push_back(e), ++rays, rays_identified += ok;
    }
    s.info(names[i] + " mean relative error", abs_error);
    s.info(names[i] + " identified fraction", identified / seeds);
    s.info(names[i] + " interval coverage", in / seeds);
  }
  s.at_least("interval coverage, identified parameters", held ? static_cast<double>(covered) / held : 0.0,
             goals.coverage, src);
  s.info("interval coverage, all parameters", static_cast<double>(all_covered) / (names.size() * seeds));
  if (rays > 0) {
    s.at_least("rays identified", static_cast<double>(rays_identified) / rays, goals.rays_identified, src);
    s.at_most("median ray modulus error", median(ray_errors), goals.median_ray, src);
  }
  s.info("seeds", seeds);
  return s;
}

}  // namespace finverse::fit::validation
