// Conservative load transfer, motion map and interface power on the shared wet surface
// (interface_transfer.hpp).
#include "fsi/interface_transfer.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"

namespace finverse::fsi {

namespace {

// Local coordinates may sit a hair outside the element from the flow side's round-off.
constexpr double kLocalSlack = 1e-10;

template <std::size_t K>
void check_elements(Eigen::Index n_nodes, const std::vector<std::array<int, K>>& elements,
                    const char* what) {
  if (n_nodes <= 0) {
    throw Error(std::string("fsi ") + what + ": expected a positive number of nodes, got " +
                std::to_string(n_nodes));
  }
  if (elements.empty()) throw Error(std::string("fsi ") + what + ": expected at least one element");
  for (std::size_t e = 0; e < elements.size(); ++e) {
    for (std::size_t k = 0; k < K; ++k) {
      const int node = elements[e][k];
      if (node < 0 || node >= n_nodes) {
        throw Error(std::string("fsi ") + what + ": element " + std::to_string(e) +
                    " names node " + std::to_string(node) + ", expected 0.." +
                    std::to_string(n_nodes - 1));
      }
      for (std::size_t l = 0; l < k; ++l) {
        if (elements[e][l] == node) {
          throw Error(std::string("fsi ") + what + ": element " + std::to_string(e) +
                      " repeats node " + std::to_string(node) + ", expected distinct nodes");
        }
      }
    }
  }
}

void check_sample(std::size_t s, int element, std::size_t n_elements, bool finite,
                  bool inside, const char* what) {
  if (element < 0 || static_cast<std::size_t>(element) >= n_elements) {
    throw Error(std::string("fsi ") + what + ": sample " + std::to_string(s) + " names element " +
                std::to_string(element) + ", expected 0.." + std::to_string(n_elements - 1));
  }
  if (!finite) {
    throw Error(std::string("fsi ") + what + ": sample " + std::to_string(s) +
                " has a non-finite force or coordinate");
  }
  if (!inside) {
    throw Error(std::string("fsi ") + what + ": sample " + std::to_string(s) +
                " lies outside its element, expected local coordinates in [0, 1]");
  }
}

}  // namespace

WetSurface2D::WetSurface2D(Eigen::Index n_nodes, std::vector<std::array<int, 2>> segments)
    : n_nodes_(n_nodes), segments_(std::move(segments)) {
  check_elements(n_nodes_, segments_, "wet surface 2-D");
}

Eigen::Matrix2Xd WetSurface2D::nodal_loads(const std::vector<Sample>& samples) const {
  Eigen::Matrix2Xd loads = Eigen::Matrix2Xd::Zero(2, n_nodes_);
  for (std::size_t s = 0; s < samples.size(); ++s) {
    const Sample& q = samples[s];
    check_sample(s, q.segment, segments_.size(), q.force.allFinite() && std::isfinite(q.xi),
                 q.xi >= -kLocalSlack && q.xi <= 1.0 + kLocalSlack, "load transfer 2-D");
    const auto& seg = segments_[static_cast<std::size_t>(q.segment)];
    loads.col(seg[0]) += (1.0 - q.xi) * q.force;
    loads.col(seg[1]) += q.xi * q.force;
  }
  return loads;
}

Eigen::Vector2d WetSurface2D::point(const Sample& sample, const Eigen::Matrix2Xd& nodes) const {
  if (nodes.cols() != n_nodes_) {
    throw Error("fsi wet surface 2-D: expected " + std::to_string(n_nodes_) +
                " node positions, got " + std::to_string(nodes.cols()));
  }
  check_sample(0, sample.segment, segments_.size(), std::isfinite(sample.xi), true,
               "wet surface 2-D point");
  const auto& seg = segments_[static_cast<std::size_t>(sample.segment)];
  return (1.0 - sample.xi) * nodes.col(seg[0]) + sample.xi * nodes.col(seg[1]);
}

WetSurface3D::WetSurface3D(Eigen::Index n_nodes, std::vector<std::array<int, 3>> triangles)
    : n_nodes_(n_nodes), triangles_(std::move(triangles)) {
  check_elements(n_nodes_, triangles_, "wet surface 3-D");
}

Eigen::Matrix3Xd WetSurface3D::nodal_loads(const std::vector<Sample>& samples) const {
  Eigen::Matrix3Xd loads = Eigen::Matrix3Xd::Zero(3, n_nodes_);
  for (std::size_t s = 0; s < samples.size(); ++s) {
    const Sample& q = samples[s];
    const double a = q.local(0), b = q.local(1);
    check_sample(s, q.triangle, triangles_.size(), q.force.allFinite() && q.local.allFinite(),
                 a >= -kLocalSlack && b >= -kLocalSlack && a + b <= 1.0 + kLocalSlack,
                 "load transfer 3-D");
    const auto& tri = triangles_[static_cast<std::size_t>(q.triangle)];
    loads.col(tri[0]) += (1.0 - a - b) * q.force;
    loads.col(tri[1]) += a * q.force;
    loads.col(tri[2]) += b * q.force;
  }
  return loads;
}

Eigen::Vector3d WetSurface3D::point(const Sample& sample, const Eigen::Matrix3Xd& nodes) const {
  if (nodes.cols() != n_nodes_) {
    throw Error("fsi wet surface 3-D: expected " + std::to_string(n_nodes_) +
                " node positions, got " + std::to_string(nodes.cols()));
  }
  check_sample(0, sample.triangle, triangles_.size(), sample.local.allFinite(), true,
               "wet surface 3-D point");
  const auto& tri = triangles_[static_cast<std::size_t>(sample.triangle)];
  const double a = sample.local(0), b = sample.local(1);
  return (1.0 - a - b) * nodes.col(tri[0]) + a * nodes.col(tri[1]) + b * nodes.col(tri[2]);
}

MotionMap::MotionMap(Eigen::Index n_nodes, std::vector<int> vertex_to_node)
    : n_nodes_(n_nodes), index_(std::move(vertex_to_node)) {
  if (n_nodes_ <= 0 || index_.empty()) {
    throw Error("fsi motion map: expected structure nodes and flow surface vertices, got " +
                std::to_string(n_nodes_) + " nodes and " + std::to_string(index_.size()) +
                " vertices");
  }
  for (std::size_t j = 0; j < index_.size(); ++j) {
    if (index_[j] < 0 || index_[j] >= n_nodes_) {
      throw Error("fsi motion map: flow vertex " + std::to_string(j) + " maps to node " +
                  std::to_string(index_[j]) + ", expected 0.." + std::to_string(n_nodes_ - 1) +
                  " (the wet surface does not match the flow body)");
    }
  }
}

Eigen::MatrixXd MotionMap::to_vertices(const Eigen::MatrixXd& node_values) const {
  if (node_values.cols() != n_nodes_) {
    throw Error("fsi motion map: expected values at " + std::to_string(n_nodes_) +
                " structure nodes, got " + std::to_string(node_values.cols()));
  }
  Eigen::MatrixXd out(node_values.rows(), vertices());
  for (std::size_t j = 0; j < index_.size(); ++j) {
    out.col(static_cast<Eigen::Index>(j)) = node_values.col(index_[j]);
  }
  return out;
}

Eigen::MatrixXd MotionMap::to_nodes(const Eigen::MatrixXd& vertex_forces) const {
  if (vertex_forces.cols() != vertices()) {
    throw Error("fsi motion map: expected forces at " + std::to_string(vertices()) +
                " flow vertices, got " + std::to_string(vertex_forces.cols()));
  }
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(vertex_forces.rows(), n_nodes_);
  for (std::size_t j = 0; j < index_.size(); ++j) {
    out.col(index_[j]) += vertex_forces.col(static_cast<Eigen::Index>(j));
  }
  return out;
}

double interface_power(const Eigen::MatrixXd& forces, const Eigen::MatrixXd& velocities) {
  if (forces.rows() != velocities.rows() || forces.cols() != velocities.cols()) {
    throw Error("fsi interface power: expected forces and velocities of equal shape, got " +
                std::to_string(forces.rows()) + "x" + std::to_string(forces.cols()) + " and " +
                std::to_string(velocities.rows()) + "x" + std::to_string(velocities.cols()));
  }
  return forces.cwiseProduct(velocities).sum();
}

}  // namespace finverse::fsi
