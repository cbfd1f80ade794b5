// The unknowns of the fit and their scaled variables (parameter_space.hpp): validation of a
// specification with one-line messages naming the source and the parameter, the JSON form, and
// the maps z <-> physical value that every optimiser, the polish and the uncertainty share.
#include "fit/parameter_space.hpp"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "fit/errors.hpp"

namespace finverse::fit {

namespace {

std::string number(double value) {
  std::ostringstream s;
  s.precision(6);
  s << value;
  return s.str();
}

std::string label(const std::string& source, std::size_t i, const std::string& name) {
  std::string out = source + ": parameter " + std::to_string(i);
  if (!name.empty()) out += " ('" + name + "')";
  return out;
}

}  // namespace

const char* to_string(Scale scale) {
  return scale == Scale::log10 ? "log10" : "linear";
}

Scale parse_scale(const std::string& name, const std::string& source) {
  if (name == "log10") return Scale::log10;
  if (name == "linear") return Scale::linear;
  throw InvalidInput(source + ": unknown scale '" + name + "' (expected log10 or linear)");
}

ParameterSpace::ParameterSpace(std::vector<Parameter> parameters, const std::string& source)
    : parameters_(std::move(parameters)) {
  if (parameters_.empty()) throw InvalidInput(source + ": no parameters to fit");
  std::set<std::string> seen;
  for (std::size_t i = 0; i < parameters_.size(); ++i) {
    const Parameter& p = parameters_[i];
    const std::string where = label(source, i, p.name);
    if (p.name.empty()) throw InvalidInput(where + ": empty name");
    if (!seen.insert(p.name).second) throw InvalidInput(where + ": name repeated");
    if (!std::isfinite(p.lower) || !std::isfinite(p.upper))
      throw InvalidInput(where + ": bounds must be finite, got [" + number(p.lower) + ", " +
                         number(p.upper) + "]");
    if (p.lower > p.upper)
      throw InvalidInput(where + ": inverted bounds, lower " + number(p.lower) + " > upper " +
                         number(p.upper));
    if (p.lower == p.upper)
      throw InvalidInput(where + ": zero-width bounds, lower = upper = " + number(p.lower));
    if (p.scale == Scale::log10 && p.lower <= 0)
      throw InvalidInput(where + ": log10 scale needs a positive lower bound, got " +
                         number(p.lower));
    if (p.truth && !(*p.truth >= p.lower && *p.truth <= p.upper))
      throw InvalidInput(where + ": truth " + number(*p.truth) + " outside the bounds [" +
                         number(p.lower) + ", " + number(p.upper) + "]");
  }
}

int ParameterSpace::index(const std::string& name) const {
  for (std::size_t i = 0; i < parameters_.size(); ++i)
    if (parameters_[i].name == name) return static_cast<int>(i);
  return -1;
}

std::vector<std::string> ParameterSpace::names() const {
  std::vector<std::string> out;
  out.reserve(parameters_.size());
  for (const Parameter& p : parameters_) out.push_back(p.name);
  return out;
}

double ParameterSpace::to_scaled(int i, double physical) const {
  return (*this)[i].scale == Scale::log10 ? std::log10(physical) : physical;
}

double ParameterSpace::to_physical(int i, double scaled) const {
  return (*this)[i].scale == Scale::log10 ? std::pow(10.0, scaled) : scaled;
}

Eigen::VectorXd ParameterSpace::to_scaled(const Eigen::VectorXd& physical) const {
  if (physical.size() != size())
    throw InvalidInput("parameter vector has " + std::to_string(physical.size()) +
                       " entries, the parameter space " + std::to_string(size()));
  Eigen::VectorXd z(size());
  for (int i = 0; i < size(); ++i) z(i) = to_scaled(i, physical(i));
  return z;
}

Eigen::VectorXd ParameterSpace::to_physical(const Eigen::VectorXd& scaled) const {
  if (scaled.size() != size())
    throw InvalidInput("scaled vector has " + std::to_string(scaled.size()) +
                       " entries, the parameter space " + std::to_string(size()));
  Eigen::VectorXd p(size());
  for (int i = 0; i < size(); ++i) p(i) = to_physical(i, scaled(i));
  return p;
}

Eigen::VectorXd ParameterSpace::scaled_lower() const {
  Eigen::VectorXd z(size());
  for (int i = 0; i < size(); ++i) z(i) = to_scaled(i, parameters_[i].lower);
  return z;
}

Eigen::VectorXd ParameterSpace::scaled_upper() const {
  Eigen::VectorXd z(size());
  for (int i = 0; i < size(); ++i) z(i) = to_scaled(i, parameters_[i].upper);
  return z;
}

Eigen::VectorXd ParameterSpace::truth() const {
  Eigen::VectorXd t(size());
  for (int i = 0; i < size(); ++i) {
    if (!parameters_[i].truth) return {};
    t(i) = *parameters_[i].truth;
  }
  return t;
}

ParameterSpace parse_parameter_space(const nlohmann::json& j, const std::string& source) {
  if (!j.is_object() || !j.contains("parameters"))
    throw InvalidInput(source + ": expected an object with key 'parameters'");
  const nlohmann::json& list = j.at("parameters");
  if (!list.is_array()) throw InvalidInput(source + ": 'parameters' must be an array");
  static const std::set<std::string> known{"name", "lower", "upper", "scale", "unit", "truth",
                                           "description"};
  std::vector<Parameter> parameters;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const nlohmann::json& e = list[i];
    std::string where = source + ": parameters[" + std::to_string(i) + "]";
    if (!e.is_object()) throw InvalidInput(where + ": expected an object");
    if (e.contains("name") && e["name"].is_string())
      where += " ('" + e["name"].get<std::string>() + "')";
    for (const auto& item : e.items())
      if (!known.count(item.key()))
        throw InvalidInput(where + ": unknown key '" + item.key() +
                           "' (expected name, lower, upper, scale, unit, truth)");
    auto string_key = [&](const char* key, bool required) -> std::string {
      if (!e.contains(key)) {
        if (required) throw InvalidInput(where + ": missing key '" + key + "'");
        return {};
      }
      if (!e[key].is_string()) throw InvalidInput(where + ": '" + key + "' must be a string");
      return e[key].get<std::string>();
    };
    auto number_key = [&](const char* key) -> double {
      if (!e.contains(key)) throw InvalidInput(where + ": missing key '" + key + "'");
      if (!e[key].is_number()) throw InvalidInput(where + ": '" + key + "' must be a number");
      return e[key].get<double>();
    };
    Parameter p;
    p.name = string_key("name", true);
    p.unit = string_key("unit", false);
    p.lower = number_key("lower");
    p.upper = number_key("upper");
    if (e.contains("scale")) p.scale = parse_scale(string_key("scale", true), where + ": 'scale'");
    if (e.contains("truth")) p.truth = number_key("truth");
    parameters.push_back(std::move(p));
  }
  return ParameterSpace(std::move(parameters), source);
}

ParameterSpace read_parameter_space(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InvalidInput(path.string() + ": cannot open the parameter specification");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InvalidInput(path.string() + ": not valid JSON (" + e.what() + ")");
  }
  return parse_parameter_space(j, path.string());
}

}  // namespace finverse::fit
