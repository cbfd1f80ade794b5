// Graded scores of the report (see score.hpp).
#include "report/score.hpp"

#include <cmath>
#include <limits>

namespace finverse::report {

std::string to_string(Status s) {
  switch (s) {
    case Status::met: return "met";
    case Status::missed: return "missed";
    case Status::not_available: return "not available";
    case Status::info: return "info";
  }
  return "info";
}

Score graded(const std::string& name, double value, double goal, const std::string& source, const std::string& note,
             const std::string& units) {
  Score s{name, value, units, goal, source, note, Status::missed};
  // A NaN value (e.g. a zero reference) is never a pass.
  if (std::isfinite(value) && std::abs(value) <= goal) s.status = Status::met;
  if (!std::isfinite(value)) {
    s.value.reset();
    s.status = Status::not_available;
    s.note = note.empty() ? "the value is not finite" : note + "; the value is not finite";
  }
  return s;
}

Score unavailable(const std::string& name, double goal, const std::string& source, const std::string& why) {
  return Score{name, std::nullopt, "", goal, source, why, Status::not_available};
}

Score info(const std::string& name, double value, const std::string& units, const std::string& note) {
  Score s{name, value, units, std::nullopt, "", note, Status::info};
  if (!std::isfinite(value)) s.value.reset();
  return s;
}

double relative_difference(double a, double b) {
  if (b == 0) return std::numeric_limits<double>::quiet_NaN();
  return std::abs(a - b) / std::abs(b);
}

nlohmann::json to_json(const Score& s) {
  nlohmann::json j{{"name", s.name}, {"status", to_string(s.status)}, {"units", s.units}};
  j["value"] = s.value ? nlohmann::json(*s.value) : nlohmann::json(nullptr);
  j["goal"] = s.goal ? nlohmann::json(*s.goal) : nlohmann::json(nullptr);
  if (!s.source.empty()) j["source"] = s.source;
  if (!s.note.empty()) j["note"] = s.note;
  return j;
}

nlohmann::json to_json(const std::vector<Score>& scores) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& s : scores) a.push_back(to_json(s));
  return a;
}

}  // namespace finverse::report
