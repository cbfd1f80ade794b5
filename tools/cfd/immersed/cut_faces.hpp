// Cut-cell face apertures of a 2-D polygon on the stretched Cartesian grid: for every cell face the
// fraction of its length that lies in the fluid (outside the polygon) and the centroid of that
// fluid part. They carry the cut-cell mass balance of Seo & Mittal (2011, J. Comput. Phys.
// 230:7347, section 3) for a moving ghost-cell body (flow_solver.hpp): over the fluid part of a
// cell the incompressibility constraint reads
//     sum_f alpha_f A_f U_f + int_{body in cell} u_B . n dl = 0,
// and the apertures alpha_f change continuously as the body moves, where the cell classification
// (fluid or not, by the cell centre) jumps: the jump is what makes the pressure spike when a cell
// is cleared or covered. For a rigid velocity field u_B (divergence-free and linear in x) the body
// integral equals -sum_f alpha_f A_f u_B(xbar_f) . e_f over the fluid parts of the cell's faces,
// exactly, with xbar_f the fluid part's centroid, so the apertures and centroids are all the mass
// balance needs.
#pragma once

#include "cfd/poisson/face_coefficients.hpp"
#include "cfd/grid/stretched_grid.hpp"
#include "cfd/immersed/immersed_polygon.hpp"
#include "cfd/immersed/surface_geometry.hpp"

#include <vector>

namespace finverse::cfd {

struct CutFaces {
  FaceCoefficients aperture;  // in [0, 1]: 1 all fluid, 0 all inside the body
  // Tangential coordinate (y for an x face, x for a y face) of the fluid part's centroid; the
  // face centre where the face is all fluid or all solid.
  FaceCoefficients centroid;
};

// Apertures of the faces of a 2-D grid against a closed polygon (crossing-number inside test, as
// Polygon::contains). Apertures below 1e-12 are set to 0, so a face that only touches the polygon
// is open and a face that it barely clears is closed.
CutFaces cut_faces(const StretchedGrid& grid, const Polygon& body);
// Several disjoint solid regions (a region with outside = true is solid outside its polygon): the
// fluid aperture is what no region covers. The centroids are left at the face centres (a fixed
// body carries no flux through its surface).
CutFaces cut_faces(const StretchedGrid& grid, const std::vector<SolidRegion>& regions);

// 3-D (cut_faces_3d.cpp): the apertures of a 3-D grid's faces against a closed triangulated
// surface (the centroids are left at the face centres: a deforming body's flux is not that of a
// rigid field, so it is integrated over the surface pieces instead), and the pieces of the surface
// inside each cell: the triangles split by the grid planes, each with its area vector (outward
// normal times area) and centroid. Where the surface lies in a grid plane, a point on the plane
// counts as below it (cells are the half-open boxes (lo, hi]) in both, so that over every cell
//     sum_f (+-) alpha_f A_f e_f = sum over its pieces of the area vectors
// to round-off: the apertures and the pieces close the cell's fluid part.
struct SurfacePiece {
  std::array<int, 3> cell{};
  int triangle = -1;
  Vec3 area_vector{}, centroid{};
  // Bit e set: the piece runs along its triangle's edge e (from vertex e to vertex e + 1 mod 3)
  // for a positive length; the pieces of two triangles meet inside a cell where both run along
  // their shared edge.
  unsigned char edges = 0;
};
CutFaces cut_faces(const StretchedGrid& grid, const SurfaceGeometry& body);
std::vector<SurfacePiece> surface_pieces(const StretchedGrid& grid, const SurfaceGeometry& body);

// The cells that the surface splits (split_cells.cpp): those in which its pieces form two or more
// sheets, joined where they meet along a mesh edge inside the cell. A closed surface crossing a
// cell in one sheet leaves it one fluid part (at the rim of a thin plate the fluid wraps around
// the edge inside the cell); two sheets, the two faces of a plate thinner than the cell, leave
// fluid on both sides, which one mass balance for the cell would join through the body. Sorted.
std::vector<std::array<int, 3>> split_cells(const std::vector<SurfacePiece>& pieces, const SurfaceGeometry& body);

}  // namespace finverse::cfd
