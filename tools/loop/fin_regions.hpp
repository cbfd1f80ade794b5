// Where on the fin a node sits, for saying where a residual mode lives (issue 34): five regions
// from the rest positions and the root node set, with no reliance on ray numbering, so that any
// mesh (a fin, a flap) is classified alike.
//   chord axis u: from the root nodes' centroid to the centroid of all nodes; xi = distance along
//     u from the root, divided by its largest value (0 root .. 1 distal);
//   span axis v: the direction of largest extent orthogonal to u, oriented to +z (dorsal, DESIGN.md
//     section 3); eta = -1 .. +1 across the local span within ten xi bins (the fin fans out).
// A node is root if xi < 0.2, else dorsal edge if eta > 0.6, ventral edge if eta < -0.6, else
// distal if xi > 0.8, else middle: the edges are the edge rays along their length, the distal
// region the trailing part between them.
#pragma once

#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace finverse::loop {

enum class Region : int { root = 0, distal = 1, dorsal_edge = 2, ventral_edge = 3, middle = 4 };
inline constexpr int kRegionCount = 5;
const char* to_string(Region r);

struct FinRegions {
  std::vector<Region> region;  // per node
  Eigen::VectorXd xi, eta;     // per node
};

// rest: [nv, 3] rest positions (rows); root_nodes non-empty. Throws InvalidInput for an empty
// root set, an index out of range, or a mesh without extent along the chord.
FinRegions classify_fin_regions(const Eigen::MatrixXd& rest, const std::vector<int>& root_nodes);

// Fractions of sum_i w_i |v_i|^2 (v_i the node's 3-vector in `field`, length 3 nv) per region;
// weights empty: all 1. The fractions sum to 1 (all 0 for a zero field).
std::array<double, kRegionCount> region_energy_fractions(const FinRegions& regions, const Eigen::VectorXd& field,
                                                         const Eigen::VectorXd& weights = {});

}  // namespace finverse::loop
