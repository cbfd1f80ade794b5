// Rotation-vector utilities (see rotation.hpp).
#include "fem/rotation.hpp"

#include <cmath>

#include <Eigen/Geometry>

namespace finverse::fem {

Mat3 skew(const Vec3& v) {
  Mat3 m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

Vec3 unskew(const Mat3& m) {
  return 0.5 * Vec3(m(2, 1) - m(1, 2), m(0, 2) - m(2, 0), m(1, 0) - m(0, 1));
}

Mat3 exp_so3(const Vec3& theta) {
  const double t2 = theta.squaredNorm();
  const Mat3 S = skew(theta);
  double a, b;  // sin(t)/t, (1-cos t)/t^2
  if (t2 < 1e-8) {
    a = 1.0 - t2 / 6.0 + t2 * t2 / 120.0;
    b = 0.5 - t2 / 24.0 + t2 * t2 / 720.0;
  } else {
    const double t = std::sqrt(t2);
    a = std::sin(t) / t;
    b = (1.0 - std::cos(t)) / t2;
  }
  return Mat3::Identity() + a * S + b * S * S;
}

Vec3 log_so3(const Mat3& R) {
  // Through the unit quaternion: accurate near 0 and near pi, unlike acos((tr R - 1)/2).
  Eigen::Quaterniond q(R);
  q.normalize();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const double s = q.vec().norm();
  if (s < 1e-12) return 2.0 * q.vec() / q.w();  // sin(t/2)/(t/2) ~ 1
  const double angle = 2.0 * std::atan2(s, q.w());
  return q.vec() * (angle / s);
}

namespace {
// eta(t) = (1 - (t/2)/tan(t/2)) / t^2, also = [2 sin t - t(1 + cos t)] / (2 t^2 sin t)
double eta_of(double t) {
  const double t2 = t * t;
  if (t < 0.05) return 1.0 / 12.0 + t2 / 720.0 + t2 * t2 / 30240.0;
  return (1.0 - 0.5 * t / std::tan(0.5 * t)) / t2;
}
// mu(t) = [t(t + sin t) - 8 sin^2(t/2)] / (4 t^4 sin^2(t/2))
double mu_of(double t) {
  const double t2 = t * t;
  if (t < 0.05) return 1.0 / 360.0 + t2 / 7560.0 + t2 * t2 / 201600.0;
  const double s = std::sin(0.5 * t);
  return (t * (t + std::sin(t)) - 8.0 * s * s) / (4.0 * t2 * t2 * s * s);
}
}  // namespace

Mat3 tangent_inverse(const Vec3& theta) {
  const Mat3 S = skew(theta);
  return Mat3::Identity() - 0.5 * S + eta_of(theta.norm()) * S * S;
}

Mat3 tangent_inverse_derivative(const Vec3& theta, const Vec3& m) {
  const double t = theta.norm();
  const Mat3 S = skew(theta);
  const Mat3 H = eta_of(t) * (theta * m.transpose() - 2.0 * m * theta.transpose() +
                              theta.dot(m) * Mat3::Identity()) +
                 mu_of(t) * S * S * m * theta.transpose() - 0.5 * skew(m);
  return H * tangent_inverse(theta);
}

}  // namespace finverse::fem
