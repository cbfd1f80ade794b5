// A closed triangulated surface in 3-D and its motion: the body the 3-D sharp-interface immersed
// boundary sees (DESIGN.md section 5.1; Mittal et al. 2008, J. Comput. Phys. 227:4825). A fin is a
// closed thin body around its mid-surface (mesh.h5 /ibm); a rigid or deforming body supplies its
// vertex positions, velocities and accelerations at any time through a SurfaceMotion, with the
// connectivity fixed. The per-triangle force the flow solver integrates from the surface traction
// (SurfaceForces) is what fin-cfd maps onto the mid-surface nodes, so the nodal loads and the force
// coefficients come from one traction and agree.
#pragma once

#include <array>
#include <functional>
#include <utility>
#include <vector>

namespace finverse::cfd {

// Vertices and triangles; triangles are counter-clockwise seen from the fluid (normals into it).
// Usually the fluid is outside (outward normals, positive enclosed volume). With encloses_fluid
// the surface bounds the fluid instead (a pipe, a junction): its normals point inwards, the
// enclosed volume is negative and the solid reaches to infinity; other closed bodies may float
// inside it, oriented outward as usual (docs/studies/pipe_flow.md).
struct TriangulatedSurface {
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<int, 3>> triangles;
  bool encloses_fluid = false;
};

// The same closed surface as the wall of the fluid inside it: every triangle reversed (normals
// into the fluid) and encloses_fluid set.
inline void enclose_fluid(TriangulatedSurface& s) {
  for (auto& t : s.triangles) std::swap(t[1], t[2]);
  s.encloses_fluid = true;
}

// The surface at one instant: positions, and the vertex velocity and acceleration (the no-slip
// datum and the pressure's Neumann datum dp/dn = -a . n are interpolated linearly over a triangle).
struct SurfaceState {
  TriangulatedSurface surface;
  std::vector<std::array<double, 3>> velocity;      // [points.size()]; empty: at rest
  std::vector<std::array<double, 3>> acceleration;  // [points.size()]; empty: zero
};

// A body's motion: its state at time t (the connectivity must not change with t).
using SurfaceMotion = std::function<SurfaceState(double t)>;

// Hydrodynamic force on each triangle of the surface (pressure and viscous parts, from the
// surface traction integrated over the triangle) and their sums [N].
struct SurfaceForces {
  std::vector<std::array<double, 3>> pressure;  // [triangles.size()]
  std::vector<std::array<double, 3>> viscous;   // [triangles.size()]
  std::array<double, 3> pressure_total{}, viscous_total{}, total{};
};

}  // namespace finverse::cfd
