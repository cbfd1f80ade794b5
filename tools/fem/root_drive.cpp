// The fin's analytic root drive: heave and per-ray pitch (see root_drive.hpp).
#include "fem/root_drive.hpp"

#include <cmath>
#include <memory>
#include <numbers>
#include <string>

#include "fem/errors.hpp"

namespace finverse::fem {

RootDrive::RootDrive(std::vector<int> nodes, std::vector<Vec3> reference, std::vector<RayRoot> rays, double heave,
                     double frequency, double ramp, RootPitchProfile pitch)
    : nodes_(std::move(nodes)), reference_(std::move(reference)), rays_(std::move(rays)), heave_(heave),
      frequency_(frequency), ramp_(ramp), profile_(pitch) {
  if (nodes_.empty() || reference_.size() != nodes_.size())
    throw InvalidInput("root drive: no root nodes, or not one rest position per root node");
  if (rays_.empty()) throw InvalidInput("root drive: no ray roots among the root nodes (the pitch acts on the rays)");
  if (!(std::isfinite(heave) && std::isfinite(frequency) && frequency > 0 && std::isfinite(ramp) && ramp >= 0))
    throw InvalidInput("root drive: expected a finite heave, frequency > 0 and ramp >= 0");
  line_ = RootLine::fit(reference_);
  for (const RayRoot& r : rays_) {
    if (r.root_index < 0 || r.root_index >= static_cast<int>(nodes_.size()))
      throw InvalidInput("root drive: ray root index " + std::to_string(r.root_index) + " out of range");
    ray_coordinate_.push_back(line_.coordinate(reference_[static_cast<std::size_t>(r.root_index)]));
  }
  for (const Vec3& X : reference_) node_weights_.push_back(RootLine::weights(ray_coordinate_, line_.coordinate(X)));
}

double RootDrive::ramp_factor(double t) const {
  if (ramp_ <= 0 || t >= ramp_) return 1;
  if (t <= 0) return 0;
  return 0.5 * (1 - std::cos(std::numbers::pi * t / ramp_));
}

double RootDrive::heave(double t) const {
  return ramp_factor(t) * heave_ * std::sin(2 * std::numbers::pi * frequency_ * t);
}

double RootDrive::ray_pitch(std::size_t ray, double t) const {
  return ramp_factor(t) * profile_.pitch(rays_.at(ray).eta, 2 * std::numbers::pi * frequency_ * t);
}

double RootDrive::pitch_at(const RootLine::Weights& w, double t) const {
  const double a = ray_pitch(static_cast<std::size_t>(w.a), t);
  return w.a == w.b ? a : (1 - w.w) * a + w.w * ray_pitch(static_cast<std::size_t>(w.b), t);
}

double RootDrive::pitch(int i, double t) const { return pitch_at(node_weights_.at(static_cast<std::size_t>(i)), t); }

Vec3 RootDrive::rigid_position(const Vec3& X, double t) const {
  const double s = line_.coordinate(X);
  const Vec3 foot = line_.centre + s * line_.direction;
  const double theta = pitch_at(RootLine::weights(ray_coordinate_, s), t);
  const Vec3 r = X - foot;
  const double c = std::cos(theta), sn = std::sin(theta);
  return foot + Vec3(c * r.x() - sn * r.y(), sn * r.x() + c * r.y(), r.z()) + Vec3(0, heave(t), 0);
}

void RootDrive::apply(Model& model) const {
  auto self = std::make_shared<const RootDrive>(*this);
  for (int i = 0; i < static_cast<int>(nodes_.size()); ++i) {
    model.prescribe(nodes_[static_cast<std::size_t>(i)], 0, {});
    model.prescribe(nodes_[static_cast<std::size_t>(i)], 1, [self](double t) { return self->heave(t); });
    model.prescribe(nodes_[static_cast<std::size_t>(i)], 2, {});
    model.prescribe(nodes_[static_cast<std::size_t>(i)], 3, {});
    model.prescribe(nodes_[static_cast<std::size_t>(i)], 4, {});
    model.prescribe(nodes_[static_cast<std::size_t>(i)], 5, [self, i](double t) { return self->pitch(i, t); });
  }
}

}  // namespace finverse::fem
