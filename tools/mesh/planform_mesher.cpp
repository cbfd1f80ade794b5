// CGAL constrained Delaunay meshing of the fin planform with every ray as a constrained polyline
// (seed paper section 4.1: "20 beams" on a shell; DESIGN.md section 5.2: beams and shells share
// nodes). The only CGAL-heavy translation unit of the planform path; it works in chord units so
// the criteria are scale-free and converts back to metres on the way out.
#include "mesh/planform_mesher.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <numbers>
#include <sstream>
#include <string>

#include "core/error.hpp"
#include "core/machine_memory.hpp"

namespace finverse::mesh {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Delaunay_mesh_vertex_base_2<K>;
using Fb = CGAL::Delaunay_mesh_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// No intersection tag: validate() has already ruled out crossing constraints, and CGAL throws
// rather than silently inventing intersection points if one slipped through.
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<CDT>;
using VH = CDT::Vertex_handle;

double angle_at(const Point2& p, const Point2& q, const Point2& r) {
  const double ux = q[0] - p[0], uz = q[1] - p[1], vx = r[0] - p[0], vz = r[1] - p[1];
  return std::atan2(std::abs(ux * vz - uz * vx), ux * vx + uz * vz);
}

// Follows the constrained edges from `from` to `to` (two consecutive polyline points). Refinement
// may have split the segment; the split points lie on it, so at each step the next node is the
// constrained neighbour that advances furthest towards `to` while staying on the segment.
std::vector<VH> walk_constraint(const CDT& cdt, VH from, VH to) {
  const auto a = from->point(), b = to->point();
  const double dx = b.x() - a.x(), dz = b.y() - a.y();
  const double len2 = dx * dx + dz * dz;
  std::vector<VH> chain{from};
  VH cur = from;
  double t_cur = 0;
  while (cur != to) {
    VH best;
    double t_best = 2;
    auto ec = cdt.incident_edges(cur), done = ec;
    do {
      if (cdt.is_infinite(ec) || !cdt.is_constrained(*ec)) continue;
      const auto f = ec->first;
      const int i = ec->second;
      VH w = f->vertex(CDT::cw(i)) == cur ? f->vertex(CDT::ccw(i)) : f->vertex(CDT::cw(i));
      const double px = w->point().x() - a.x(), pz = w->point().y() - a.y();
      const double t = (px * dx + pz * dz) / len2;
      const double off = std::abs(px * dz - pz * dx) / std::sqrt(len2);
      if (off < 1e-9 && t > t_cur + 1e-12 && t < t_best) {
        t_best = t;
        best = w;
      }
    } while (++ec != done);
    if (best == VH() || t_best > 1 + 1e-9)
      throw Error("fin-mesh: internal: lost a ray constraint while collecting its mesh edges");
    chain.push_back(best);
    cur = best;
    t_cur = t_best;
  }
  return chain;
}

}  // namespace

double min_angle_deg(const Point2& a, const Point2& b, const Point2& c) {
  const double m = std::min({angle_at(a, b, c), angle_at(b, c, a), angle_at(c, a, b)});
  return m * 180.0 / std::numbers::pi;
}

PlanformMesh mesh_planform(const FinTemplate& t, const PlanformMeshOptions& o) {
  if (!(o.min_angle_deg > 0 && o.min_angle_deg <= 33)) {
    std::ostringstream what;
    what << "--min-angle " << o.min_angle_deg << ": expected more than 0 and at most 33 degrees";
    throw Error(what.str());
  }
  if (!(o.max_edge_over_chord > 0)) throw Error("--max-edge: expected > 0 chords");
  validate(t);
  const double c = t.chord;
  {
    // Triangles of edge a cover about 0.25 a^2 each (equilateral: 0.43 a^2); about 2 KiB each
    // through CGAL's triangulation, the IBM body and its self-intersection tree.
    const double triangles = t.area() / (c * c) / (0.25 * o.max_edge_over_chord * o.max_edge_over_chord);
    std::ostringstream what;
    what << "--max-edge " << o.max_edge_over_chord << ": about " << std::setprecision(3) << triangles << " triangles";
    require_memory(2048 * triangles, what.str());
  }

  CDT cdt;
  auto to_cgal = [&](const Point2& p) { return K::Point_2(p[0] / c, p[1] / c); };
  // Rays first (their vertex handles are the anchors of the beam chains), then the outline pieces
  // that are not rays: the root segment through all roots and the trailing edge through all tips.
  std::vector<std::vector<VH>> ray_handles(t.rays.size());
  try {
    for (std::size_t r = 0; r < t.rays.size(); ++r) {
      for (const auto& p : t.rays[r].points) ray_handles[r].push_back(cdt.insert(to_cgal(p)));
      for (std::size_t i = 0; i + 1 < ray_handles[r].size(); ++i)
        cdt.insert_constraint(ray_handles[r][i], ray_handles[r][i + 1]);
    }
    for (std::size_t r = 0; r + 1 < t.rays.size(); ++r) {
      cdt.insert_constraint(ray_handles[r].front(), ray_handles[r + 1].front());
      cdt.insert_constraint(ray_handles[r].back(), ray_handles[r + 1].back());
    }
    const double s = std::sin(o.min_angle_deg * std::numbers::pi / 180.0);
    CGAL::refine_Delaunay_mesh_2(cdt, Criteria(s * s, o.max_edge_over_chord));
  } catch (const std::exception& e) {
    throw Error("fin-mesh: CGAL rejected the planform constraints (crossing rays?): " + std::string(e.what()));
  }

  PlanformMesh m;
  std::map<VH, int> index;
  auto node = [&](VH v) {
    auto [it, fresh] = index.emplace(v, static_cast<int>(m.points.size()));
    if (fresh) m.points.push_back({v->point().x() * c, v->point().y() * c});
    return it->second;
  };
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->is_in_domain()) continue;
    m.triangles.push_back({node(f->vertex(0)), node(f->vertex(1)), node(f->vertex(2))});
  }
  if (m.triangles.empty()) throw Error("fin-mesh: the planform has no interior (degenerate outline)");

  // Outline nodes: on an edge that only one in-domain triangle uses.
  std::map<std::pair<int, int>, int> edge_use;
  m.min_angle_deg = 180;
  for (const auto& tri : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      const int a = tri[k], b = tri[(k + 1) % 3];
      ++edge_use[{std::min(a, b), std::max(a, b)}];
      m.max_edge = std::max(m.max_edge, std::hypot(m.points[a][0] - m.points[b][0], m.points[a][1] - m.points[b][1]));
    }
    m.min_angle_deg = std::min(m.min_angle_deg, min_angle_deg(m.points[tri[0]], m.points[tri[1]], m.points[tri[2]]));
  }
  m.on_boundary.assign(m.points.size(), 0);
  for (const auto& [e, n] : edge_use)
    if (n == 1) m.on_boundary[e.first] = m.on_boundary[e.second] = 1;

  for (std::size_t r = 0; r < t.rays.size(); ++r) {
    std::vector<int> chain{node(ray_handles[r].front())};
    for (std::size_t i = 0; i + 1 < ray_handles[r].size(); ++i) {
      const auto piece = walk_constraint(cdt, ray_handles[r][i], ray_handles[r][i + 1]);
      for (std::size_t k = 1; k < piece.size(); ++k) chain.push_back(node(piece[k]));
    }
    std::vector<double> s(chain.size(), 0.0);
    for (std::size_t k = 1; k < chain.size(); ++k)
      s[k] = s[k - 1] + std::hypot(m.points[chain[k]][0] - m.points[chain[k - 1]][0],
                                   m.points[chain[k]][1] - m.points[chain[k - 1]][1]);
    for (auto& v : s) v /= s.back();
    m.ray_nodes.push_back(std::move(chain));
    m.ray_node_s.push_back(std::move(s));
  }
  if (index.size() != m.points.size() || m.points.size() != cdt.number_of_vertices())
    throw Error("fin-mesh: internal: mesh nodes outside the planform");

  if (m.min_angle_deg < o.min_angle_deg - 1e-6)
    throw Error("fin-mesh: the mesher reached a smallest angle of " + std::to_string(m.min_angle_deg) +
                " degrees, below the requested " + std::to_string(o.min_angle_deg) +
                " (a sharp corner in the planform?); lower --min-angle or fix the template");
  return m;
}

}  // namespace finverse::mesh
