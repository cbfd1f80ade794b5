// A prescribed rigid motion from harmonics or a pose table; see prescribed_rigid_motion.hpp.
#include "cfd/immersed/prescribed_rigid_motion.hpp"

#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace finverse::cfd {

namespace {

using Mat3 = std::array<Vec3, 3>;

Mat3 identity3() { return {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}}; }

// Rodrigues: the rotation by theta about the unit axis e.
Mat3 axis_rotation(const Vec3& e, double theta) {
  const double c = std::cos(theta), s = std::sin(theta), v = 1 - c;
  return {{{c + v * e[0] * e[0], v * e[0] * e[1] - s * e[2], v * e[0] * e[2] + s * e[1]},
           {v * e[1] * e[0] + s * e[2], c + v * e[1] * e[1], v * e[1] * e[2] - s * e[0]},
           {v * e[2] * e[0] - s * e[1], v * e[2] * e[1] + s * e[0], c + v * e[2] * e[2]}}};
}

Mat3 matmul(const Mat3& a, const Mat3& b) {
  Mat3 m{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) m[i][j] += a[i][k] * b[k][j];
  return m;
}

Vec3 rotate(const Mat3& a, const Vec3& x) { return {dot(a[0], x), dot(a[1], x), dot(a[2], x)}; }

Vec3 plus(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
Vec3 times(double s, const Vec3& a) { return {s * a[0], s * a[1], s * a[2]}; }

bool finite(const MotionChannel& c) {
  bool ok = std::isfinite(c.offset) && std::isfinite(c.rate);
  for (const Harmonic& h : c.harmonics)
    ok = ok && std::isfinite(h.amplitude) && std::isfinite(h.frequency) && std::isfinite(h.phase);
  return ok;
}

}  // namespace

PrescribedRigidMotion::PrescribedRigidMotion(Vec3 pivot, std::array<MotionChannel, 3> translation,
                                             std::vector<Rotation> rotations, std::optional<TimeSpline> table,
                                             const std::string& what)
    : pivot_(pivot), translation_(translation), rotations_(std::move(rotations)), table_(std::move(table)), what_(what) {
  if (!(std::isfinite(pivot[0]) && std::isfinite(pivot[1]) && std::isfinite(pivot[2])))
    throw Error(what_ + ": the pivot must be finite");
  const int columns = table_ ? static_cast<int>(table_->channels()) : 0;
  const auto check = [&](const MotionChannel& c, const std::string& name) {
    if (!finite(c)) throw Error(what_ + ": " + name + ": every amplitude, frequency, phase, offset and rate must be finite");
    if (c.column >= columns)
      throw Error(what_ + ": " + name + ": the pose table has " + std::to_string(columns) + " value columns, not " +
                  std::to_string(c.column + 1));
  };
  for (int d = 0; d < 3; ++d) check(translation_[static_cast<std::size_t>(d)], std::string("translation ") + "xyz"[d]);
  for (std::size_t k = 0; k < rotations_.size(); ++k) {
    Rotation& r = rotations_[k];
    const double l = norm(r.axis);
    if (!(l > 0) || !std::isfinite(l)) throw Error(what_ + ": rotation " + std::to_string(k + 1) + ": the axis must be a non-zero vector");
    r.axis = unit(r.axis);
    check(r.angle, "rotation " + std::to_string(k + 1));
  }
}

bool PrescribedRigidMotion::moves() const {
  bool m = false;
  for (const MotionChannel& c : translation_) m = m || c.moves();
  for (const Rotation& r : rotations_) m = m || r.angle.moves() || r.angle.offset != 0;
  return m;
}

std::optional<std::array<double, 2>> PrescribedRigidMotion::span() const {
  if (!table_ || table_->wrap()) return std::nullopt;
  return std::array<double, 2>{table_->t_begin(), table_->t_end()};
}

void PrescribedRigidMotion::channel(const MotionChannel& c, double t, const std::vector<double>& row,
                                    const std::vector<double>& first, const std::vector<double>& second, double& q,
                                    double& q1, double& q2) const {
  if (c.column >= 0) {
    const auto j = static_cast<std::size_t>(c.column);
    q = c.offset + row[j];
    q1 = first[j];
    q2 = second[j];
    return;
  }
  q = c.offset + c.rate * t;
  q1 = c.rate;
  q2 = 0;
  for (const Harmonic& h : c.harmonics) {
    const double w = 2 * std::numbers::pi * h.frequency, a = w * t + h.phase;
    q += h.amplitude * std::sin(a);
    q1 += h.amplitude * w * std::cos(a);
    q2 -= h.amplitude * w * w * std::sin(a);
  }
}

RigidPose PrescribedRigidMotion::pose(double t) const {
  std::vector<double> row, first, second;
  if (table_) {
    const std::size_t n = table_->channels();
    row.resize(n);
    first.resize(n);
    second.resize(n);
    table_->evaluate(t, row.data(), first.data(), second.data());
  }
  RigidPose p;
  for (std::size_t d = 0; d < 3; ++d)
    channel(translation_[d], t, row, first, second, p.displacement[d], p.velocity[d], p.acceleration[d]);
  // R = R_n ... R_1; P_k = R_n ... R_{k+1} carries axis k to where the later rotations put it.
  const std::size_t n = rotations_.size();
  std::vector<double> th(n), th1(n), th2(n);
  std::vector<Mat3> R(n);
  for (std::size_t k = 0; k < n; ++k) {
    channel(rotations_[k].angle, t, row, first, second, th[k], th1[k], th2[k]);
    R[k] = axis_rotation(rotations_[k].axis, th[k]);
  }
  Mat3 P = identity3();
  Vec3 w_later{0, 0, 0};  // angular velocity of the rotations after k
  for (std::size_t k = n; k-- > 0;) {
    const Vec3 e = rotate(P, rotations_[k].axis);
    const Vec3 wk = times(th1[k], e);
    p.angular_acceleration = plus(p.angular_acceleration, plus(times(th2[k], e), cross(w_later, wk)));
    w_later = plus(w_later, wk);
    P = matmul(P, R[k]);
  }
  p.angular_velocity = w_later;
  p.rotation = P;
  return p;
}

PointKinematics PrescribedRigidMotion::point(const RigidPose& p, const Vec3& X) const {
  const Vec3 r = rotate(p.rotation, sub(X, pivot_));
  const Vec3& w = p.angular_velocity;
  PointKinematics k;
  k.position = plus(plus(pivot_, p.displacement), r);
  k.velocity = plus(p.velocity, cross(w, r));
  k.acceleration = plus(plus(p.acceleration, cross(p.angular_acceleration, r)), cross(w, cross(w, r)));
  return k;
}

RigidState PrescribedRigidMotion::plane_state(double t) const {
  for (const Rotation& r : rotations_)
    if (std::abs(r.axis[0]) > 1e-12 || std::abs(r.axis[1]) > 1e-12)
      throw Error(what_ + ": a plane body rotates about z only");
  const RigidPose p = pose(t);
  RigidState s;
  s.displacement = {p.displacement[0], p.displacement[1]};
  s.velocity = {p.velocity[0], p.velocity[1]};
  s.acceleration = {p.acceleration[0], p.acceleration[1]};
  // The angle itself, not atan2 of R: continuous over any number of turns.
  std::vector<double> row, first, second;
  if (table_) {
    row.resize(table_->channels());
    first.resize(row.size());
    second.resize(row.size());
    table_->evaluate(t, row.data(), first.data(), second.data());
  }
  for (const Rotation& r : rotations_) {
    double q = 0, q1 = 0, q2 = 0;
    channel(r.angle, t, row, first, second, q, q1, q2);
    s.angle += r.axis[2] * q;
  }
  s.angular_velocity = p.angular_velocity[2];
  s.angular_acceleration = p.angular_acceleration[2];
  return s;
}

}  // namespace finverse::cfd
