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

#include "cfd/face_coefficients.hpp"
#include "cfd/grid.hpp"
#include "cfd/immersed_polygon.hpp"

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

}  // namespace finverse::cfd
