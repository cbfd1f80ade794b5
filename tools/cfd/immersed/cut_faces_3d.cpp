// Cut-cell geometry of a closed triangulated surface on the 3-D grid (see cut_faces.hpp): the fluid
// aperture of every face and the pieces of the surface inside every cell.
//
// One convention makes the two consistent where the surface touches a grid plane x_d = c: a point
// with x_d <= c counts as below the plane (as if the plane sat at c + 0). Cells are then the
// half-open boxes (lo, hi], a surface piece lying in a plane belongs to the cell below it, and the
// cross-section of the body seen by the faces on that plane is the one just above it.
//
// Apertures: the surface is sliced by each grid plane through its bounding box; each triangle that
// crosses the plane gives a segment, oriented along e_d x n so that the body's cross-section lies
// on its left, and the segments close into the cross-section's outline. The solid area of a face
// [a1, b1] x [a2, b2] follows from Green's theorem, area = closed integral of (t1 - a1) dt2 around
// the part of the cross-section inside the face: the outline clipped to the face, plus the face's
// right edge where it runs inside the cross-section (the other edges contribute nothing), whose
// inside length comes from the outline's crossings with that grid line.
//
// Pieces: every triangle is split by the grid planes it spans, x then y then z, into convex
// polygons, each within one cell; a piece carries its area vector, its centroid and the edges of
// its triangle it runs along (tracked through the splits: a split's new edge lies in the plane).
#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

#include "cfd/immersed/cut_faces.hpp"
#include "cfd/immersed/vec3.hpp"

namespace finverse::cfd {

namespace {

using Poly = std::vector<Vec3>;


// The point where edge a -> b meets x_d = c (a and b on opposite sides).
Vec3 on_plane(const Vec3& a, const Vec3& b, int d, double c) {
  const auto D = static_cast<std::size_t>(d);
  const double t = (c - a[D]) / (b[D] - a[D]);
  Vec3 p{a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
  p[D] = c;
  return p;
}

// Cell index along an axis under the (lo, hi] convention, clamped to the grid.
int cell_of(const Axis& ax, double x) {
  const auto& f = ax.faces();
  const int i = static_cast<int>(std::lower_bound(f.begin(), f.end(), x) - f.begin()) - 1;
  return std::clamp(i, 0, ax.size() - 1);
}

// Splits a convex polygon by x_d = c into its parts below (x_d <= c) and above. Each vertex
// carries the label of the edge that starts at it (the triangle edge it runs along, or -1 for a
// cut by an earlier plane); the new edge along the plane is a cut.
void split(const Poly& p, const std::vector<int>& label, int d, double c, Poly& below, std::vector<int>& below_label,
           Poly& above, std::vector<int>& above_label) {
  below.clear();
  above.clear();
  below_label.clear();
  above_label.clear();
  const auto D = static_cast<std::size_t>(d);
  for (std::size_t k = 0; k < p.size(); ++k) {
    const Vec3& a = p[k];
    const Vec3& b = p[(k + 1) % p.size()];
    const bool a_up = a[D] > c, b_up = b[D] > c;
    (a_up ? above : below).push_back(a);
    (a_up ? above_label : below_label).push_back(label[k]);
    if (a_up != b_up) {
      const Vec3 q = on_plane(a, b, d, c);
      // On a's side the edge from q runs along the plane; on b's side it continues towards b.
      (a_up ? above : below).push_back(q);
      (a_up ? above_label : below_label).push_back(-1);
      (a_up ? below : above).push_back(q);
      (a_up ? below_label : above_label).push_back(label[k]);
    }
  }
}

struct Segment {
  double p1, p2, q1, q2;  // tangential coordinates (t1, t2) of the start and the end
};

}  // namespace

CutFaces cut_faces(const StretchedGrid& g, const SurfaceGeometry& body) {
  CutFaces cf{FaceCoefficients(g, 1.0), FaceCoefficients(g, 0.0)};
  const auto& pts = body.surface().points;
  const auto& tris = body.surface().triangles;
  const Vec3 lo = body.lower(), hi = body.upper();
  for (int d = 0; d < 3; ++d) {
    const int t1 = (d + 1) % 3, t2 = (d + 2) % 3;
    const auto D = static_cast<std::size_t>(d), T1 = static_cast<std::size_t>(t1), T2 = static_cast<std::size_t>(t2);
    const Axis& ax = g.axis(d);
    const Axis& a1 = g.axis(t1);
    const Axis& a2 = g.axis(t2);
    // The faces normal to d are indexed (i, j, k) with the d-th index the plane; the tangential
    // indices m1 (along t1) and m2 (along t2) map to (i, j, k) by axis.
    const auto face_index = [&](int plane, int m1, int m2) {
      int idx[3];
      idx[d] = plane;
      idx[t1] = m1;
      idx[t2] = m2;
      return std::array<int, 3>{idx[0], idx[1], idx[2]};
    };
    std::vector<Segment> segs;
    std::unordered_map<long, double> solid;  // face (m1, m2) on the current plane -> solid area
    for (int f = 0; f <= ax.size(); ++f) {
      const double c = ax.face(f);
      if (c < lo[D] || c > hi[D]) continue;
      segs.clear();
      for (std::size_t t = 0; t < tris.size(); ++t) {
        const Vec3* v[3] = {&pts[static_cast<std::size_t>(tris[t][0])], &pts[static_cast<std::size_t>(tris[t][1])],
                            &pts[static_cast<std::size_t>(tris[t][2])]};
        const bool up[3] = {(*v[0])[D] > c, (*v[1])[D] > c, (*v[2])[D] > c};
        if (up[0] == up[1] && up[1] == up[2]) continue;
        Vec3 e[2];
        int m = 0;
        for (int k = 0; k < 3 && m < 2; ++k)
          if (up[k] != up[(k + 1) % 3]) e[m++] = on_plane(*v[k], *v[(k + 1) % 3], d, c);
        // Orientation along e_d x n (n the triangle's normal): the cross-section on the left.
        const Vec3 n = body.triangle_normal(static_cast<int>(t));
        const double s1 = -n[T2], s2 = n[T1];
        Segment s{e[0][T1], e[0][T2], e[1][T1], e[1][T2]};
        if ((s.q1 - s.p1) * s1 + (s.q2 - s.p2) * s2 < 0) s = {e[1][T1], e[1][T2], e[0][T1], e[0][T2]};
        segs.push_back(s);
      }
      if (segs.empty()) continue;
      solid.clear();
      const long n1 = a1.size();
      // The outline inside each face: integral of (t1 - a1) dt2 along the clipped segments.
      for (const Segment& s : segs) {
        const int i0 = cell_of(a1, std::min(s.p1, s.q1)), i1 = cell_of(a1, std::max(s.p1, s.q1));
        const int j0 = cell_of(a2, std::min(s.p2, s.q2)), j1 = cell_of(a2, std::max(s.p2, s.q2));
        for (int j = std::max(j0 - 1, 0); j <= std::min(j1 + 1, a2.size() - 1); ++j)
          for (int i = std::max(i0 - 1, 0); i <= std::min(i1 + 1, a1.size() - 1); ++i) {
            const double x0 = a1.face(i), x1 = a1.face(i + 1), y0 = a2.face(j), y1 = a2.face(j + 1);
            double u0 = 0, u1 = 1;  // Liang-Barsky
            const double dx = s.q1 - s.p1, dy = s.q2 - s.p2;
            const double P[4] = {-dx, dx, -dy, dy}, Q[4] = {s.p1 - x0, x1 - s.p1, s.p2 - y0, y1 - s.p2};
            bool out = false;
            for (int k = 0; k < 4 && !out; ++k) {
              if (P[k] == 0) {
                out = Q[k] < 0;
                continue;
              }
              const double r = Q[k] / P[k];
              if (P[k] < 0) u0 = std::max(u0, r);
              else u1 = std::min(u1, r);
            }
            if (out || u1 <= u0) continue;
            const double um = 0.5 * (u0 + u1);
            const double contribution = (s.p1 + um * dx - x0) * (u1 - u0) * dy;
            if (contribution != 0) solid[i + n1 * j] += contribution;
          }
      }
      // The right edge t1 = a1.face(i + 1) of each face where it runs inside the cross-section.
      double smin = 1e300, smax = -1e300;
      for (const Segment& s : segs) {
        smin = std::min({smin, s.p1, s.q1});
        smax = std::max({smax, s.p1, s.q1});
      }
      std::vector<double> cr;
      for (int i = 0; i < a1.size(); ++i) {
        const double x = a1.face(i + 1);
        if (x < smin || x > smax) continue;
        cr.clear();
        for (const Segment& s : segs)
          if ((s.p1 <= x) != (s.q1 <= x)) cr.push_back(s.p2 + (x - s.p1) / (s.q1 - s.p1) * (s.q2 - s.p2));
        std::sort(cr.begin(), cr.end());
        const double w = a1.width(i);
        for (std::size_t q = 0; q + 1 < cr.size(); q += 2)
          for (int j = cell_of(a2, cr[q]); j < a2.size() && a2.face(j) < cr[q + 1]; ++j) {
            const double len = std::min(cr[q + 1], a2.face(j + 1)) - std::max(cr[q], a2.face(j));
            if (len > 0) solid[i + n1 * j] += w * len;
          }
      }
      for (const auto& [key, area] : solid) {
        const int i = static_cast<int>(key % n1), j = static_cast<int>(key / n1);
        const double alpha = 1 - area / (a1.width(i) * a2.width(j));
        const auto id = face_index(f, i, j);
        cf.aperture(d, id[0], id[1], id[2]) = alpha < 1e-12 ? 0.0 : std::min(alpha, 1.0);
      }
    }
  }
  return cf;
}

std::vector<SurfacePiece> surface_pieces(const StretchedGrid& g, const SurfaceGeometry& body) {
  std::vector<SurfacePiece> out;
  const auto& pts = body.surface().points;
  const auto& tris = body.surface().triangles;
  // Each polygon with its cell indices along the axes split so far: a piece's cell is where the
  // splitting put it, not where its centroid's rounding falls (a piece in a grid plane belongs to
  // the cell below it).
  struct Part {
    Poly p;
    std::vector<int> label;  // label[k]: the triangle edge that p[k] -> p[k + 1] runs along, or -1
    std::array<int, 3> cell{};
  };
  std::vector<Part> cur, next;
  Poly below, above;
  std::vector<int> below_label, above_label;
  for (std::size_t t = 0; t < tris.size(); ++t) {
    cur.assign(1, Part{Poly{pts[static_cast<std::size_t>(tris[t][0])], pts[static_cast<std::size_t>(tris[t][1])],
                            pts[static_cast<std::size_t>(tris[t][2])]},
                       {0, 1, 2},
                       {}});
    for (int d = 0; d < 3; ++d) {
      const auto D = static_cast<std::size_t>(d);
      const Axis& ax = g.axis(d);
      next.clear();
      for (Part& part : cur) {
        double mn = 1e300, mx = -1e300;
        for (const Vec3& v : part.p) {
          mn = std::min(mn, v[D]);
          mx = std::max(mx, v[D]);
        }
        // A surface that reaches through the domain's sides (FlowOptions::surface_crosses) is
        // clipped to the domain: the parts outside belong to no cell (cell_of would lump them
        // into the outermost one). The cut edge is no mesh edge (label -1).
        Part rest{std::move(part.p), std::move(part.label), part.cell};
        if (mn < ax.face(0)) {
          split(rest.p, rest.label, d, ax.face(0), below, below_label, above, above_label);
          rest.p = above;
          rest.label = above_label;
          mn = ax.face(0);
        }
        if (mx > ax.face(ax.size()) && rest.p.size() >= 3) {
          split(rest.p, rest.label, d, ax.face(ax.size()), below, below_label, above, above_label);
          rest.p = below;
          rest.label = below_label;
          mx = ax.face(ax.size());
        }
        if (rest.p.size() < 3) continue;
        // Interior planes between the cells of the lowest and the highest point.
        const int c0 = cell_of(ax, mn), c1 = cell_of(ax, mx);
        for (int c = c0; c < c1; ++c) {
          split(rest.p, rest.label, d, ax.face(c + 1), below, below_label, above, above_label);
          if (below.size() >= 3) {
            next.push_back(Part{below, below_label, rest.cell});
            next.back().cell[D] = c;
          }
          rest.p = above;
          rest.label = above_label;
        }
        rest.cell[D] = c1;
        if (rest.p.size() >= 3) next.push_back(std::move(rest));
      }
      std::swap(cur, next);
    }
    // An edge shorter than this is a point where a vertex lay on a plane (round-off of the split).
    double longest = 0;
    for (int e = 0; e < 3; ++e) {
      const Vec3 a = sub(pts[static_cast<std::size_t>(tris[t][static_cast<std::size_t>((e + 1) % 3)])],
                         pts[static_cast<std::size_t>(tris[t][static_cast<std::size_t>(e)])]);
      longest = std::max(longest, std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]));
    }
    const double tiny = 1e-9 * longest;
    for (const Part& part : cur) {
      const Poly& p = part.p;
      // Area vector and centroid by a fan from the first vertex.
      Vec3 av{0, 0, 0}, cen{0, 0, 0};
      double wsum = 0;
      for (std::size_t k = 1; k + 1 < p.size(); ++k) {
        const Vec3 a = cross(sub(p[k], p[0]), sub(p[k + 1], p[0]));
        const double w = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        for (std::size_t q = 0; q < 3; ++q) {
          av[q] += 0.5 * a[q];
          cen[q] += w * (p[0][q] + p[k][q] + p[k + 1][q]) / 3;
        }
        wsum += w;
      }
      if (!(wsum > 0)) continue;
      for (double& x : cen) x /= wsum;
      unsigned char edges = 0;
      for (std::size_t k = 0; k < p.size(); ++k) {
        if (part.label[k] < 0) continue;
        const Vec3 e = sub(p[(k + 1) % p.size()], p[k]);
        if (std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]) > tiny)
          edges = static_cast<unsigned char>(edges | (1u << part.label[k]));
      }
      out.push_back(SurfacePiece{part.cell, static_cast<int>(t), av, cen, edges});
    }
  }
  return out;
}

}  // namespace finverse::cfd
