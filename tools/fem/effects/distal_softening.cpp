// Distal softening (issue 34, effect 4): the rays get softer towards their tips beyond the fitted
// taper, EI(s) = EI_0 exp(-k s / L_ray) with s the arc length from the ray's root and k a
// dimensionless rate per ray length (k < 0: distal stiffening; s / L_ray is mesh.h5 /beams/s). Applied per element at its
// mid-length as the stiffness field's shape factor, so it multiplies the moduli a fitter sets.
#include <cmath>

#include "fem/effects/catalogue.hpp"
#include "fem/errors.hpp"

namespace finverse::fem::effects {
namespace {

class DistalSoftening final : public ParameterisedEffect {
 public:
  DistalSoftening() : ParameterisedEffect("distal_softening", {{"rate", "1/ray length", 0, -2, 5}}, true, false) {}

  void apply(Model& model, const FinLayout& layout) const override {
    if (value(0) == 0) return;
    int n = 0;
    for (const auto& b : layout.beams) {
      if (!in_group(layout, b.ray)) continue;
      model.set_element_stiffness_shape(b.element, std::exp(-value(0) * 0.5 * (b.s0 + b.s1)));
      ++n;
    }
    if (n == 0) throw InvalidInput("effect distal_softening: group " + group_name() + " has no ray elements");
  }
};

}  // namespace

std::unique_ptr<ParameterisedEffect> make_distal_softening() { return std::make_unique<DistalSoftening>(); }

}  // namespace finverse::fem::effects
