// Loads of the closed thin body mapped back onto the fin's mid-surface (DESIGN.md section 5.1: "its
// load is mapped back to the mid-surface nodes as a net (pressure-jump plus shear) force").
//
// Nodal force: each surface triangle's force (pressure + viscous, SurfaceForces) goes to its three
// vertices in equal thirds -- the consistent nodal load of a constant traction with linear shape
// functions -- and each surface vertex hands its share to its source node. Both sides of the body
// and the rim wall land on the same mid-surface node, so the result is the net force on the node;
// the sum over nodes equals the sum over triangles (to round-off).
//
// Pressure jump per shell (mid-surface) triangle: the mean pressure of a surface triangle is
// p_j = -F_j . a_j / |a_j|^2 (F_j its pressure force, a_j its area vector, F_j = -p_j a_j for a
// pressure constant over it); on each side of a shell triangle the facing surface triangle is the
// one whose three vertices are that side's copies of the shell triangle's nodes (fin-mesh's
// construction always has it; otherwise the side pressure is the mean of the area-weighted side
// pressures at the three nodes). With "front" the side the shell triangle's right-hand normal n
// points to,
//     pressure_jump = p_back - p_front,
// so the net pressure force on the shell triangle is pressure_jump * area * n.
#pragma once

#include <array>
#include <vector>

#include "cfd/immersed/thin_body.hpp"
#include "cfd/immersed/triangulated_surface.hpp"

namespace finverse::cfd {

// Net force on each mid-surface node [body.node_count] from the per-triangle forces (pressure and
// viscous) on the body's surface.
std::vector<Vec3> nodal_forces(const ThinBody& body, const SurfaceForces& forces);

// Sum of the per-triangle forces (pressure + viscous), in triangle order.
Vec3 triangle_force_sum(const SurfaceForces& forces);

// Pressure jump [per mid-surface triangle] from the pressure forces on the surface in the state
// `surface` (the same instant as the forces). Pressure in the units of the forces per area.
std::vector<double> pressure_jump(const ThinBody& body, const std::vector<std::array<int, 3>>& mid_triangles,
                                  const TriangulatedSurface& surface, const SurfaceForces& forces);

}  // namespace finverse::cfd
