// Shared pieces of the validation cases; see case_support.hpp.
#include "cfd/validation/case_support.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>

#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/log.hpp"

namespace finverse::cfd::validation {

std::string fmt(const char* format, double value) {
  char b[64];
  std::snprintf(b, sizeof b, format, value);
  return b;
}

Axis multigrid_axis(double lo, double hi, double ulo, double uhi, double h, double ratio) {
  const int n = Axis::stretched(lo, hi, ulo, uhi, h, ratio).size();
  return Axis::stretched_count(lo, hi, ulo, uhi, std::max(8, 8 * ((n + 7) / 8)), ratio);
}

Ramp cosine_ramp(double t, double t_ramp) {
  Ramp a;
  if (t < t_ramp) {
    const double q = std::numbers::pi / t_ramp;
    a.r = (1 - std::cos(q * t)) / 2;
    a.dr = q * std::sin(q * t) / 2;
    a.ddr = q * q * std::cos(q * t) / 2;
  }
  return a;
}

nlohmann::json read_reference(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error("--reference: cannot read " + path);
  try {
    nlohmann::json ref;
    in >> ref;
    return ref;
  } catch (const std::exception&) {
    throw Error("--reference: " + path + " is not valid JSON");
  }
}

std::string csv_row(std::initializer_list<double> values) {
  std::string row;
  char b[32];
  for (double v : values) {
    std::snprintf(b, sizeof b, "%.9g", v);
    if (!row.empty()) row += ',';
    row += b;
  }
  return row + '\n';
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

int finish(Summary& s, const std::filesystem::path& dir, double wall_seconds) {
  s.set_timing(wall_seconds, cli::threads_in_use());
  std::filesystem::create_directories(dir);
  s.write(dir / "summary.json");
  log::info("wrote " + (dir / "summary.json").string() + (s.pass() ? " (all metrics pass)" : " (a metric FAILED)"));
  return s.pass() ? kExitOk : kExitDifferent;
}

}  // namespace finverse::cfd::validation
