// summary.json of validation cases and benchmarks (format in summary.hpp).
#include "core/summary.hpp"

#include <cmath>
#include <fstream>
#include <limits>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/provenance.hpp"

namespace finverse {

double Metric::error() const {
  if (kind == "relative" && reference) return std::abs(value - *reference) / std::abs(*reference);
  if (kind == "absolute" && reference) return std::abs(value - *reference);
  if ((kind == "max" || kind == "min") && tolerance) return value / *tolerance;  // fraction of the goal
  return std::numeric_limits<double>::quiet_NaN();
}

std::optional<bool> Metric::pass() const {
  if (kind == "info" || !tolerance) return std::nullopt;
  if (!std::isfinite(value)) return false;
  if (kind == "max") return value <= *tolerance;
  if (kind == "min") return value >= *tolerance;  // a floor, e.g. a p value that must stay large
  return error() <= *tolerance;
}

Summary::Summary(std::string kind, std::string name, std::string description)
    : kind_(std::move(kind)), name_(std::move(name)), description_(std::move(description)) {
  if (kind_ != "validation" && kind_ != "bench") throw Error("summary: kind must be validation or bench, got " + kind_);
}

Metric& Summary::relative(const std::string& name, double value, double reference, double tolerance,
                          const std::string& source, const std::string& units) {
  if (reference == 0) throw Error("summary: metric " + name + ": a relative error needs a nonzero reference");
  return metrics_.emplace_back(Metric{name, value, units, "relative", reference, source, tolerance});
}
Metric& Summary::absolute(const std::string& name, double value, double reference, double tolerance,
                          const std::string& source, const std::string& units) {
  return metrics_.emplace_back(Metric{name, value, units, "absolute", reference, source, tolerance});
}
Metric& Summary::at_most(const std::string& name, double value, double goal, const std::string& source,
                         const std::string& units) {
  return metrics_.emplace_back(Metric{name, value, units, "max", std::nullopt, source, goal});
}
Metric& Summary::at_least(const std::string& name, double value, double floor, const std::string& source,
                          const std::string& units) {
  return metrics_.emplace_back(Metric{name, value, units, "min", std::nullopt, source, floor});
}
Metric& Summary::info(const std::string& name, double value, const std::string& units) {
  return metrics_.emplace_back(Metric{name, value, units, "info", std::nullopt, "", std::nullopt});
}

void Summary::set_timing(double wall_seconds, int threads) {
  wall_s_ = wall_seconds;
  threads_ = threads;
}

bool Summary::pass() const {
  for (const auto& m : metrics_)
    if (auto p = m.pass(); p && !*p) return false;
  return true;
}

namespace {
nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
template <class T>
nlohmann::json opt(const std::optional<T>& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); }
}  // namespace

nlohmann::json Summary::to_json() const {
  nlohmann::json j;
  j["schema"] = "finverse/summary";
  j["schema_version"] = 1;
  j["kind"] = kind_;
  j["name"] = name_;
  j["description"] = description_;
  j["pass"] = pass();
  auto& ms = j["metrics"] = nlohmann::json::array();
  for (const auto& m : metrics_) {
    ms.push_back({{"name", m.name}, {"value", number_or_null(m.value)}, {"units", m.units}, {"kind", m.kind},
                  {"reference", opt(m.reference)}, {"source", m.source}, {"error", number_or_null(m.error())},
                  {"tolerance", opt(m.tolerance)}, {"pass", opt(m.pass())}});
  }
  j["parameters"] = parameters_;
  j["timing"] = {{"wall_s", wall_s_}, {"threads", threads_}};
  j["provenance"] = {{"producer", producer_string()}, {"host", host_name()}};
  return j;
}

Summary Summary::from_json(const nlohmann::json& j) {
  if (j.value("schema", "") != "finverse/summary") throw Error("summary: not a finverse/summary document");
  Summary s(j.at("kind").get<std::string>(), j.at("name").get<std::string>(), j.value("description", ""));
  for (const auto& m : j.at("metrics")) {
    Metric x;
    x.name = m.at("name").get<std::string>();
    x.value = m.at("value").is_null() ? std::numeric_limits<double>::quiet_NaN() : m.at("value").get<double>();
    x.units = m.value("units", "");
    x.kind = m.at("kind").get<std::string>();
    if (!m.at("reference").is_null()) x.reference = m.at("reference").get<double>();
    x.source = m.value("source", "");
    if (!m.at("tolerance").is_null()) x.tolerance = m.at("tolerance").get<double>();
    s.metrics_.push_back(x);
  }
  s.parameters_ = j.value("parameters", nlohmann::json::object());
  s.wall_s_ = j.at("timing").value("wall_s", 0.0);
  s.threads_ = j.at("timing").value("threads", 1);
  return s;
}

void Summary::write(const std::filesystem::path& path) const {
  write_text_atomic(path, to_json().dump(2) + "\n");
}

Summary Summary::read(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw Error(path.string() + ": cannot open summary");
  try {
    return from_json(nlohmann::json::parse(in));
  } catch (const nlohmann::json::exception& e) {
    throw Error(path.string() + ": malformed summary: " + e.what());
  }
}

}  // namespace finverse
