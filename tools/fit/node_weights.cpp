// Default and caller-given node weights of the objectives (see node_weights.hpp).
#include "fit/node_weights.hpp"

#include <cmath>

#include <Eigen/Geometry>

#include "fit/errors.hpp"

namespace finverse::fit {

Eigen::VectorXd default_node_weights(const fem::Model& model, const std::vector<int>& prescribed) {
  const int nn = model.node_count();
  const auto& X = model.reference_positions();
  Eigen::VectorXd area = Eigen::VectorXd::Zero(nn), length = Eigen::VectorXd::Zero(nn);
  double edge_sum = 0;
  long edges = 0;
  for (const auto& e : model.elements()) {
    const auto n = e->nodes();
    if (n.size() == 2) {
      const double L = (X[n[1]] - X[n[0]]).norm();
      length(n[0]) += 0.5 * L, length(n[1]) += 0.5 * L;
    } else if (n.size() >= 3) {
      // Polygon area by a fan from the first node (triangles: exact).
      fem::Vec3 an = fem::Vec3::Zero();
      for (size_t a = 1; a + 1 < n.size(); ++a) an += (X[n[a]] - X[n[0]]).cross(X[n[a + 1]] - X[n[0]]);
      const double A = 0.5 * an.norm();
      for (int v : n) area(v) += A / static_cast<double>(n.size());
      for (size_t a = 0; a < n.size(); ++a) edge_sum += (X[n[(a + 1) % n.size()]] - X[n[a]]).norm();
      edges += static_cast<long>(n.size());
    }
  }
  const double strip = edges > 0 ? edge_sum / static_cast<double>(edges) : 1.0;
  Eigen::VectorXd w(nn);
  for (int i = 0; i < nn; ++i) w(i) = area(i) > 0 ? area(i) : length(i) * strip;
  for (int n : prescribed) w(n) = 0;
  const long compared = (w.array() > 0).count();
  if (compared == 0) throw InvalidInput("node weights: every node is prescribed or on no element");
  return w * (static_cast<double>(compared) / w.sum());
}

Eigen::VectorXd checked_node_weights(const Eigen::VectorXd& weights, int node_count,
                                     const std::vector<int>& prescribed, const std::string& what) {
  if (weights.size() != node_count)
    throw InvalidInput(what + ": " + std::to_string(weights.size()) + " node weights for " +
                       std::to_string(node_count) + " nodes");
  for (int i = 0; i < node_count; ++i)
    if (!std::isfinite(weights(i)) || weights(i) < 0)
      throw InvalidInput(what + ": node weight " + std::to_string(i) + " = " + std::to_string(weights(i)) +
                         ", expected finite and >= 0");
  Eigen::VectorXd w = weights;
  for (int n : prescribed) w(n) = 0;
  if (!(w.sum() > 0)) throw InvalidInput(what + ": every node off the prescribed ones has weight 0");
  return w;
}

std::vector<int> compared_nodes(const Eigen::VectorXd& weights) {
  std::vector<int> nodes;
  for (int i = 0; i < weights.size(); ++i)
    if (weights(i) > 0) nodes.push_back(i);
  return nodes;
}

Eigen::Matrix3Xd compared_points(const fem::Model& model, const std::vector<int>& nodes) {
  Eigen::Matrix3Xd p(3, static_cast<Eigen::Index>(nodes.size()));
  for (size_t i = 0; i < nodes.size(); ++i) p.col(static_cast<Eigen::Index>(i)) = model.reference_positions()[nodes[i]];
  return p;
}

}  // namespace finverse::fit
