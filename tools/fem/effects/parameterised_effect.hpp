// Common plumbing of the candidate effects (structural_effect.hpp): a named list of bounded
// continuous parameters and a few fixed settings (ray group, frequency), read from and written
// to the JSON spec, with the range checks and one-line errors every effect shares.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "fem/effects/structural_effect.hpp"

namespace finverse::fem::effects {

class ParameterisedEffect : public StructuralEffect {
 public:
  std::string name() const override { return name_; }
  std::vector<EffectParameter> parameters() const override { return params_; }
  void set_parameters(const std::vector<double>& values) override;
  nlohmann::json to_json() const override;

  // Reads the spec's parameters and settings; throws InvalidInput for an unknown key.
  void configure(const nlohmann::json& spec);

 protected:
  ParameterisedEffect(std::string name, std::vector<EffectParameter> params, bool grouped, bool periodic);
  double value(std::size_t i) const { return params_[i].value; }
  // Rays of the layout in the effect's group ("group" setting, default all).
  bool in_group(const FinLayout& layout, int ray) const;
  // Frequency of the effect's time dependence [Hz]: the "frequency" setting, else the layout's
  // beat frequency; throws InvalidInput when neither is known.
  double frequency(const FinLayout& layout) const;
  // Smooth start r(t) of time-dependent effects (0 before layout.start_time, 1 after the ramp).
  static double ramp(const FinLayout& layout, double t);
  std::string group_name() const { return group_; }
  // Effect-specific settings beyond group and frequency: true when the key was taken.
  virtual bool configure_setting(const std::string& /*key*/, const nlohmann::json& /*value*/) { return false; }
  virtual void write_settings(nlohmann::json& /*spec*/) const {}
  virtual std::string setting_keys() const { return ""; }

 private:
  std::string name_;
  std::vector<EffectParameter> params_;
  bool grouped_, periodic_;
  std::string group_ = "all";
  std::vector<RayGroup> groups_{RayGroup::dorsal, RayGroup::middle, RayGroup::ventral};
  std::optional<double> frequency_;
};

}  // namespace finverse::fem::effects
