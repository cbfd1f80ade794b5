// The one format of validation and benchmark results (DESIGN.md section 6):
// results/validation/<case>/summary.json and results/bench/<name>.json.
//
// Per metric: value, units, reference and its source, error, tolerance, pass. Three kinds:
//   relative  error = |value - reference| / |reference|, passes when error <= tolerance
//   absolute  error = |value - reference|,               passes when error <= tolerance
//   max       a goal: passes when value <= tolerance (e.g. a time ratio against a peer <= 0.5)
//   info      reported only: no reference, no pass/fail
// The file also records the run's parameters, timing and provenance. tools/scripts/summary.py
// prints any of these files as a table.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace finverse {

struct Metric {
  std::string name;
  double value = 0;
  std::string units;  // "" for dimensionless
  std::string kind;   // relative | absolute | max | info
  std::optional<double> reference;
  std::string source;
  std::optional<double> tolerance;
  double error() const;  // NaN for info
  std::optional<bool> pass() const;
};

class Summary {
 public:
  // kind: "validation" or "bench"; name: the case or benchmark name.
  Summary(std::string kind, std::string name, std::string description);

  Metric& relative(const std::string& name, double value, double reference, double tolerance,
                   const std::string& source, const std::string& units = "");
  Metric& absolute(const std::string& name, double value, double reference, double tolerance,
                   const std::string& source, const std::string& units = "");
  Metric& at_most(const std::string& name, double value, double goal, const std::string& source,
                  const std::string& units = "");
  // kind "min": passes when value >= floor (e.g. a p value that must stay large).
  Metric& at_least(const std::string& name, double value, double floor, const std::string& source,
                   const std::string& units = "");
  Metric& info(const std::string& name, double value, const std::string& units = "");

  nlohmann::json& parameters() { return parameters_; }
  void set_timing(double wall_seconds, int threads);
  const std::vector<Metric>& metrics() const { return metrics_; }
  bool pass() const;  // every graded metric passes

  nlohmann::json to_json() const;
  static Summary from_json(const nlohmann::json& j);
  void write(const std::filesystem::path& path) const;  // atomic (temporary + rename)
  static Summary read(const std::filesystem::path& path);

 private:
  std::string kind_, name_, description_;
  std::vector<Metric> metrics_;
  nlohmann::json parameters_ = nlohmann::json::object();
  double wall_s_ = 0;
  int threads_ = 1;
};

}  // namespace finverse
