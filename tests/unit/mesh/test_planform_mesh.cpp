// Planform mesh quality (DESIGN.md section 5.2, seed paper Fig. 9): minimum angle, size bound,
// every ray segment is a chain of mesh edges, root nodes on x = 0, mesh area equals the outline
// area; and the closed IBM surface: watertight, outward, free of self-intersections.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "mesh/ibm_surface.hpp"
#include "mesh/planform_mesher.hpp"
#include "mesh/structural_mesh.hpp"

using namespace finverse;
using namespace finverse::mesh;

namespace {

struct Fixture : ::testing::Test {
  static void SetUpTestSuite() {
    fin = new FinTemplate(make_caudal_fin({}));
    pm = new PlanformMesh(mesh_planform(*fin, {}));
  }
  static void TearDownTestSuite() {
    delete pm;
    delete fin;
  }
  static FinTemplate* fin;
  static PlanformMesh* pm;
};
FinTemplate* Fixture::fin = nullptr;
PlanformMesh* Fixture::pm = nullptr;

double tri_area(const PlanformMesh& m, const std::array<int, 3>& t) {
  const auto &a = m.points[t[0]], &b = m.points[t[1]], &c = m.points[t[2]];
  return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
}

// Distance from p to the polyline.
double polyline_distance(const std::vector<Point2>& pl, const Point2& p) {
  double best = 1e300;
  for (std::size_t i = 0; i + 1 < pl.size(); ++i) {
    const double dx = pl[i + 1][0] - pl[i][0], dz = pl[i + 1][1] - pl[i][1];
    const double u = std::clamp(((p[0] - pl[i][0]) * dx + (p[1] - pl[i][1]) * dz) / (dx * dx + dz * dz), 0.0, 1.0);
    best = std::min(best, std::hypot(p[0] - pl[i][0] - u * dx, p[1] - pl[i][1] - u * dz));
  }
  return best;
}

}  // namespace

TEST_F(Fixture, MinimumAngleAndSize) {
  EXPECT_GE(pm->min_angle_deg, 25.0 - 1e-9);
  double recomputed = 180, longest = 0;
  for (const auto& t : pm->triangles) {
    recomputed = std::min(recomputed, min_angle_deg(pm->points[t[0]], pm->points[t[1]], pm->points[t[2]]));
    for (int k = 0; k < 3; ++k) {
      const auto &a = pm->points[t[k]], &b = pm->points[t[(k + 1) % 3]];
      longest = std::max(longest, std::hypot(a[0] - b[0], a[1] - b[1]));
    }
  }
  EXPECT_DOUBLE_EQ(recomputed, pm->min_angle_deg);
  EXPECT_GE(recomputed, 25.0 - 1e-9);
  EXPECT_LE(longest, 0.04 * fin->chord * (1 + 1e-9));
  EXPECT_GT(pm->triangles.size(), 1000u);  // the size bound forced real refinement
}

TEST_F(Fixture, TrianglesCounterClockwiseAndAreaEqualsOutline) {
  double area = 0;
  for (const auto& t : pm->triangles) {
    EXPECT_GT(tri_area(*pm, t), 0);
    area += tri_area(*pm, t);
  }
  EXPECT_NEAR(area, fin->area(), 1e-12 * fin->area());
}

TEST_F(Fixture, EveryRaySegmentIsAMeshEdge) {
  std::set<std::pair<int, int>> edges;
  for (const auto& t : pm->triangles)
    for (int k = 0; k < 3; ++k) edges.insert({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
  ASSERT_EQ(pm->ray_nodes.size(), fin->ray_count());
  for (std::size_t r = 0; r < fin->ray_count(); ++r) {
    const auto& chain = pm->ray_nodes[r];
    ASSERT_GE(chain.size(), fin->rays[r].points.size());  // refinement only adds nodes
    for (std::size_t k = 0; k + 1 < chain.size(); ++k)
      EXPECT_TRUE(edges.count({std::min(chain[k], chain[k + 1]), std::max(chain[k], chain[k + 1])}))
          << "ray " << r + 1 << " segment " << k;
    // The chain runs root to tip along the ray polyline.
    for (int d = 0; d < 2; ++d) {  // up to the rounding of the mesher's chord units
      EXPECT_NEAR(pm->points[chain.front()][d], fin->rays[r].points.front()[d], 1e-17);
      EXPECT_NEAR(pm->points[chain.back()][d], fin->rays[r].points.back()[d], 1e-17);
    }
    for (int n : chain) EXPECT_LT(polyline_distance(fin->rays[r].points, pm->points[n]), 1e-12);
    const auto& s = pm->ray_node_s[r];
    for (std::size_t k = 1; k < s.size(); ++k) EXPECT_GT(s[k], s[k - 1]);
    EXPECT_DOUBLE_EQ(s.back(), 1.0);
  }
}

TEST_F(Fixture, StructuralMeshBeamsRootsAndSections) {
  const auto ibm = build_ibm_surface(*pm, 0.05 * fin->chord);
  const auto m = assemble_mesh(*fin, *pm, ibm, 0.0);
  // Root nodes: exactly the nodes on x = 0, including every ray root.
  std::set<int> roots(m.root_nodes.data.begin(), m.root_nodes.data.end());
  for (std::size_t i = 0; i < pm->points.size(); ++i)
    EXPECT_EQ(roots.count(static_cast<int>(i)) == 1, std::abs(pm->points[i][0]) < 1e-12) << "node " << i;
  for (const auto& chain : pm->ray_nodes) EXPECT_TRUE(roots.count(chain.front()));
  // Beams: ray numbers 1..20, sections from the template at each end, thickest at the root.
  const std::size_t nb = m.beam_ray.size();
  for (std::size_t b = 0; b < nb; ++b) {
    const int ray = m.beam_ray(b);
    ASSERT_GE(ray, 1);
    ASSERT_LE(ray, 20);
    EXPECT_LT(m.beam_s(b, 0), m.beam_s(b, 1));
    EXPECT_GT(m.beam_thickness(b, 0), m.beam_thickness(b, 1));
    EXPECT_DOUBLE_EQ(m.beam_thickness(b, 1), fin->section(ray - 1, m.beam_s(b, 1)).thickness);
  }
  // A root band of 10% chord (the paper's prescribed region) holds more nodes, all with x <= 0.1 c.
  const auto band = root_nodes(*fin, *pm, 0.1 * fin->chord);
  EXPECT_GT(band.size(), roots.size());
  for (int n : band) EXPECT_LE(pm->points[n][0], 0.1 * fin->chord + 1e-12);
}

TEST_F(Fixture, IbmSurfaceClosedOutwardNoSelfIntersection) {
  const double h = 0.05 * fin->chord;
  const auto ibm = build_ibm_surface(*pm, h);
  const auto c = check_surface(ibm.points, ibm.body.triangles);
  EXPECT_TRUE(c.closed);
  EXPECT_FALSE(c.self_intersecting);
  EXPECT_TRUE(c.outward);
  // A prism of the planform: volume area * h, surface 2 area + perimeter * h.
  double perimeter = 0;
  const auto poly = fin->outline();
  for (std::size_t i = 0; i < poly.size(); ++i)
    perimeter += std::hypot(poly[(i + 1) % poly.size()][0] - poly[i][0], poly[(i + 1) % poly.size()][1] - poly[i][1]);
  EXPECT_NEAR(c.volume, fin->area() * h, 1e-9 * fin->area() * h);
  EXPECT_NEAR(c.area, 2 * fin->area() + perimeter * h, 1e-9 * c.area);
  // Each vertex is its node offset by exactly offset_sign * h/2 along y; the rim vertices are
  // exactly the outline nodes, one each.
  std::vector<int> rim(pm->points.size(), 0);
  for (std::size_t i = 0; i < ibm.points.size(); ++i) {
    const int src = ibm.body.source_node[i];
    EXPECT_EQ(ibm.points[i][0], pm->points[src][0]);
    EXPECT_EQ(ibm.points[i][1], 0.5 * h * ibm.body.offset_sign[i]);
    EXPECT_EQ(ibm.points[i][2], pm->points[src][1]);
    if (ibm.body.offset_sign[i] == 0) ++rim[src];
  }
  for (std::size_t n = 0; n < rim.size(); ++n) EXPECT_EQ(rim[n], pm->on_boundary[n] ? 1 : 0) << "node " << n;
  EXPECT_NO_THROW(check_watertight(ibm.body.triangles, static_cast<int>(ibm.points.size()), "ibm"));
}

TEST(IbmSurfaceCheck, DetectsOpenAndSelfIntersectingSurfaces) {
  // A tetrahedron is closed; drop a face and it is open; push a vertex through and it intersects.
  std::vector<std::array<double, 3>> p{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  std::vector<std::array<int, 3>> t{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  auto c = check_surface(p, t);
  EXPECT_TRUE(c.closed);
  EXPECT_FALSE(c.self_intersecting);
  EXPECT_TRUE(c.outward);
  EXPECT_NEAR(c.volume, 1.0 / 6, 1e-12);
  auto open = t;
  open.pop_back();
  EXPECT_FALSE(check_surface(p, open).closed);
  // Two triangles crossing each other (not sharing vertices).
  std::vector<std::array<double, 3>> q{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, -1}, {0.5, 0.5, 1}, {3, 3, 0}};
  std::vector<std::array<int, 3>> u{{0, 1, 2}, {3, 4, 5}};
  EXPECT_TRUE(check_surface(q, u).self_intersecting);
}

TEST(PlanformMesher, FinerSizeGivesMoreElementsAtTheSameQuality) {
  const auto fin = make_caudal_fin({});
  PlanformMeshOptions o;
  o.max_edge_over_chord = 0.08;
  const auto coarse = mesh_planform(fin, o);
  o.max_edge_over_chord = 0.03;
  const auto fine = mesh_planform(fin, o);
  EXPECT_GT(fine.triangles.size(), 2 * coarse.triangles.size());
  EXPECT_GE(coarse.min_angle_deg, 25.0 - 1e-9);
  EXPECT_GE(fine.min_angle_deg, 25.0 - 1e-9);
}
