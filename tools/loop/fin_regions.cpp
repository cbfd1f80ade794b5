// Five regions of a fin from its rest shape and root nodes (fin_regions.hpp).
#include "loop/fin_regions.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>

#include "loop/errors.hpp"

namespace finverse::loop {

const char* to_string(Region r) {
  switch (r) {
    case Region::root: return "root";
    case Region::distal: return "distal";
    case Region::dorsal_edge: return "dorsal_edge";
    case Region::ventral_edge: return "ventral_edge";
    case Region::middle: return "middle";
  }
  return "?";
}

FinRegions classify_fin_regions(const Eigen::MatrixXd& rest, const std::vector<int>& root_nodes) {
  const int nv = static_cast<int>(rest.rows());
  if (rest.cols() != 3 || nv == 0) throw InvalidInput("mesh.h5: /points: expected [nv, 3] rest positions");
  if (root_nodes.empty()) throw InvalidInput("mesh.h5: /root_nodes: expected at least one root node");
  Eigen::RowVector3d root = Eigen::RowVector3d::Zero();
  for (int n : root_nodes) {
    if (n < 0 || n >= nv) throw InvalidInput("mesh.h5: /root_nodes: node " + std::to_string(n) + " out of range");
    root += rest.row(n);
  }
  root /= static_cast<double>(root_nodes.size());
  const Eigen::RowVector3d centroid = rest.colwise().mean();
  Eigen::RowVector3d u = centroid - root;
  if (u.norm() <= 0) throw InvalidInput("mesh.h5: /points: the mesh has no extent away from its root nodes");
  u.normalize();
  const Eigen::MatrixXd rel = rest.rowwise() - root;
  Eigen::VectorXd xi = rel * u.transpose();
  const double xmax = xi.maxCoeff();
  if (!(xmax > 0)) throw InvalidInput("mesh.h5: /points: the mesh has no extent away from its root nodes");
  xi /= xmax;
  const Eigen::MatrixXd off = rel - xi * xmax * u;  // components orthogonal to the chord
  const Eigen::Matrix3d cov = off.transpose() * off;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  Eigen::Vector3d v = eig.eigenvectors().col(2);
  if (v.z() < 0 || (v.z() == 0 && v.y() < 0)) v = -v;
  const Eigen::VectorXd along = off * v;

  constexpr int kBins = 10;
  std::vector<double> lo(kBins, INFINITY), hi(kBins, -INFINITY);
  auto bin = [&](double x) { return std::clamp(static_cast<int>(x * kBins), 0, kBins - 1); };
  for (int i = 0; i < nv; ++i) {
    const int b = bin(xi(i));
    lo[b] = std::min(lo[b], along(i));
    hi[b] = std::max(hi[b], along(i));
  }
  FinRegions out;
  out.xi = xi;
  out.eta.resize(nv);
  out.region.resize(nv);
  for (int i = 0; i < nv; ++i) {
    const int b = bin(xi(i));
    const double width = hi[b] - lo[b];
    out.eta(i) = width > 0 ? 2 * (along(i) - lo[b]) / width - 1 : 0;
    if (xi(i) < 0.2) out.region[i] = Region::root;
    else if (out.eta(i) > 0.6) out.region[i] = Region::dorsal_edge;
    else if (out.eta(i) < -0.6) out.region[i] = Region::ventral_edge;
    else if (xi(i) > 0.8) out.region[i] = Region::distal;
    else out.region[i] = Region::middle;
  }
  return out;
}

std::array<double, kRegionCount> region_energy_fractions(const FinRegions& regions, const Eigen::VectorXd& field,
                                                         const Eigen::VectorXd& weights) {
  std::array<double, kRegionCount> e{};
  double total = 0;
  const int nv = static_cast<int>(regions.region.size());
  for (int i = 0; i < nv; ++i) {
    const double w = weights.size() ? weights(i) : 1.0;
    const double ei = w * field.segment<3>(3 * i).squaredNorm();
    e[static_cast<int>(regions.region[i])] += ei;
    total += ei;
  }
  if (total > 0)
    for (auto& x : e) x /= total;
  return e;
}

}  // namespace finverse::loop
