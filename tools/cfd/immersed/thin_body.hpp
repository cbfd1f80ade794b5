// The closed thin body around a deforming fin mid-surface, as the 3-D immersed boundary sees it at
// every instant. Its topology, the placement of a vertex along its node's normal and the
// watertightness check are core/thin_body.hpp's (the construction fin-mesh writes into mesh.h5
// /ibm); this adds what only a moving body needs: the mid-surface vertex normals with their time
// derivatives and the vertex positions, velocities and accelerations they give.
//
// The vertex velocity and acceleration are the exact first and second time derivatives of
// x_v = X_s + offset_sign_v * normal_sign * (thickness / 2) * n_s for given node velocities and
// accelerations (n = N/|N|, N = sum of (b-a) x (c-a), differentiated analytically), so the
// immersed boundary gets the kinematics consistent with the positions.
#pragma once

#include <array>
#include <vector>

#include "cfd/immersed/triangulated_surface.hpp"
#include "core/thin_body.hpp"

namespace finverse::cfd {

using Vec3 = std::array<double, 3>;
using finverse::build_thin_body;
using finverse::check_watertight;
using finverse::ThinBody;

// Area-weighted unit vertex normals (right-hand normals of the triangles) and their first and
// second time derivatives for node velocities v and accelerations a (either may be empty: zero).
struct VertexNormals {
  std::vector<Vec3> n, dn, ddn;
};
VertexNormals vertex_normals(const std::vector<Vec3>& x, const std::vector<Vec3>& v, const std::vector<Vec3>& a,
                             const std::vector<std::array<int, 3>>& triangles);

// The body's surface state for mid-surface node positions x, velocities v and accelerations a
// (v, a may be empty: zero; the state then has empty velocity/acceleration only if both are).
SurfaceState place_thin_body(const ThinBody& body, const std::vector<Vec3>& x, const std::vector<Vec3>& v,
                             const std::vector<Vec3>& a, const std::vector<std::array<int, 3>>& mid_triangles);

}  // namespace finverse::cfd
