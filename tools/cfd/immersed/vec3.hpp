// Vector algebra on points and directions of 3-D space (std::array<double, 3>) for the
// triangulated bodies: closest points, cut faces, thin-body surfaces, wall conditions and surface
// motion all need the same few products, written once here.
#pragma once

#include <array>
#include <cmath>

namespace finverse::cfd {

using Vec3 = std::array<double, 3>;

inline Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }
inline Vec3 unit(const Vec3& a) {
  const double l = norm(a);
  return {a[0] / l, a[1] / l, a[2] / l};
}

}  // namespace finverse::cfd
