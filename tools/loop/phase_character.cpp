// Residual mode against root displacement, velocity and acceleration (phase_character.hpp).
#include "loop/phase_character.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/SVD>

#include "loop/errors.hpp"

namespace finverse::loop {
namespace {

// Second-order derivative of samples y(t) on a (possibly non-uniform) grid: three-point Lagrange
// at every sample (one-sided at the ends).
Eigen::VectorXd derivative(const std::vector<double>& t, const Eigen::VectorXd& y) {
  const int n = static_cast<int>(y.size());
  Eigen::VectorXd d(n);
  for (int i = 0; i < n; ++i) {
    const int j = std::clamp(i, 1, n - 2);  // centre of the stencil j-1, j, j+1
    const double t0 = t[j - 1], t1 = t[j], t2 = t[j + 1], x = t[i];
    const double l0 = ((x - t1) + (x - t2)) / ((t0 - t1) * (t0 - t2));
    const double l1 = ((x - t0) + (x - t2)) / ((t1 - t0) * (t1 - t2));
    const double l2 = ((x - t0) + (x - t1)) / ((t2 - t0) * (t2 - t1));
    d(i) = l0 * y(j - 1) + l1 * y(j) + l2 * y(j + 1);
  }
  return d;
}

double pearson(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const Eigen::VectorXd x = a.array() - a.mean(), y = b.array() - b.mean();
  const double den = x.norm() * y.norm();
  return den > 0 ? x.dot(y) / den : 0.0;
}

}  // namespace

RootSignal root_signal(const SampledMotion& reconstruction, const FinRegions& regions) {
  const int nf = static_cast<int>(reconstruction.times.size());
  if (nf < 3) throw InvalidInput(reconstruction.source + ": /time: the root signal needs at least 3 frames");
  Eigen::MatrixXd mean(nf, 3);
  mean.setZero();
  int count = 0;
  for (std::size_t i = 0; i < regions.region.size(); ++i) {
    if (regions.region[i] != Region::root) continue;
    ++count;
    for (int k = 0; k < nf; ++k) mean.row(k) += reconstruction.positions[k].segment<3>(3 * i).transpose();
  }
  if (count == 0) throw InvalidInput(reconstruction.source + ": no node in the root region");
  mean /= count;
  const Eigen::MatrixXd centred = mean.rowwise() - mean.colwise().mean();
  RootSignal s;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(centred, Eigen::ComputeThinV);
  s.direction = svd.matrixV().col(0);
  if (s.direction.y() < 0 || (s.direction.y() == 0 && s.direction.sum() < 0)) s.direction = -s.direction;
  s.displacement = centred * s.direction;
  s.amplitude = 0.5 * (s.displacement.maxCoeff() - s.displacement.minCoeff());
  s.velocity = derivative(reconstruction.times, s.displacement);
  s.acceleration = derivative(reconstruction.times, s.velocity);
  return s;
}

PhaseCharacter phase_character(const Eigen::VectorXd& coefficient, const RootSignal& root, double collinear,
                               double weak) {
  PhaseCharacter p;
  p.rho_displacement = pearson(coefficient, root.displacement);
  p.rho_velocity = pearson(coefficient, root.velocity);
  p.rho_acceleration = pearson(coefficient, root.acceleration);
  p.rho_displacement_acceleration = pearson(root.displacement, root.acceleration);
  const double d = std::abs(p.rho_displacement), v = std::abs(p.rho_velocity), a = std::abs(p.rho_acceleration);
  if (d < weak && v < weak && a < weak) p.character = "none";
  else if (v >= d && v >= a) p.character = "damping-like";
  else if (std::abs(p.rho_displacement_acceleration) > collinear) p.character = "stiffness- or inertia-like";
  else p.character = d >= a ? "stiffness-like" : "inertia-like";
  return p;
}

}  // namespace finverse::loop
