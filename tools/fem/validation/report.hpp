// Result of a validation case: metrics with value, reference and its source, error, tolerance,
// plus the run's parameters. Same semantics as finverse::Summary (tools/core/summary.hpp), which
// the executable converts it to; kept here so that the validation cases build without
// finverse_core.
//   relative  error = |value - reference| / |reference|, passes when error <= tolerance
//   absolute  error = |value - reference|,               passes when error <= tolerance
//   max       a goal: passes when value <= tolerance
//   info      reported only
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace finverse::fem::validation {

struct Metric {
  std::string name;
  double value = 0;
  std::string units;
  std::string kind;  // relative | absolute | max | info
  std::optional<double> reference;
  std::string source;
  std::optional<double> tolerance;
  double error() const;  // NaN for info
  std::optional<bool> pass() const;
};

struct Report {
  std::string name;
  std::string description;
  std::vector<Metric> metrics;
  nlohmann::json parameters = nlohmann::json::object();
  double wall_seconds = 0;
  int threads = 1;

  Metric& relative(const std::string& name, double value, double reference, double tolerance,
                   const std::string& source, const std::string& units = "");
  Metric& absolute(const std::string& name, double value, double reference, double tolerance,
                   const std::string& source, const std::string& units = "");
  Metric& at_most(const std::string& name, double value, double goal, const std::string& source,
                  const std::string& units = "");
  Metric& info(const std::string& name, double value, const std::string& units = "");
  bool pass() const;  // every graded metric passes
};

}  // namespace finverse::fem::validation
