// Array comparison and the fin-diff report table (see array_compare.hpp).
#include "core/array_compare.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

namespace finverse {
Comparison mismatch(const std::string& object, const std::string& status, const std::string& detail) {
  Comparison c;
  c.object = object;
  c.ok = false;
  c.status = status;
  c.detail = detail;
  return c;
}

Comparison compare_values(const std::string& object, const NdArray<double>& ref, const NdArray<double>& cand, Tolerance tol) {
  if (ref.shape != cand.shape)
    return mismatch(object, "SHAPE", "reference " + shape_string(ref.shape) + ", candidate " + shape_string(cand.shape));
  Comparison c;
  c.object = object;
  c.tol = tol;
  c.n = ref.size();
  std::size_t worst = 0, nan_mismatch = 0;
  double worst_excess = -std::numeric_limits<double>::infinity();
  bool identical = true;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    const double a = ref.data[i], b = cand.data[i];
    if (std::isnan(a) || std::isnan(b)) {
      if (std::isnan(a) && std::isnan(b)) continue;
      ++nan_mismatch;
      ++c.n_bad;
      identical = false;
      if (worst_excess < std::numeric_limits<double>::infinity()) worst = i, worst_excess = std::numeric_limits<double>::infinity();
      continue;
    }
    if (a == b) continue;  // also equal infinities
    identical = false;
    const double abs_err = std::abs(a - b);
    const double rel_err = a != 0 ? abs_err / std::abs(a) : std::numeric_limits<double>::infinity();
    c.max_abs = std::max(c.max_abs, abs_err);
    c.max_rel = std::max(c.max_rel, rel_err);
    const double excess = abs_err - (tol.atol + tol.rtol * std::abs(a));
    if (!(excess <= 0)) ++c.n_bad;
    if (excess > worst_excess) worst_excess = excess, worst = i;
  }
  if (!identical) c.where = index_string(worst, ref.shape);
  c.ok = c.n_bad == 0;
  c.status = identical ? "equal" : c.ok ? "within" : nan_mismatch ? "NaN" : "DIFFERENT";
  if (nan_mismatch) c.detail = std::to_string(nan_mismatch) + " NaN mismatches";
  return c;
}

Comparison compare_strings(const std::string& object, const std::vector<std::string>& ref, const std::vector<std::string>& cand) {
  if (ref.size() != cand.size())
    return mismatch(object, "SHAPE", "reference [" + std::to_string(ref.size()) + "], candidate [" + std::to_string(cand.size()) + "]");
  Comparison c;
  c.object = object;
  c.n = ref.size();
  for (std::size_t i = 0; i < ref.size(); ++i)
    if (ref[i] != cand[i]) {
      if (c.n_bad++ == 0) {
        c.where = "[" + std::to_string(i) + "]";
        c.detail = "'" + ref[i].substr(0, 40) + "' vs '" + cand[i].substr(0, 40) + "'";
      }
    }
  c.ok = c.n_bad == 0;
  c.status = c.ok ? "equal" : "DIFFERENT";
  return c;
}

std::string format_table(const std::vector<Comparison>& rows, bool all) {
  std::size_t width = 6;
  for (const auto& r : rows)
    if (all || !r.ok) width = std::max(width, r.object.size());
  std::string out;
  char buf[512];
  std::snprintf(buf, sizeof buf, "%-*s  %-9s  %10s  %10s  %-14s  %-17s  %s\n", int(width), "object", "status", "max abs",
                "max rel", "worst at", "tolerance a/r", "detail");
  out += buf;
  for (const auto& r : rows) {
    if (!all && r.ok) continue;
    char tol[40];
    std::snprintf(tol, sizeof tol, "%.1e/%.1e", r.tol.atol, r.tol.rtol);
    std::snprintf(buf, sizeof buf, "%-*s  %-9s  %10.3e  %10.3e  %-14s  %-17s  %s\n", int(width), r.object.c_str(),
                  r.status.c_str(), r.max_abs, r.max_rel, r.where.c_str(), tol,
                  (r.n_bad && r.status != "NaN" ? std::to_string(r.n_bad) + "/" + std::to_string(r.n) + " outside " : std::string()) .append(r.detail).c_str());
    out += buf;
  }
  return out;
}

}  // namespace finverse
