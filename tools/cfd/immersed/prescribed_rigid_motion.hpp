// A prescribed rigid motion of a body in 3-D or in the plane (issue 44, deliverable 4: moving
// bodies as case files). Each scalar channel (three translations of the pivot, one angle per
// rotation axis) is either an offset plus a constant rate plus a sum of harmonics
//     q(t) = q0 + r t + sum_k a_k sin(2 pi f_k t + phi_k),
// or a column of a pose table interpolated by a cubic spline in time (time_spline.hpp: C2, so the
// acceleration that the closed body's pressure datum needs is continuous). The body's placement is
//     x(t) = p + d(t) + R(t) (X - p),        R = R_n(theta_n) ... R_1(theta_1),
// rotation 1 applied first, every axis fixed in space through the moving pivot p + d(t) (a pitching
// wing that also flaps: pitch first, then the stroke). Velocity and acceleration are exact:
//     v = d' + w x r,   a = d'' + w' x r + w x (w x r),   r = R (X - p),
//     w = sum_k theta_k' P_k e_k,   P_k = R_n ... R_{k+1},   w' = sum_k (theta_k'' P_k e_k + w_{>k} x theta_k' P_k e_k).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "cfd/immersed/rigid_motion.hpp"
#include "cfd/immersed/time_spline.hpp"
#include "cfd/immersed/vec3.hpp"

namespace finverse::cfd {

struct Harmonic {
  double amplitude = 0;  // [m] or [rad]
  double frequency = 0;  // [Hz]
  double phase = 0;      // [rad]
};

// One scalar of the motion: offset + rate t + harmonics, or (column >= 0) a column of the pose table.
struct MotionChannel {
  double offset = 0, rate = 0;
  std::vector<Harmonic> harmonics;
  int column = -1;
  bool moves() const { return rate != 0 || !harmonics.empty() || column >= 0; }
};

struct RigidPose {
  Vec3 displacement{}, velocity{}, acceleration{};     // of the pivot
  std::array<Vec3, 3> rotation{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};  // R, row-major
  Vec3 angular_velocity{}, angular_acceleration{};
};

struct PointKinematics {
  Vec3 position, velocity, acceleration;
};

class PrescribedRigidMotion {
 public:
  struct Rotation {
    Vec3 axis{0, 0, 1};  // normalised on construction
    MotionChannel angle;
  };

  PrescribedRigidMotion() = default;
  // Throws finverse::Error (naming `what`) for a zero axis, a non-finite value, or a table column
  // that the table does not have.
  PrescribedRigidMotion(Vec3 pivot, std::array<MotionChannel, 3> translation, std::vector<Rotation> rotations,
                        std::optional<TimeSpline> table = {}, const std::string& what = "motion");

  RigidPose pose(double t) const;
  PointKinematics point(const RigidPose& pose, const Vec3& reference) const;
  // The plane motion (rotations about z only; throws otherwise) as the 2-D moving body's state.
  RigidState plane_state(double t) const;
  const Vec3& pivot() const { return pivot_; }
  bool moves() const;
  // The time span a pose table covers (none: any time).
  std::optional<std::array<double, 2>> span() const;

 private:
  void channel(const MotionChannel& c, double t, const std::vector<double>& table_row,
               const std::vector<double>& table_first, const std::vector<double>& table_second, double& q,
               double& q1, double& q2) const;

  Vec3 pivot_{};
  std::array<MotionChannel, 3> translation_{};
  std::vector<Rotation> rotations_;
  std::optional<TimeSpline> table_;
  std::string what_ = "motion";
};

}  // namespace finverse::cfd
