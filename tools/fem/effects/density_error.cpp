// Density / inertia error (issue 34, effect 5): the solid's mass times a factor, on the rays, the
// membrane or both (mass matrix, weight and total mass: Model::set_element_mass_factor). It stands
// for a wrong density and, with a factor > 1, for inertia the model lacks (entrained water that
// the quasi-static loads do not carry). The "target" setting picks the elements.
#include "fem/effects/catalogue.hpp"
#include "fem/errors.hpp"

namespace finverse::fem::effects {
namespace {

class DensityError final : public ParameterisedEffect {
 public:
  DensityError() : ParameterisedEffect("density_error", {{"factor", "", 1, 0.1, 10}}, false, false) {}

  bool configure_setting(const std::string& key, const nlohmann::json& v) override {
    if (key != "target") return false;
    if (!v.is_string() || (v != "all" && v != "rays" && v != "membrane"))
      throw InvalidInput("effect density_error: target " + v.dump() + ", expected \"all\", \"rays\" or \"membrane\"");
    target_ = v.get<std::string>();
    return true;
  }
  void write_settings(nlohmann::json& j) const override { j["target"] = target_; }
  std::string setting_keys() const override { return "target"; }

  void apply(Model& model, const FinLayout& layout) const override {
    if (value(0) == 1) return;
    if (target_ != "membrane")
      for (const auto& b : layout.beams) model.set_element_mass_factor(b.element, value(0));
    if (target_ != "rays")
      for (int e : layout.shell_elements) model.set_element_mass_factor(e, value(0));
  }

 private:
  std::string target_ = "all";
};

}  // namespace

std::unique_ptr<ParameterisedEffect> make_density_error() { return std::make_unique<DensityError>(); }

}  // namespace finverse::fem::effects
