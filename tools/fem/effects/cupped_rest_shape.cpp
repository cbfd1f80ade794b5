// Cupped rest shape (issue 34, effect 6, the rest-shape variant): the unloaded fin is not flat but
// cupped, its dorsal and ventral edges bowed out of the fin plane. Each node off the root moves
// along the fin normal by  depth * L_c * eta^2 * (u / L_c)^2,  u its distance from the root
// along the chord axis (L_c the largest), eta its span coordinate (-1 .. +1 at the widest): zero
// at the root and along the mid-line, largest at the distal corners. The new rest shape is stress
// free (the model is built on it), so it changes the fin's stiffness to lateral loads through its
// curvature, not through a pre-stress. Root nodes keep their place, so the root motion still fits.
#include <algorithm>
#include <cmath>

#include "fem/effects/catalogue.hpp"
#include "fem/errors.hpp"

namespace finverse::fem::effects {
namespace {

class CuppedRestShape final : public ParameterisedEffect {
 public:
  CuppedRestShape() : ParameterisedEffect("cupped_rest_shape", {{"depth", "chord", 0, -0.5, 0.5}}, false, false) {}

  void reshape(std::vector<Vec3>& rest, const FinLayout& layout) const override {
    if (value(0) == 0) return;
    double lc = 0, vmax = 0;
    for (const auto& X : rest) {
      lc = std::max(lc, (X - layout.root_centre).dot(layout.chord_axis));
      vmax = std::max(vmax, std::abs((X - layout.root_centre).dot(layout.span_axis)));
    }
    if (!(lc > 0) || !(vmax > 0)) throw InvalidInput("effect cupped_rest_shape: the fin has no extent off the root");
    std::vector<bool> root(rest.size(), false);
    for (int n : layout.root_nodes) root.at(static_cast<std::size_t>(n)) = true;
    for (std::size_t i = 0; i < rest.size(); ++i) {
      if (root[i]) continue;
      const Vec3 d = rest[i] - layout.root_centre;
      const double u = std::max(0.0, d.dot(layout.chord_axis)) / lc, eta = d.dot(layout.span_axis) / vmax;
      rest[i] += value(0) * lc * eta * eta * u * u * layout.normal;
    }
  }
  void apply(Model&, const FinLayout&) const override {}
};

}  // namespace

std::unique_ptr<ParameterisedEffect> make_cupped_rest_shape() { return std::make_unique<CuppedRestShape>(); }

}  // namespace finverse::fem::effects
