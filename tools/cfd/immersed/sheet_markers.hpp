// Lagrangian markers on a zero-thickness surface (a sheet: triangles in 3-D, segments in 2-D).
// Chosen once on the rest state: seeds thinned to at least `spacing` apart (closer markers make
// the marker system singular), each standing for the patch of the sheet nearest to it. Position
// and velocity are the patch's area-weighted mean of the nodes' values, and the marker's force
// returns to the patch's nodes by the transpose, so force and moment are kept and a mesh finer
// than the markers is loaded on every node. Measurements: docs/studies/thin_surface.md.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "cfd/immersed/vec3.hpp"

namespace finverse::cfd {

// The sheet's connectivity: dim 2, elements are segments {a, b, -1} in the (x, y) plane; dim 3,
// triangles {a, b, c}. Node indices in [0, nodes).
struct SheetTopology {
  int dim = 3;
  std::size_t nodes = 0;
  std::vector<std::array<int, 3>> elements;
};

// The sheet's nodes at one instant (velocity empty: at rest).
struct SheetState {
  std::vector<Vec3> position, velocity;
};

// A moving sheet: its node state at time t (the topology does not change).
using SheetMotion = std::function<SheetState(double t)>;

// Force of the fluid on the sheet [N; per unit depth in 2-D]: per marker, per node (the markers'
// forces returned by the transposed weights) and their sum.
struct SheetLoads {
  std::vector<Vec3> marker, nodal;
  Vec3 total{0, 0, 0};
};

class SheetMarkers {
 public:
  SheetMarkers() = default;
  // Markers on `rest` (the nodes' rest positions), seeds no closer than `spacing`. Throws a one-line
  // finverse::Error naming `what` and the element for a node index out of range or a degenerate
  // element (length or area below 1e-12 of the sheet's extent). `period`: the domain's length along
  // each periodic axis (0: not periodic). There distances are minimum-image ones, so that a sheet
  // that spans the period (nodes on both ends) gets one row of markers at the seam, not two.
  SheetMarkers(const SheetTopology& topology, const std::vector<Vec3>& rest, double spacing, const std::string& what,
               const std::array<double, 3>& period = {0, 0, 0});

  std::size_t size() const { return element_.size(); }
  const SheetTopology& topology() const { return topo_; }
  // The element that holds the marker's seed.
  int element(std::size_t m) const { return element_[m]; }
  // Per marker, node value -> marker value: sum over its entries e of weight[e] * value[node[e]].
  std::size_t entries_begin(std::size_t m) const { return start_[m]; }
  std::size_t entries_end(std::size_t m) const { return start_[m + 1]; }
  int entry_node(std::size_t e) const { return node_[e]; }
  double entry_weight(std::size_t e) const { return weight_[e]; }
  double spacing() const { return spacing_; }

  // Node values (velocities) interpolated to the markers.
  std::vector<Vec3> at_markers(const std::vector<Vec3>& node_values) const;
  // Node positions interpolated to the markers: at_markers plus the marker's periodic offset (the
  // mean shift by whole periods of the pieces that lie across a periodic seam; zero elsewhere).
  std::vector<Vec3> positions_at_markers(const std::vector<Vec3>& node_positions) const;
  const Vec3& offset(std::size_t m) const { return offset_[m]; }
  // Marker values (forces) returned to the nodes by the transposed weights.
  std::vector<Vec3> to_nodes(const std::vector<Vec3>& marker_values) const;
  // The sheet's length (2-D) or area (3-D) lumped to its nodes (a third of every triangle's area,
  // half of every segment's length) at node positions x.
  std::vector<double> node_measure(const std::vector<Vec3>& x) const;
  // Element lengths or areas and unit normals at node positions x (2-D: the normal (-t_y, t_x) of
  // the segment direction t = (b - a)/|b - a|; 3-D: the right-hand normal (b - a) x (c - a)).
  void element_geometry(const std::vector<Vec3>& x, std::vector<double>& measure, std::vector<Vec3>& normal) const;

 private:
  SheetTopology topo_;
  double spacing_ = 0;
  std::vector<int> element_;
  std::vector<std::size_t> start_;  // entries of marker m: [start_[m], start_[m + 1])
  std::vector<int> node_;
  std::vector<double> weight_;
  std::vector<Vec3> offset_;  // per marker, see positions_at_markers
};

}  // namespace finverse::cfd
