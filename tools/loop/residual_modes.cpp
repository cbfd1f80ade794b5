// POD of the residual by a weighted thin SVD (residual_modes.hpp).
#include "loop/residual_modes.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/SVD>

#include "loop/errors.hpp"

namespace finverse::loop {

ResidualModes residual_modes(const ResidualField& field, const Eigen::VectorXd& weights, int max_modes) {
  const int nv = field.node_count();
  if (weights.size() != 0 && weights.size() != nv)
    throw InvalidInput("residual modes: expected " + std::to_string(nv) + " node weights, got " +
                       std::to_string(weights.size()));
  if (weights.size() != 0 && (weights.array() < 0).any())
    throw InvalidInput("residual modes: node weights must be >= 0");
  Eigen::VectorXd sw = Eigen::VectorXd::Ones(3 * nv);
  if (weights.size() != 0)
    for (int i = 0; i < nv; ++i) sw.segment<3>(3 * i).setConstant(std::sqrt(weights(i)));
  const Eigen::MatrixXd a = sw.asDiagonal() * field.values;
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd s = svd.singularValues();
  const int modes = std::min<int>(max_modes, static_cast<int>(s.size()));
  ResidualModes out;
  out.total_energy = s.squaredNorm();
  out.energy_fraction.resize(modes);
  out.shape.resize(3 * nv, modes);
  out.coefficient.resize(field.frame_count(), modes);
  for (int m = 0; m < modes; ++m) {
    out.energy_fraction(m) = out.total_energy > 0 ? s(m) * s(m) / out.total_energy : 0;
    Eigen::VectorXd phi = svd.matrixU().col(m);
    Eigen::VectorXd coef = s(m) * svd.matrixV().col(m);
    // Sign convention: the largest-magnitude component of the shape is positive (reproducible).
    Eigen::Index big = 0;
    phi.cwiseAbs().maxCoeff(&big);
    if (phi(big) < 0) {
      phi = -phi;
      coef = -coef;
    }
    for (Eigen::Index r = 0; r < phi.size(); ++r) phi(r) = sw(r) > 0 ? phi(r) / sw(r) : 0.0;
    out.shape.col(m) = phi;
    out.coefficient.col(m) = coef;
  }
  return out;
}

}  // namespace finverse::loop
