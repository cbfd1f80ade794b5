// Active ray stiffening (issue 34, effect 1; the paper's first suspect): the rays of a group
// stiffen and relax twice per beat, E(t) = E (1 + a sin(2 * 2 pi f t + phi)), f the beat
// frequency. It enters the model as the stiffness field's modulation (stiffness_field.hpp), so it
// multiplies whatever moduli a fitter sets and every analysis (static at each time, quasi-static,
// dynamic, FSI) sees E(t). It replaces a modulation the materials file gave these rays.
#include <cmath>
#include <numbers>

#include "fem/effects/catalogue.hpp"
#include "fem/errors.hpp"

namespace finverse::fem::effects {
namespace {

class ActiveStiffening final : public ParameterisedEffect {
 public:
  ActiveStiffening()
      : ParameterisedEffect("active_stiffening",
                            {{"amplitude", "", 0, -0.9, 0.9}, {"phase", "rad", 0, -2 * std::numbers::pi, 2 * std::numbers::pi}},
                            true, true) {}

  void apply(Model& model, const FinLayout& layout) const override {
    if (value(0) == 0) return;
    const ModulusModulation m{value(0), 2 * frequency(layout), value(1)};
    int n = 0;
    for (const auto& b : layout.beams)
      if (in_group(layout, b.ray)) model.set_element_modulation(b.element, m), ++n;
    if (n == 0) throw InvalidInput("effect active_stiffening: group " + group_name() + " has no ray elements");
  }
};

}  // namespace

std::unique_ptr<ParameterisedEffect> make_active_stiffening() { return std::make_unique<ActiveStiffening>(); }

}  // namespace finverse::fem::effects
