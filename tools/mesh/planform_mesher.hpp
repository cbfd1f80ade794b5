// Triangulation of the fin planform (DESIGN.md section 5.2; seed paper section 4.1, Fig. 9):
// a CGAL constrained Delaunay triangulation refined by Ruppert/Shewchuk's Delaunay mesher, with
// the outline and every ray inserted as constrained polylines. Refinement only ever splits a
// constrained edge at points on it, so each ray ends up as a chain of mesh edges and the beam
// elements of the structural model share their nodes with the shell elements.
#pragma once

#include <array>
#include <vector>

#include "mesh/fin_template.hpp"

namespace finverse::mesh {

struct PlanformMeshOptions {
  double max_edge_over_chord = 0.04;  // upper bound on any edge length, in chords
  double min_angle_deg = 25.0;        // Ruppert's shape criterion; <= 30 degrees terminates reliably
};

struct PlanformMesh {
  std::vector<Point2> points;                // nodes (x, z), metres
  std::vector<std::array<int, 3>> triangles; // counter-clockwise in the (x, z) plane
  std::vector<std::vector<int>> ray_nodes;   // per ray (0 = ray 1): nodes along it, root to tip
  std::vector<std::vector<double>> ray_node_s;  // arc-length fraction of each of those nodes
  std::vector<char> on_boundary;             // per node: lies on the outline
  double min_angle_deg = 0;                  // achieved smallest triangle angle
  double max_edge = 0;                       // achieved longest edge, metres
};

// Meshes a validated template. Throws finverse::Error when CGAL rejects the constraints or the
// requested minimum angle is not reached.
PlanformMesh mesh_planform(const FinTemplate& t, const PlanformMeshOptions& options = {});

// Smallest interior angle, in degrees, of the triangle (a, b, c).
double min_angle_deg(const Point2& a, const Point2& b, const Point2& c);

}  // namespace finverse::mesh
