// A harmonic correction of a prescribed root drive (see drive_correction.hpp).
#include "fem/drive_correction.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>

#include <Eigen/SVD>

#include "fem/errors.hpp"
#include "fem/load_history.hpp"
#include "fem/root_motion.hpp"

namespace finverse::fem {

double legendre(int k, double x) {
  double p0 = 1, p1 = x;
  if (k == 0) return p0;
  for (int n = 1; n < k; ++n) {
    const double p2 = ((2 * n + 1) * x * p1 - n * p0) / (n + 1);
    p0 = p1;
    p1 = p2;
  }
  return p1;
}

bool DriveCorrection::is_zero() const {
  auto zero = [](const std::vector<double>& v) { return std::all_of(v.begin(), v.end(), [](double x) { return x == 0; }); };
  return zero(pitch_sin) && zero(pitch_cos) && heave_sin == 0 && heave_cos == 0;
}

double DriveCorrection::ramp_factor(double t) const {
  return sample_weights(std::vector<double>{first_time}, ramp, t).w0;
}

double DriveCorrection::pitch(double eta, double t) const {
  const double wt = 2 * std::numbers::pi * frequency * t;
  double a = 0, b = 0;
  for (std::size_t k = 0; k < pitch_sin.size(); ++k) {
    const double p = legendre(static_cast<int>(k), eta);
    a += p * pitch_sin[k];
    b += p * pitch_cos[k];
  }
  return ramp_factor(t) * (a * std::sin(wt) + b * std::cos(wt));
}

double DriveCorrection::heave(double t) const {
  const double wt = 2 * std::numbers::pi * frequency * t;
  return ramp_factor(t) * (heave_sin * std::sin(wt) + heave_cos * std::cos(wt));
}

namespace {
// The normal of the best-fit plane through the points, towards +y (then +x, +z).
Vec3 plane_normal(const std::vector<Vec3>& p) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& x : p) c += x / static_cast<double>(p.size());
  Mat3 C = Mat3::Zero();
  for (const Vec3& x : p) C += (x - c) * (x - c).transpose();
  Eigen::JacobiSVD<Mat3> svd(C, Eigen::ComputeFullU);
  Vec3 n = svd.matrixU().col(2);
  if (n.y() < 0 || (n.y() == 0 && (n.x() < 0 || (n.x() == 0 && n.z() < 0)))) n = -n;
  return n;
}
}  // namespace

void DriveCorrection::apply(Model& model, const std::vector<int>& root_nodes) const {
  if (!(std::isfinite(frequency) && frequency > 0 && std::isfinite(first_time) && std::isfinite(ramp) && ramp >= 0))
    throw InvalidInput("drive correction: expected a finite frequency > 0, first time and ramp >= 0");
  if (pitch_sin.size() != pitch_cos.size())
    throw InvalidInput("drive correction: as many pitch sine as cosine coefficients expected");
  for (double v : pitch_sin)
    if (!std::isfinite(v)) throw InvalidInput("drive correction: a non-finite pitch coefficient");
  for (double v : pitch_cos)
    if (!std::isfinite(v)) throw InvalidInput("drive correction: a non-finite pitch coefficient");
  if (!std::isfinite(heave_sin) || !std::isfinite(heave_cos))
    throw InvalidInput("drive correction: a non-finite heave coefficient");

  const auto& X = model.reference_positions();
  std::vector<Vec3> root;
  for (int n : root_nodes) root.push_back(X.at(static_cast<std::size_t>(n)));
  const RootLine line = RootLine::fit(root);
  double lo = 0, hi = 0;
  for (std::size_t i = 0; i < root.size(); ++i) {
    const double s = line.coordinate(root[i]);
    lo = i == 0 ? s : std::min(lo, s);
    hi = i == 0 ? s : std::max(hi, s);
  }
  if (root.size() < 2 || !(hi > lo))
    throw InvalidInput("drive correction: the root needs at least two distinct nodes to place the rays along it");
  const Vec3 axis = line.direction, normal = plane_normal(X);

  // The prescriptions before the correction, per (node, dof).
  auto existing = [&](int node, int dof) -> TimeFunction {
    for (const PrescribedDof& p : model.prescribed())
      if (p.node == node && p.dof == dof) return p.value;
    return {};
  };
  auto self = std::make_shared<const DriveCorrection>(*this);
  for (std::size_t i = 0; i < root_nodes.size(); ++i) {
    const int n = root_nodes[i];
    const double eta = 2 * (line.coordinate(root[i]) - lo) / (hi - lo) - 1;
    for (int d = 0; d < 3; ++d) {
      TimeFunction u = existing(n, d), r = existing(n, 3 + d);
      const double hn = normal(d), ax = axis(d);
      model.prescribe(n, d, [u, self, hn](double t) { return (u ? u(t) : 0.0) + hn * self->heave(t); });
      model.prescribe(n, 3 + d, [r, self, eta, ax](double t) { return (r ? r(t) : 0.0) + ax * self->pitch(eta, t); });
    }
  }
}

}  // namespace finverse::fem
