// Structural (Rayleigh) damping (issue 34, effect 3): a_M M plus a_K times each element's local
// stiffness on its corotated deformation rate (Kelvin-Voigt, Element::viscous_force) added to the
// model (Model::set_rayleigh_damping; every dynamic solver, the FSI structure included, adds it to
// its own). A damping ratio zeta at circular frequency w follows zeta = a_M / (2 w) + a_K w / 2.
// Static and quasi-static analyses carry no velocity, so it changes only dynamic runs.
#include "fem/effects/catalogue.hpp"

namespace finverse::fem::effects {
namespace {

class RayleighDampingEffect final : public ParameterisedEffect {
 public:
  RayleighDampingEffect()
      : ParameterisedEffect("rayleigh_damping", {{"mass", "1/s", 0, 0, 1e3}, {"stiffness", "s", 0, 0, 1e-2}}, false,
                            false) {}

  void apply(Model& model, const FinLayout&) const override {
    model.set_rayleigh_damping(model.rayleigh_mass() + value(0), model.rayleigh_stiffness() + value(1));
  }
};

}  // namespace

std::unique_ptr<ParameterisedEffect> make_rayleigh_damping() { return std::make_unique<RayleighDampingEffect>(); }

}  // namespace finverse::fem::effects
