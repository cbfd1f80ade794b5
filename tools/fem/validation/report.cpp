// Validation metrics (see report.hpp).
#include "fem/validation/report.hpp"

#include <cmath>
#include <limits>

namespace finverse::fem::validation {

double Metric::error() const {
  if (kind == "relative") return std::abs(value - *reference) / std::abs(*reference);
  if (kind == "absolute") return std::abs(value - *reference);
  if (kind == "max") return value;
  return std::numeric_limits<double>::quiet_NaN();
}

std::optional<bool> Metric::pass() const {
  if (kind == "info") return std::nullopt;
  const double e = error();
  return std::isfinite(e) && e <= *tolerance;
}

Metric& Report::relative(const std::string& n, double v, double ref, double tol,
                         const std::string& src, const std::string& units) {
  metrics.push_back({n, v, units, "relative", ref, src, tol});
  return metrics.back();
}

Metric& Report::absolute(const std::string& n, double v, double ref, double tol,
                         const std::string& src, const std::string& units) {
  metrics.push_back({n, v, units, "absolute", ref, src, tol});
  return metrics.back();
}

Metric& Report::at_most(const std::string& n, double v, double goal, const std::string& src,
                        const std::string& units) {
  metrics.push_back({n, v, units, "max", std::nullopt, src, goal});
  return metrics.back();
}

Metric& Report::info(const std::string& n, double v, const std::string& units) {
  metrics.push_back({n, v, units, "info", std::nullopt, "", std::nullopt});
  return metrics.back();
}

bool Report::pass() const {
  for (const auto& m : metrics)
    if (m.pass() == false) return false;
  return true;
}

}  // namespace finverse::fem::validation
