// Residual RMS over the trailing edge and its excursion (trailing_edge_error.hpp).
#include "loop/trailing_edge_error.hpp"

#include <cmath>
#include <limits>
#include <string>

#include <Eigen/SVD>

#include "loop/errors.hpp"

namespace finverse::loop {

double trailing_edge_excursion(const SampledMotion& reconstruction, const std::vector<int>& nodes) {
  const int nf = static_cast<int>(reconstruction.positions.size());
  const int nv = reconstruction.node_count();
  if (nodes.empty()) throw InvalidInput(reconstruction.source + ": no trailing-edge nodes");
  double sum = 0;
  for (int n : nodes) {
    if (n < 0 || n >= nv)
      throw InvalidInput(reconstruction.source + ": trailing-edge node " + std::to_string(n) + " out of range");
    Eigen::MatrixXd x(nf, 3);
    for (int k = 0; k < nf; ++k) x.row(k) = reconstruction.positions[k].segment<3>(3 * n).transpose();
    x.rowwise() -= x.colwise().mean();
    if (nf < 2) continue;
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(x, Eigen::ComputeThinV);
    const Eigen::VectorXd along = x * svd.matrixV().col(0);
    sum += along.maxCoeff() - along.minCoeff();
  }
  return sum / static_cast<double>(nodes.size());
}

TrailingEdgeError trailing_edge_error(const ResidualField& residual, const SampledMotion& reconstruction,
                                      const std::vector<int>& nodes) {
  TrailingEdgeError e;
  e.excursion = trailing_edge_excursion(reconstruction, nodes);
  double sum = 0;
  for (int n : nodes) {
    if (n >= residual.node_count()) throw InvalidInput("residual: trailing-edge node out of range");
    sum += residual.values.middleRows(3 * n, 3).squaredNorm();
  }
  e.rms = std::sqrt(sum / static_cast<double>(nodes.size() * residual.frame_count()));
  e.relative = e.excursion > 0 ? e.rms / e.excursion : std::numeric_limits<double>::quiet_NaN();
  return e;
}

}  // namespace finverse::loop
