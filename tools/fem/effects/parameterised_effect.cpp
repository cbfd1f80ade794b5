// Parameters, settings and checks shared by the candidate effects (see parameterised_effect.hpp).
#include "fem/effects/parameterised_effect.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "fem/errors.hpp"

namespace finverse::fem::effects {

ParameterisedEffect::ParameterisedEffect(std::string name, std::vector<EffectParameter> params, bool grouped,
                                         bool periodic)
    : name_(std::move(name)), params_(std::move(params)), grouped_(grouped), periodic_(periodic) {}

void ParameterisedEffect::set_parameters(const std::vector<double>& values) {
  if (values.size() != params_.size())
    throw InvalidInput("effect " + name_ + ": " + std::to_string(values.size()) + " parameter values, expected " +
                       std::to_string(params_.size()));
  for (std::size_t i = 0; i < values.size(); ++i) {
    const EffectParameter& p = params_[i];
    if (!std::isfinite(values[i]) || values[i] < p.lower || values[i] > p.upper) {
      std::ostringstream os;
      os << "effect " << name_ << ": " << p.name << " = " << values[i] << ", expected " << p.lower << " .. "
         << p.upper << (p.unit.empty() ? "" : " " + p.unit);
      throw InvalidInput(os.str());
    }
  }
  for (std::size_t i = 0; i < values.size(); ++i) params_[i].value = values[i];
}

void ParameterisedEffect::configure(const nlohmann::json& spec) {
  std::vector<double> v;
  for (const auto& p : params_) v.push_back(p.value);
  for (const auto& [key, val] : spec.items()) {
    if (key == "name") continue;
    auto it =
        std::find_if(params_.begin(), params_.end(), [&key = key](const EffectParameter& p) { return p.name == key; });
    if (it != params_.end()) {
      if (!val.is_number()) throw InvalidInput("effect " + name_ + ": " + key + " must be a number");
      v[static_cast<std::size_t>(it - params_.begin())] = val.get<double>();
    } else if (key == "group" && grouped_) {
      if (!val.is_string()) throw InvalidInput("effect " + name_ + ": group must be a string");
      groups_ = parse_ray_groups(val.get<std::string>(), name_);
      group_ = val.get<std::string>();
    } else if (key == "frequency" && periodic_) {
      if (!val.is_number() || !(val.get<double>() >= 0) || !std::isfinite(val.get<double>()))
        throw InvalidInput("effect " + name_ + ": frequency must be a number >= 0 [Hz]");
      frequency_ = val.get<double>();
    } else if (configure_setting(key, val)) {
    } else {
      std::string keys;
      for (const auto& p : params_) keys += (keys.empty() ? "" : ", ") + p.name;
      if (grouped_) keys += ", group";
      if (periodic_) keys += ", frequency";
      if (!setting_keys().empty()) keys += ", " + setting_keys();
      throw InvalidInput("effect " + name_ + ": unknown key '" + key + "', expected " + keys);
    }
  }
  set_parameters(v);
}

nlohmann::json ParameterisedEffect::to_json() const {
  nlohmann::json j;
  j["name"] = name_;
  for (const auto& p : params_) j[p.name] = p.value;
  if (grouped_) j["group"] = group_;
  if (periodic_ && frequency_) j["frequency"] = *frequency_;
  write_settings(j);
  return j;
}

bool ParameterisedEffect::in_group(const FinLayout& layout, int ray) const {
  auto it = layout.ray_group.find(ray);
  if (it == layout.ray_group.end()) return false;
  return std::find(groups_.begin(), groups_.end(), it->second) != groups_.end();
}

double ParameterisedEffect::frequency(const FinLayout& layout) const {
  if (frequency_) return *frequency_;
  if (layout.beat_frequency > 0) return layout.beat_frequency;
  throw InvalidInput("effect " + name_ + ": the beat frequency is unknown here, give \"frequency\" [Hz]");
}

double ParameterisedEffect::ramp(const FinLayout& layout, double t) {
  if (t <= layout.start_time) return layout.ramp > 0 ? 0.0 : 1.0;
  if (layout.ramp <= 0 || t >= layout.start_time + layout.ramp) return 1.0;
  return 0.5 * (1 - std::cos(std::numbers::pi * (t - layout.start_time) / layout.ramp));
}

}  // namespace finverse::fem::effects
