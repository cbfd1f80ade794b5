// Transfer across the shared wet surface of flow and structure (issue 32, "interface transfer";
// seed paper section 2.3: "the flow and solid solvers share the triangular mesh on the exposed
// surface", loads interpolated onto the solid surface nodes).
//  - Loads, flow -> structure, conservative: the flow delivers samples (a point on a surface element
//    given by its local coordinates, and the force there: traction times the sample's area, per unit
//    depth in 2-D). Each sample's force goes to the element's nodes with the element's linear shape
//    functions at the point: (1 - xi, xi) on a 2-D segment, barycentric (1 - a - b, a, b) on a 3-D
//    triangle. The weights sum to one (total force kept) and reproduce the point (sum_i w_i x_i = p),
//    so the moment about any c, sum_i (x_i - c) x w_i F = (p - c) x F, is kept too.
//  - Motion, structure -> flow: flow surface vertex j moves with structure node index[j] (the flow's
//    surface vertices are a subset or permutation of the structure's surface nodes).
//  - Interface power sum_i F_i . v_i; with the loads above it equals the flow side's
//    sum_s F_s . v(p_s) for the linearly interpolated velocity, to round-off.
// Arrays are dim x count (columns are nodes, vertices or samples). Bad input throws finverse::Error.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

namespace finverse::fsi {

// A 2-D wet surface: segments (pairs of structure node indices), a polyline or several.
class WetSurface2D {
 public:
  WetSurface2D(Eigen::Index n_nodes, std::vector<std::array<int, 2>> segments);

  struct Sample {
    int segment = 0;
    double xi = 0.0;  // in [0, 1], 0 at the segment's first node
    Eigen::Vector2d force = Eigen::Vector2d::Zero();
  };
  // 2 x n_nodes nodal loads; nodes off the surface get zero.
  [[nodiscard]] Eigen::Matrix2Xd nodal_loads(const std::vector<Sample>& samples) const;
  // The point of a sample on the surface with the given 2 x n_nodes node positions.
  [[nodiscard]] Eigen::Vector2d point(const Sample& sample, const Eigen::Matrix2Xd& nodes) const;

  [[nodiscard]] Eigen::Index nodes() const { return n_nodes_; }
  [[nodiscard]] const std::vector<std::array<int, 2>>& segments() const { return segments_; }

 private:
  Eigen::Index n_nodes_;
  std::vector<std::array<int, 2>> segments_;
};

// A 3-D wet surface: triangles of structure node indices.
class WetSurface3D {
 public:
  WetSurface3D(Eigen::Index n_nodes, std::vector<std::array<int, 3>> triangles);

  struct Sample {
    int triangle = 0;
    Eigen::Vector2d local = Eigen::Vector2d::Zero();  // (a, b): weights of nodes 1, 2; node 0 1-a-b
    Eigen::Vector3d force = Eigen::Vector3d::Zero();
  };
  [[nodiscard]] Eigen::Matrix3Xd nodal_loads(const std::vector<Sample>& samples) const;
  [[nodiscard]] Eigen::Vector3d point(const Sample& sample, const Eigen::Matrix3Xd& nodes) const;

  [[nodiscard]] Eigen::Index nodes() const { return n_nodes_; }
  [[nodiscard]] const std::vector<std::array<int, 3>>& triangles() const { return triangles_; }

 private:
  Eigen::Index n_nodes_;
  std::vector<std::array<int, 3>> triangles_;
};

// Structure node -> flow surface vertex: vertex j is node index[j].
class MotionMap {
 public:
  MotionMap(Eigen::Index n_nodes, std::vector<int> vertex_to_node);

  // dim x n_nodes node values (positions, displacements, velocities) -> dim x n_vertices.
  [[nodiscard]] Eigen::MatrixXd to_vertices(const Eigen::MatrixXd& node_values) const;
  // The transpose: dim x n_vertices vertex forces -> dim x n_nodes node forces (summed; conservative).
  [[nodiscard]] Eigen::MatrixXd to_nodes(const Eigen::MatrixXd& vertex_forces) const;

  [[nodiscard]] Eigen::Index nodes() const { return n_nodes_; }
  [[nodiscard]] Eigen::Index vertices() const { return static_cast<Eigen::Index>(index_.size()); }

 private:
  Eigen::Index n_nodes_;
  std::vector<int> index_;
};

// sum_i F_i . v_i over the columns of two dim x n arrays of equal shape.
[[nodiscard]] double interface_power(const Eigen::MatrixXd& forces, const Eigen::MatrixXd& velocities);

}  // namespace finverse::fsi
