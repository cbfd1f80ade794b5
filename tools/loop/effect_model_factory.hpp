// The fitted fin with candidate effects switched on, as a fit::ModelFactory (issue 34): the
// parameters are the base fit's (fit/fin_parameters.hpp) followed by each effect's continuous
// parameters (fem/effects/structural_effect.hpp), so the fit's objectives and its
// Levenberg-Marquardt polish refit moduli and effect magnitudes together. build(p) builds the base
// model (on a mesh moved by the rest-shape effects, when one is on) and applies the effects to it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fem/effects/structural_effect.hpp"
#include "fit/fin_parameters.hpp"

namespace finverse::loop {

class EffectModelFactory : public fit::ModelFactory {
 public:
  // effects: make_effect() specs (their parameter values are replaced by p's tail); layout from
  // fem::io::make_fin_layout with its timing set. Throws fem::InvalidInput for a bad spec.
  EffectModelFactory(std::shared_ptr<const fit::FinModelFactory> base, std::vector<nlohmann::json> effects,
                     fem::FinLayout layout);

  std::vector<std::string> parameter_names() const override { return names_; }
  std::unique_ptr<fem::Model> build(const Eigen::VectorXd& physical) const override;
  Eigen::VectorXd default_parameters() const override { return defaults_; }
  std::vector<int> prescribed_nodes() const override { return base_->prescribed_nodes(); }
  fit::RayleighDamping damping() const override { return base_->damping(); }

  // Effect parameters of one spec (bounds, default = off), named "<effect>.<parameter>".
  static std::vector<fem::EffectParameter> effect_parameters(const nlohmann::json& spec);

 private:
  std::shared_ptr<const fit::FinModelFactory> base_;
  std::vector<nlohmann::json> specs_;
  fem::FinLayout layout_;
  std::vector<std::string> names_;
  Eigen::VectorXd defaults_;
  int base_count_ = 0;
};

}  // namespace finverse::loop
