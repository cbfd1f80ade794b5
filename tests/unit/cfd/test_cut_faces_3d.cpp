// Tests of the 3-D cut-cell geometry (cut_faces.hpp, cut_faces_3d.cpp): exact apertures of a box,
// the closure of every cell's fluid part (the apertures' area vectors equal the surface pieces'
// in each cell, for a sphere on a stretched grid and for a box whose faces lie in grid planes),
// and the pieces tiling the surface; the cells a thin body splits into two fluid parts (split_cells).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "cfd/immersed/cut_faces.hpp"
#include "cfd/immersed/surface_shapes.hpp"

namespace finverse::cfd {
namespace {

double overlap3(double a, double b, double lo, double hi) { return std::max(0.0, std::min(b, hi) - std::max(a, lo)); }

// Largest |sum_f (+-) alpha_f A_f e_f - sum of the pieces' area vectors| over the cells, relative
// to the cell's largest face; and the number of cells with pieces.
double worst_closure(const StretchedGrid& g, const CutFaces& cf, const std::vector<SurfacePiece>& pieces, int& cells) {
  std::map<std::array<int, 3>, Vec3> by_cell;
  for (const SurfacePiece& p : pieces) {
    Vec3& a = by_cell[p.cell];
    for (std::size_t q = 0; q < 3; ++q) a[q] += p.area_vector[q];
  }
  double worst = 0;
  cells = 0;
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) {
        const Vec3 piece = by_cell.count({i, j, k}) ? by_cell[{i, j, k}] : Vec3{0, 0, 0};
        cells += by_cell.count({i, j, k}) > 0;
        const double A[3] = {g.dy(j) * g.dz(k), g.dx(i) * g.dz(k), g.dx(i) * g.dy(j)};
        for (int d = 0; d < 3; ++d) {
          int hi[3] = {i, j, k};
          ++hi[d];
          const double faces = (cf.aperture(d, hi[0], hi[1], hi[2]) - cf.aperture(d, i, j, k)) * A[d];
          worst = std::max(worst, std::abs(faces - piece[static_cast<std::size_t>(d)]) / std::max({A[0], A[1], A[2]}));
        }
      }
  return worst;
}

TEST(CutFaces3D, BoxGivesExactAperturesAndClosedCells) {
  const StretchedGrid g(Axis::uniform(0, 1, 10), Axis::stretched(0, 1, 0.3, 0.7, 0.08, 1.1), Axis::uniform(0, 0.5, 6));
  const Vec3 lo{0.23, 0.352, 0.11}, hi{0.61, 0.718, 0.37};
  const SurfaceGeometry box(box_surface(lo, hi));
  const CutFaces cf = cut_faces(g, box);
  int partial = 0;
  for (int d = 0; d < 3; ++d) {
    const int t1 = (d + 1) % 3, t2 = (d + 2) % 3;
    for (int k = 0; k < g.nz() + (d == 2); ++k)
      for (int j = 0; j < g.ny() + (d == 1); ++j)
        for (int i = 0; i < g.nx() + (d == 0); ++i) {
          const int idx[3] = {i, j, k};
          const double c = g.axis(d).face(idx[d]);
          const double a1 = g.axis(t1).face(idx[t1]), b1 = g.axis(t1).face(idx[t1] + 1);
          const double a2 = g.axis(t2).face(idx[t2]), b2 = g.axis(t2).face(idx[t2] + 1);
          const auto D = static_cast<std::size_t>(d), T1 = static_cast<std::size_t>(t1), T2 = static_cast<std::size_t>(t2);
          const double solid = (c > lo[D] && c < hi[D]) ? overlap3(a1, b1, lo[T1], hi[T1]) * overlap3(a2, b2, lo[T2], hi[T2]) : 0;
          const double alpha = 1 - solid / ((b1 - a1) * (b2 - a2));
          ASSERT_NEAR(cf.aperture(d, i, j, k), alpha, 1e-12) << d << ": " << i << ", " << j << ", " << k;
          partial += alpha > 0 && alpha < 1;
        }
  }
  EXPECT_GT(partial, 20);
  int cells = 0;
  EXPECT_LT(worst_closure(g, cf, surface_pieces(g, box), cells), 1e-13);
  EXPECT_GT(cells, 20);
}

TEST(CutFaces3D, BoxInTheGridPlanesClosesEveryCell) {
  // Faces of the box exactly on grid planes (x = 0.3, 0.7; y = 0.2; z = 0.25): the pieces there go
  // to the cell below, and the apertures on those planes see the cross-section just above.
  const StretchedGrid g(Axis::uniform(0, 1, 10), Axis::uniform(0, 1, 10), Axis::uniform(0, 0.5, 10));
  const SurfaceGeometry box(box_surface({0.3, 0.2, 0.1}, {0.7, 0.63, 0.25}));
  const CutFaces cf = cut_faces(g, box);
  int cells = 0;
  EXPECT_LT(worst_closure(g, cf, surface_pieces(g, box), cells), 1e-13);
  EXPECT_GT(cells, 20);
}

TEST(CutFaces3D, BoxThroughTheDomainSidesIsClippedToThem) {
  // A box reaching through both z sides (FlowOptions::surface_crosses): its pieces are the lateral
  // faces inside 0 < z < 0.5 only (the end caps and the parts outside belong to no cell), and every
  // cell still closes, the boundary planes' apertures seeing the cross-section.
  const StretchedGrid g(Axis::uniform(0, 1, 10), Axis::uniform(0, 1, 10), Axis::uniform(0, 0.5, 4));
  const Vec3 lo{0.23, 0.352, -0.2}, hi{0.61, 0.718, 0.7};
  const SurfaceGeometry box(box_surface(lo, hi));
  const CutFaces cf = cut_faces(g, box);
  const std::vector<SurfacePiece> pieces = surface_pieces(g, box);
  double area = 0;
  for (const SurfacePiece& p : pieces) {
    EXPECT_NEAR(p.area_vector[2], 0, 1e-15);
    EXPECT_GE(p.centroid[2], 0);
    EXPECT_LE(p.centroid[2], 0.5);
    area += std::hypot(p.area_vector[0], p.area_vector[1]);
  }
  EXPECT_NEAR(area, 2 * ((hi[0] - lo[0]) + (hi[1] - lo[1])) * 0.5, 1e-12);
  int cells = 0;
  EXPECT_LT(worst_closure(g, cf, pieces, cells), 1e-13);
  EXPECT_GT(cells, 20);
}

TEST(CutFaces3D, SpherePiecesTileTheSurfaceAndCloseEveryCell) {
  const StretchedGrid g(Axis::stretched(0, 1, 0.3, 0.7, 0.05, 1.1), Axis::uniform(0, 1, 20), Axis::uniform(0, 1, 16));
  const SurfaceGeometry sphere(icosphere({0.47, 0.52, 0.49}, 0.19, 3));
  const std::vector<SurfacePiece> pieces = surface_pieces(g, sphere);
  double area = 0, flux = 0, exact_flux = 0;
  // A linear, not divergence-free, field: the pieces integrate it exactly, as the triangles do.
  const auto u = [](const Vec3& x) { return Vec3{0.3 + 2 * x[0] - x[1], -0.2 + x[2], 0.7 + 3 * x[2] + x[0]}; };
  for (const SurfacePiece& p : pieces) {
    area += std::sqrt(p.area_vector[0] * p.area_vector[0] + p.area_vector[1] * p.area_vector[1] +
                      p.area_vector[2] * p.area_vector[2]);
    const Vec3 v = u(p.centroid);
    flux += v[0] * p.area_vector[0] + v[1] * p.area_vector[1] + v[2] * p.area_vector[2];
  }
  const auto& s = sphere.surface();
  for (std::size_t t = 0; t < s.triangles.size(); ++t) {
    const Vec3 &a = s.points[static_cast<std::size_t>(s.triangles[t][0])], &b = s.points[static_cast<std::size_t>(s.triangles[t][1])],
               &c = s.points[static_cast<std::size_t>(s.triangles[t][2])];
    const Vec3 v = u({(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3, (a[2] + b[2] + c[2]) / 3});
    const Vec3& n = sphere.triangle_normal(static_cast<int>(t));
    exact_flux += sphere.triangle_area(static_cast<int>(t)) * (v[0] * n[0] + v[1] * n[1] + v[2] * n[2]);
  }
  EXPECT_NEAR(area, sphere.area(), 1e-12);
  EXPECT_NEAR(flux, exact_flux, 1e-12);
  EXPECT_NEAR(flux, 5 * sphere.volume(), 1e-12);  // divergence of u is 5
  int cells = 0;
  EXPECT_LT(worst_closure(g, cut_faces(g, sphere), pieces, cells), 1e-12);
  EXPECT_GT(cells, 100);
}

// A plate thinner than the cells it crosses: the cells its two faces cross away from the rim hold
// fluid above and below it (two sheets: split); at the rim the fluid wraps around the edge inside
// the cell (one sheet, the faces joined by the side walls' triangles). Each face of box_surface is
// two triangles, so the sheets join pieces across the diagonals too.
TEST(CutFaces3D, SplitCellsAreThoseAPlateCrossesAwayFromItsRim) {
  const StretchedGrid g(Axis::uniform(0, 1, 10), Axis::uniform(0, 1, 10), Axis::uniform(0, 1, 10));
  const SurfaceGeometry plate(box_surface({0.23, 0.31, 0.42}, {0.77, 0.69, 0.47}));
  const std::vector<SurfacePiece> pieces = surface_pieces(g, plate);
  const std::vector<std::array<int, 3>> split = split_cells(pieces, plate);
  std::vector<std::array<int, 3>> expected;
  for (int i = 3; i <= 6; ++i)
    for (int j = 4; j <= 5; ++j) expected.push_back({i, j, 4});
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(split, expected);
  // The same plate on a grid whose planes cut it through the thickness: no cell holds both faces.
  const StretchedGrid fine(Axis::uniform(0, 1, 10), Axis::uniform(0, 1, 10), Axis::uniform(0, 1, 40));
  EXPECT_TRUE(split_cells(surface_pieces(fine, plate), plate).empty());
}

// A body many cells across is crossed by one sheet in every cell, however its triangles fall.
TEST(CutFaces3D, ASphereSplitsNoCell) {
  const StretchedGrid g(Axis::stretched(0, 1, 0.3, 0.7, 0.05, 1.1), Axis::uniform(0, 1, 20), Axis::uniform(0, 1, 16));
  const SurfaceGeometry sphere(icosphere({0.47, 0.52, 0.49}, 0.19, 3));
  const std::vector<SurfacePiece> pieces = surface_pieces(g, sphere);
  std::set<std::array<int, 3>> cells;
  for (const SurfacePiece& p : pieces) cells.insert(p.cell);
  ASSERT_GT(cells.size(), 100u);
  EXPECT_TRUE(split_cells(pieces, sphere).empty());
}

}  // namespace
}  // namespace finverse::cfd
