// Active root curvature (issue 34, effect 2; the paper's bilaminar suspect): the two half-rays
// of a fin ray, pulled differently at the root, bend the ray's proximal part with an imposed
// (eigen-) curvature kappa(t) = (angle / l) sin(2 pi f t + phi) over the root zone l =
// root_fraction * L_ray; with frequency 0 the curvature is constant, angle / l. "angle" is the
// bend the zone takes when nothing resists it (kappa l), positive towards the fin normal.
//
// An eigen-curvature kappa in a beam element is equivalent to end moments -EI kappa and +EI kappa
// about its bending axis (exact for a linear element: they make the element stress-free at
// curvature kappa). EI is the element's harmonic mean (the beam's flexibility integral) at the
// current modulus E(t), so a fitted or modulated E scales the actuation. The moment axis turns
// with the ray root's prescribed rotation (the zone sits at the root; its own bending is not
// followed): exact for small rotations and for the root pitch about z.
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include <Eigen/Geometry>

#include "fem/beam_section.hpp"
#include "fem/corotational_beam.hpp"
#include "fem/effects/catalogue.hpp"
#include "fem/errors.hpp"
#include "fem/rotation.hpp"

namespace finverse::fem::effects {
namespace {

struct ZoneElement {
  int element = 0, node0 = 0, node1 = 0, root = 0;
  Vec3 axis;                 // unit bending axis at rest, t x n
  double length_over_flex = 0;  // L / integral(ds / I): E times this is the harmonic-mean EI
  double curvature_weight = 0;  // share of the element inside the zone
  double zone_length = 0;
};

class RootCurvature final : public ParameterisedEffect {
 public:
  RootCurvature()
      : ParameterisedEffect("root_curvature",
                            {{"angle", "rad", 0, -1.5, 1.5}, {"phase", "rad", 0, -2 * std::numbers::pi, 2 * std::numbers::pi}},
                            true, true) {}

  bool configure_setting(const std::string& key, const nlohmann::json& v) override {
    if (key != "root_fraction") return false;
    if (!v.is_number() || !(v.get<double>() > 0 && v.get<double>() <= 1))
      throw InvalidInput("effect root_curvature: root_fraction " + v.dump() + ", expected 0 < value <= 1");
    root_fraction_ = v.get<double>();
    return true;
  }
  void write_settings(nlohmann::json& j) const override { j["root_fraction"] = root_fraction_; }
  std::string setting_keys() const override { return "root_fraction"; }

  void apply(Model& model, const FinLayout& layout) const override {
    if (value(0) == 0) return;
    std::map<int, std::pair<double, int>> ray_root;  // ray -> (smallest s0, its node)
    for (const auto& b : layout.beams) {
      auto [it, fresh] = ray_root.emplace(b.ray, std::make_pair(b.s0, b.node0));
      if (!fresh && b.s0 < it->second.first) it->second = {b.s0, b.node0};
    }
    std::vector<ZoneElement> zone;
    for (const auto& b : layout.beams) {
      if (!in_group(layout, b.ray)) continue;
      const double lo = std::min(b.s0, b.s1), hi = std::max(b.s0, b.s1);  // fractions of the ray
      const double inside = std::clamp(std::min(hi, root_fraction_) - lo, 0.0, hi - lo);
      if (inside <= 0) continue;
      const auto* beam = dynamic_cast<const CorotationalBeam*>(&model.element(b.element));
      if (!beam) throw InvalidInput("effect root_curvature: element " + std::to_string(b.element) + " is no beam");
      const Vec3 t = beam->reference_frame().col(0) * (b.s1 >= b.s0 ? 1.0 : -1.0);
      Vec3 axis = t.cross(layout.normal);
      if (!(axis.norm() > 1e-6)) throw InvalidInput("effect root_curvature: a ray lies along the fin normal");
      axis.normalize();
      // Bending about the section's local y (thin direction), the out-of-plane bending.
      const GaussRule g = gauss_legendre_01(4);
      double flex = 0;
      for (std::size_t q = 0; q < g.points.size(); ++q) flex += g.weights[q] / beam->section().at(g.points[q]).iy;
      ZoneElement z;
      z.element = b.element;
      z.node0 = b.s1 >= b.s0 ? b.node0 : b.node1;
      z.node1 = b.s1 >= b.s0 ? b.node1 : b.node0;
      z.root = ray_root.at(b.ray).second;
      z.axis = axis;
      z.length_over_flex = 1.0 / flex;  // flex was integral(ds/I)/L
      z.curvature_weight = inside / (hi - lo);
      z.zone_length = root_fraction_ * layout.ray_length.at(b.ray);
      zone.push_back(z);
    }
    if (zone.empty()) throw InvalidInput("effect root_curvature: group " + group_name() + " has no ray elements");
    const double angle = value(0), phase = value(1), f = frequency(layout);
    const FinLayout timing = layout;
    model.add_load_function([zone, angle, phase, f, timing](const Model& m, double t, Eigen::VectorXd& out) {
      const double shape = (f > 0 ? std::sin(2 * std::numbers::pi * f * t + phase) : 1.0) * ramp(timing, t);
      if (shape == 0) return;
      std::map<int, Vec3> root_rotation;
      for (const auto& z : zone) root_rotation.emplace(z.root, Vec3::Zero());
      for (const auto& p : m.prescribed())
        if (p.dof >= 3)
          if (auto it = root_rotation.find(p.node); it != root_rotation.end()) it->second(p.dof - 3) = p.at(t);
      for (const auto& z : zone) {
        const double kappa = angle / z.zone_length * shape * z.curvature_weight;
        const Vec3 moment = kappa * m.element_youngs_modulus(z.element, t) * z.length_over_flex *
                            (exp_so3(root_rotation.at(z.root)) * z.axis);
        out.segment<3>(kDofsPerNode * z.node0 + 3) -= moment;
        out.segment<3>(kDofsPerNode * z.node1 + 3) += moment;
      }
    });
  }

 private:
  double root_fraction_ = 0.2;
};

}  // namespace

std::unique_ptr<ParameterisedEffect> make_root_curvature() { return std::make_unique<RootCurvature>(); }

}  // namespace finverse::fem::effects
