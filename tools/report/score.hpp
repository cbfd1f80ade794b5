// One graded number of the report (issue 33 "Scores"; the table of report/summary.json): its value,
// the goal it is held to and whether it met it, missed it, or could not be computed because an
// input is absent (e.g. every FSI-against-reconstruction score without fsi.h5). A score that is
// not available says why in `note`, so the reader never mistakes a missing input for a pass.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace finverse::report {

enum class Status { met, missed, not_available, info };
std::string to_string(Status s);

struct Score {
  std::string name;                // e.g. "trailing-edge point 1 peak-to-peak, FSI vs reconstruction"
  std::optional<double> value;     // the graded number (a relative error, or a value for info)
  std::string units;               // "" for dimensionless or a fraction
  std::optional<double> goal;      // met when value <= goal
  std::string source;              // where the goal comes from
  std::string note;                // why not available, or what the value is compared with
  Status status = Status::info;
};

// A graded score: met when |value| <= goal.
Score graded(const std::string& name, double value, double goal, const std::string& source,
             const std::string& note = "", const std::string& units = "");
Score unavailable(const std::string& name, double goal, const std::string& source, const std::string& why);
Score info(const std::string& name, double value, const std::string& units = "", const std::string& note = "");

// |a - b| / |b| (b = reference); NaN when b == 0.
double relative_difference(double a, double b);

nlohmann::json to_json(const Score& s);
nlohmann::json to_json(const std::vector<Score>& scores);

}  // namespace finverse::report
