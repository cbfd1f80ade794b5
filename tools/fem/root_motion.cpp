// Root displacements and rigid-body rotation from tracked positions (see root_motion.hpp).
#include "fem/root_motion.hpp"

#include <cmath>
#include <memory>
#include <numbers>
#include <sstream>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>

#include "fem/errors.hpp"
#include "fem/load_history.hpp"

namespace finverse::fem {

RootRotation parse_root_rotation(const std::string& name) {
  if (name == "fit") return RootRotation::fit;
  if (name == "zero") return RootRotation::zero;
  throw InvalidInput("root rotation '" + name + "', expected fit or zero");
}

Mat3 fit_rigid_rotation(const std::vector<Vec3>& X, const std::vector<Vec3>& x) {
  const size_t n = X.size();
  if (n < 2) return Mat3::Identity();
  Vec3 c0 = Vec3::Zero(), c = Vec3::Zero();
  for (size_t i = 0; i < n; ++i) c0 += X[i], c += x[i];
  c0 /= static_cast<double>(n);
  c /= static_cast<double>(n);
  Mat3 H = Mat3::Zero();
  for (size_t i = 0; i < n; ++i) H += (X[i] - c0) * (x[i] - c).transpose();
  Eigen::JacobiSVD<Mat3> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Vec3 s = svd.singularValues();
  if (!(s(0) > 0)) return Mat3::Identity();
  if (s(1) <= 1e-8 * s(0)) {
    // Collinear: smallest rotation from the reference line direction onto the current one.
    Vec3 d0 = svd.matrixU().col(0), d1 = svd.matrixV().col(0);  // H d1 = s0 d0 (up to sign)
    if (d0.dot(H * d1) < 0) d1 = -d1;
    const Vec3 axis = d0.cross(d1);
    const double angle = std::atan2(axis.norm(), d0.dot(d1));
    return axis.norm() > 0 ? exp_so3(axis.normalized() * angle) : Mat3::Identity();
  }
  const Mat3 U = svd.matrixU(), V = svd.matrixV();
  Mat3 D = Mat3::Identity();
  D(2, 2) = (V * U.transpose()).determinant() < 0 ? -1.0 : 1.0;
  return V * D * U.transpose();
}

RootMotion::RootMotion(std::vector<int> nodes, std::vector<Vec3> reference, std::vector<double> times,
                       const std::vector<std::vector<Vec3>>& positions, RootRotation rotation, double ramp,
                       const RotationSupport& support)
    : nodes_(std::move(nodes)), times_(std::move(times)), ramp_(ramp) {
  check_sample_times(times_, ramp_, "root motion");
  if (nodes_.empty()) throw InvalidInput("root motion: no root nodes");
  if (reference.size() != nodes_.size() || positions.size() != times_.size())
    throw InvalidInput("root motion: inconsistent numbers of root nodes / frames");
  if (!support.reference.empty() && support.positions.size() != times_.size())
    throw InvalidInput("root motion: the rotation support has the wrong number of frames");
  std::vector<Vec3> fit_reference = reference;
  fit_reference.insert(fit_reference.end(), support.reference.begin(), support.reference.end());
  for (size_t k = 0; k < positions.size(); ++k) {
    if (positions[k].size() != nodes_.size())
      throw InvalidInput("root motion: frame " + std::to_string(k) + " has the wrong number of root nodes");
    for (size_t i = 0; i < nodes_.size(); ++i)
      if (!positions[k][i].allFinite()) {
        std::ostringstream os;
        os << "root motion: position of root node " << nodes_[i] << " at frame " << k << " is not finite";
        throw InvalidInput(os.str());
      }
    std::vector<Vec3> u(nodes_.size());
    for (size_t i = 0; i < nodes_.size(); ++i) u[i] = positions[k][i] - reference[i];
    displacement_.push_back(std::move(u));
    if (rotation == RootRotation::fit) {
      std::vector<Vec3> current = positions[k];
      if (!support.reference.empty()) {
        const auto& extra = support.positions[k];
        if (extra.size() != support.reference.size())
          throw InvalidInput("root motion: frame " + std::to_string(k) + " of the rotation support has the wrong size");
        for (const Vec3& p : extra)
          if (!p.allFinite())
            throw InvalidInput("root motion: a rotation support point at frame " + std::to_string(k) + " is not finite");
        current.insert(current.end(), extra.begin(), extra.end());
      }
      rotation_.push_back(log_so3(fit_rigid_rotation(fit_reference, current)));
    } else {
      rotation_.push_back(Vec3::Zero());
    }
    if (k > 0 && (rotation_[k] - rotation_[k - 1]).norm() > std::numbers::pi) {
      std::ostringstream os;
      os << "root motion: root rotation changes by more than pi between frames " << k - 1 << " and " << k;
      throw InvalidInput(os.str());
    }
  }
}

Vec3 RootMotion::displacement(int i, double t) const {
  const SampleWeights w = sample_weights(times_, ramp_, t);
  return w.w0 * displacement_[w.i0][i] + w.w1 * displacement_[w.i1][i];
}

Vec3 RootMotion::rotation_vector(double t) const {
  const SampleWeights w = sample_weights(times_, ramp_, t);
  return w.w0 * rotation_[w.i0] + w.w1 * rotation_[w.i1];
}

void RootMotion::apply(Model& model) const {
  // The model's time functions share one copy of the tables.
  auto self = std::make_shared<const RootMotion>(*this);
  for (int i = 0; i < static_cast<int>(nodes_.size()); ++i) {
    for (int d = 0; d < 3; ++d) {
      model.prescribe(nodes_[i], d, [self, i, d](double t) { return self->displacement(i, t)(d); });
      model.prescribe(nodes_[i], 3 + d, [self, d](double t) { return self->rotation_vector(t)(d); });
    }
  }
}

}  // namespace finverse::fem
