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
  if (name == "per_ray") return RootRotation::per_ray;
  if (name == "zero") return RootRotation::zero;
  throw InvalidInput("root rotation '" + name + "', expected fit, per_ray or zero");
}

Mat3 smallest_rotation(const Vec3& a, const Vec3& b) {
  const Vec3 axis = a.cross(b);
  const double angle = std::atan2(axis.norm(), a.dot(b));
  return axis.norm() > 0 ? exp_so3(axis.normalized() * angle) : Mat3::Identity();
}

RootLine RootLine::fit(const std::vector<Vec3>& p) {
  RootLine line;
  if (p.empty()) return line;
  for (const Vec3& x : p) line.centre += x / static_cast<double>(p.size());
  Mat3 C = Mat3::Zero();
  for (const Vec3& x : p) C += (x - line.centre) * (x - line.centre).transpose();
  if (!(C.trace() > 0)) return line;
  Eigen::JacobiSVD<Mat3> svd(C, Eigen::ComputeFullU);
  line.direction = svd.matrixU().col(0);
  // A fixed sign (towards +z, then +x), so the coordinate does not depend on the SVD's choice.
  const Vec3& d = line.direction;
  if (d.z() < 0 || (d.z() == 0 && (d.x() < 0 || (d.x() == 0 && d.y() < 0)))) line.direction = -d;
  return line;
}

RootLine::Weights RootLine::weights(const std::vector<double>& c, double s) {
  if (c.empty()) throw InvalidInput("root line: no carriers to interpolate between");
  int lo = -1, hi = -1;  // nearest carrier at or below s, at or above s
  for (int k = 0; k < static_cast<int>(c.size()); ++k) {
    if (c[k] <= s && (lo < 0 || c[k] > c[lo])) lo = k;
    if (c[k] >= s && (hi < 0 || c[k] < c[hi])) hi = k;
  }
  if (lo < 0) return {hi, hi, 0.0};
  if (hi < 0 || hi == lo || c[hi] == c[lo]) return {lo, lo, 0.0};
  return {lo, hi, (s - c[lo]) / (c[hi] - c[lo])};
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
  // per_ray: which root nodes carry their own rotation, and every other's interpolation weights.
  std::vector<std::vector<int>> own(nodes_.size());  // support points of each root node
  std::vector<int> carriers;                          // root nodes with support points
  std::vector<RootLine::Weights> interp(nodes_.size());
  if (rotation == RootRotation::per_ray) {
    if (support.reference.empty() || support.root_index.size() != support.reference.size())
      throw InvalidInput("root motion: per_ray rotation needs a support point on each ray leaving the root "
                         "(none given, or points without their root node)");
    for (size_t j = 0; j < support.root_index.size(); ++j) {
      const int r = support.root_index[j];
      if (r < 0 || r >= static_cast<int>(nodes_.size()))
        throw InvalidInput("root motion: support point " + std::to_string(j) + " names root node index " +
                           std::to_string(r) + ", expected 0.." + std::to_string(nodes_.size() - 1));
      own[static_cast<size_t>(r)].push_back(static_cast<int>(j));
    }
    const RootLine line = RootLine::fit(reference);
    std::vector<double> s;
    for (size_t i = 0; i < nodes_.size(); ++i)
      if (!own[i].empty()) carriers.push_back(static_cast<int>(i)), s.push_back(line.coordinate(reference[i]));
    for (size_t i = 0; i < nodes_.size(); ++i) {
      interp[i] = RootLine::weights(s, line.coordinate(reference[i]));
      interp[i].a = carriers[static_cast<size_t>(interp[i].a)];
      interp[i].b = carriers[static_cast<size_t>(interp[i].b)];
    }
  }
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
    std::vector<Vec3> theta(nodes_.size(), Vec3::Zero());
    if (rotation != RootRotation::zero) {
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
      const Mat3 R0 = fit_rigid_rotation(fit_reference, current);
      if (rotation == RootRotation::fit) {
        theta.assign(nodes_.size(), log_so3(R0));
      } else {
        // R0 of the root nodes alone: collinear, it turns the root line and leaves the spin about
        // it (the pitch) to each ray, so the rays' different pitches do not leak into R0 as a roll.
        const Mat3 R_line = fit_rigid_rotation(reference, positions[k]);
        for (int i : carriers) {
          Vec3 sum = Vec3::Zero();
          for (int j : own[static_cast<size_t>(i)]) {
            const Vec3 d_ref = R_line * (support.reference[static_cast<size_t>(j)] - reference[static_cast<size_t>(i)]);
            const Vec3 d_now = support.positions[k][static_cast<size_t>(j)] - positions[k][static_cast<size_t>(i)];
            sum += log_so3(smallest_rotation(d_ref, d_now) * R_line);
          }
          theta[static_cast<size_t>(i)] = sum / static_cast<double>(own[static_cast<size_t>(i)].size());
        }
        for (size_t i = 0; i < nodes_.size(); ++i)
          if (own[i].empty())
            theta[i] = (1 - interp[i].w) * theta[static_cast<size_t>(interp[i].a)] +
                       interp[i].w * theta[static_cast<size_t>(interp[i].b)];
      }
    }
    rotation_.push_back(std::move(theta));
    for (size_t i = 0; k > 0 && i < nodes_.size(); ++i)
      if ((rotation_[k][i] - rotation_[k - 1][i]).norm() > std::numbers::pi) {
        std::ostringstream os;
        os << "root motion: the rotation of root node " << nodes_[i] << " changes by more than pi between frames "
           << k - 1 << " and " << k;
        throw InvalidInput(os.str());
      }
  }
}

Vec3 RootMotion::displacement(int i, double t) const {
  const SampleWeights w = sample_weights(times_, ramp_, t);
  return w.w0 * displacement_[w.i0][i] + w.w1 * displacement_[w.i1][i];
}

Vec3 RootMotion::rotation_vector(int i, double t) const {
  const SampleWeights w = sample_weights(times_, ramp_, t);
  return w.w0 * rotation_[w.i0][i] + w.w1 * rotation_[w.i1][i];
}

void RootMotion::apply(Model& model) const {
  // The model's time functions share one copy of the tables.
  auto self = std::make_shared<const RootMotion>(*this);
  for (int i = 0; i < static_cast<int>(nodes_.size()); ++i) {
    for (int d = 0; d < 3; ++d) {
      model.prescribe(nodes_[i], d, [self, i, d](double t) { return self->displacement(i, t)(d); });
      model.prescribe(nodes_[i], 3 + d, [self, i, d](double t) { return self->rotation_vector(i, t)(d); });
    }
  }
}

}  // namespace finverse::fem
