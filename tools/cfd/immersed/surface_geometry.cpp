// Closed triangulated surface: validation, bounding-volume hierarchy, closest point and sign; see
// surface_geometry.hpp.
#include "cfd/immersed/surface_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>

#include "core/error.hpp"

namespace finverse::cfd {

namespace {

// Feature of a triangle on which the closest point lies: 0 the interior, 1 + v vertex v, 4 + e the
// edge from vertex e to vertex e + 1 (mod 3).
struct TrianglePoint {
  Vec3 bary{};
  int feature = 0;
};

// Closest point of triangle (a, b, c) to p by the Voronoi regions of its vertices, edges and face,
// tested in that order with dot products of the edge vectors (no square roots, no division unless
// the point projects onto an edge or the face).
TrianglePoint closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return {{1, 0, 0}, 1};
  const Vec3 bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return {{0, 1, 0}, 2};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {{1 - v, v, 0}, 4};
  }
  const Vec3 cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return {{0, 0, 1}, 3};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {{1 - w, 0, w}, 6};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {{0, 1 - w, w}, 5};
  }
  const double den = 1 / (va + vb + vc);
  const double v = vb * den, w = vc * den;
  return {{1 - v - w, v, w}, 0};
}

double box_distance2(const Vec3& x, const Vec3& lo, const Vec3& hi) {
  double s = 0;
  for (int d = 0; d < 3; ++d) {
    const auto D = static_cast<std::size_t>(d);
    const double e = x[D] < lo[D] ? lo[D] - x[D] : x[D] > hi[D] ? x[D] - hi[D] : 0.0;
    s += e * e;
  }
  return s;
}
}  // namespace

SurfaceGeometry::SurfaceGeometry(TriangulatedSurface surface, const std::string& what) : s_(std::move(surface)) {
  const int nv = static_cast<int>(s_.points.size());
  if (s_.triangles.size() < 4 || nv < 4) throw Error(what + ": a closed surface needs at least 4 triangles and 4 vertices");
  // Before the edges: a NaN vertex is not merged with its copies and would read as a hole.
  for (int v = 0; v < nv; ++v)
    for (std::size_t d = 0; d < 3; ++d)
      if (!std::isfinite(s_.points[static_cast<std::size_t>(v)][d]))
        throw Error(what + ": vertex " + std::to_string(v) + " has a coordinate that is not a finite number");
  for (std::size_t t = 0; t < s_.triangles.size(); ++t)
    for (int v : s_.triangles[t])
      if (v < 0 || v >= nv)
        throw Error(what + ": triangle " + std::to_string(t) + " refers to vertex " + std::to_string(v) + " of " +
                    std::to_string(nv));
  // Edges as (lower vertex, higher vertex, triangle, local edge); each must appear exactly twice,
  // once in each direction.
  std::vector<std::tuple<int, int, int, int>> edges;
  edges.reserve(3 * s_.triangles.size());
  for (std::size_t t = 0; t < s_.triangles.size(); ++t)
    for (int e = 0; e < 3; ++e) {
      const int a = s_.triangles[t][static_cast<std::size_t>(e)], b = s_.triangles[t][static_cast<std::size_t>((e + 1) % 3)];
      if (a == b) throw Error(what + ": triangle " + std::to_string(t) + " repeats vertex " + std::to_string(a));
      edges.emplace_back(std::min(a, b), std::max(a, b), static_cast<int>(t), e);
    }
  std::sort(edges.begin(), edges.end());
  edge_triangle_.assign(s_.triangles.size(), {-1, -1, -1});
  for (std::size_t n = 0; n < edges.size();) {
    std::size_t m = n;
    while (m < edges.size() && std::get<0>(edges[m]) == std::get<0>(edges[n]) && std::get<1>(edges[m]) == std::get<1>(edges[n])) ++m;
    const std::string edge = "(" + std::to_string(std::get<0>(edges[n])) + ", " + std::to_string(std::get<1>(edges[n])) + ")";
    if (m - n != 2)
      throw Error(what + ": edge " + edge + " is shared by " + std::to_string(m - n) +
                  " triangles (not watertight: every edge needs exactly two)");
    const auto [lo, hi, t0, e0] = edges[n];
    const auto [lo1, hi1, t1, e1] = edges[n + 1];
    const auto first = [&](int t, int e) { return s_.triangles[static_cast<std::size_t>(t)][static_cast<std::size_t>(e)]; };
    if (first(t0, e0) == first(t1, e1))
      throw Error(what + ": triangles " + std::to_string(t0) + " and " + std::to_string(t1) +
                  " are not consistently oriented across edge " + edge);
    edge_triangle_[static_cast<std::size_t>(t0)][static_cast<std::size_t>(e0)] = t1;
    edge_triangle_[static_cast<std::size_t>(t1)][static_cast<std::size_t>(e1)] = t0;
    n = m;
  }
  compute_normals(what);
  build();
}

void SurfaceGeometry::move_to(const std::vector<Vec3>& points) {
  if (points.size() != s_.points.size())
    throw Error("triangulated surface: moved to " + std::to_string(points.size()) + " vertices, the surface has " +
                std::to_string(s_.points.size()));
  s_.points = points;
  compute_normals("moved triangulated surface");
  build();
}

void SurfaceGeometry::compute_normals(const std::string& what) {
  const std::size_t nt = s_.triangles.size();
  face_normal_.assign(nt, Vec3{});
  face_area_.assign(nt, 0.0);
  vertex_normal_.assign(s_.points.size(), Vec3{});
  Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  Vec3 hi{-lo[0], -lo[1], -lo[2]};
  for (const Vec3& p : s_.points) {
    if (!std::isfinite(p[0] + p[1] + p[2])) throw Error(what + ": a vertex is not finite");
    for (std::size_t d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], p[d]);
      hi[d] = std::max(hi[d], p[d]);
    }
  }
  const double scale = norm(sub(hi, lo));
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = s_.triangles[t];
    const Vec3& a = s_.points[static_cast<std::size_t>(tri[0])];
    const Vec3& b = s_.points[static_cast<std::size_t>(tri[1])];
    const Vec3& c = s_.points[static_cast<std::size_t>(tri[2])];
    const Vec3 n = cross(sub(b, a), sub(c, a));
    const double len = norm(n);
    if (!(len > 1e-14 * scale * scale)) throw Error(what + ": triangle " + std::to_string(t) + " is degenerate (zero area)");
    face_area_[t] = 0.5 * len;
    face_normal_[t] = {n[0] / len, n[1] / len, n[2] / len};
    // Angle-weighted vertex pseudo-normals.
    const std::array<const Vec3*, 3> v{&a, &b, &c};
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3 e1 = sub(*v[(k + 1) % 3], *v[k]), e2 = sub(*v[(k + 2) % 3], *v[k]);
      const double angle = std::acos(std::clamp(dot(e1, e2) / (norm(e1) * norm(e2)), -1.0, 1.0));
      Vec3& vn = vertex_normal_[static_cast<std::size_t>(tri[k])];
      for (std::size_t d = 0; d < 3; ++d) vn[d] += angle * face_normal_[t][d];
    }
  }
  if (s_.encloses_fluid && !(volume() < 0))
    throw Error(what + ": the surface encloses the fluid, but its enclosed volume is not negative (triangles must be "
                       "counter-clockwise seen from the fluid inside)");
  if (!s_.encloses_fluid && !(volume() > 0))
    throw Error(what + ": the enclosed volume is not positive (triangles must be counter-clockwise seen from outside)");
}

double SurfaceGeometry::volume() const {
  double v = 0;
  for (const auto& tri : s_.triangles)
    v += dot(s_.points[static_cast<std::size_t>(tri[0])],
             cross(s_.points[static_cast<std::size_t>(tri[1])], s_.points[static_cast<std::size_t>(tri[2])]));
  return v / 6;
}

double SurfaceGeometry::area() const {
  double a = 0;
  for (double x : face_area_) a += x;
  return a;
}

void SurfaceGeometry::build() {
  const std::size_t nt = s_.triangles.size();
  std::vector<Vec3> centroid(nt);
  for (std::size_t t = 0; t < nt; ++t)
    for (std::size_t d = 0; d < 3; ++d)
      centroid[t][d] = (s_.points[static_cast<std::size_t>(s_.triangles[t][0])][d] +
                        s_.points[static_cast<std::size_t>(s_.triangles[t][1])][d] +
                        s_.points[static_cast<std::size_t>(s_.triangles[t][2])][d]) / 3;
  order_.resize(nt);
  for (std::size_t t = 0; t < nt; ++t) order_[t] = static_cast<int>(t);
  nodes_.clear();
  nodes_.reserve(2 * nt + 1);
  build_node(0, static_cast<int>(nt), centroid);
}

int SurfaceGeometry::build_node(int first, int count, const std::vector<Vec3>& centroid) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.emplace_back();
  Node node;
  node.lo = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  node.hi = {-node.lo[0], -node.lo[1], -node.lo[2]};
  Vec3 clo = node.lo, chi = node.hi;
  for (int n = first; n < first + count; ++n) {
    const int t = order_[static_cast<std::size_t>(n)];
    for (int v : s_.triangles[static_cast<std::size_t>(t)])
      for (std::size_t d = 0; d < 3; ++d) {
        node.lo[d] = std::min(node.lo[d], s_.points[static_cast<std::size_t>(v)][d]);
        node.hi[d] = std::max(node.hi[d], s_.points[static_cast<std::size_t>(v)][d]);
      }
    for (std::size_t d = 0; d < 3; ++d) {
      clo[d] = std::min(clo[d], centroid[static_cast<std::size_t>(t)][d]);
      chi[d] = std::max(chi[d], centroid[static_cast<std::size_t>(t)][d]);
    }
  }
  if (count <= 4) {
    node.first = first;
    node.count = count;
    nodes_[static_cast<std::size_t>(id)] = node;
    return id;
  }
  std::size_t axis = 0;
  for (std::size_t d = 1; d < 3; ++d)
    if (chi[d] - clo[d] > chi[axis] - clo[axis]) axis = d;
  const int half = count / 2;
  auto* base = order_.data() + first;
  std::nth_element(base, base + half, base + count, [&](int a, int b) {
    const double ca = centroid[static_cast<std::size_t>(a)][axis], cb = centroid[static_cast<std::size_t>(b)][axis];
    return ca < cb || (ca == cb && a < b);
  });
  node.left = build_node(first, half, centroid);
  node.right = build_node(first + half, count - half, centroid);
  nodes_[static_cast<std::size_t>(id)] = node;
  return id;
}

SurfaceHit SurfaceGeometry::closest(const Vec3& x) const {
  double best = std::numeric_limits<double>::infinity();
  int best_t = -1;
  TrianglePoint best_p;
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& nd = nodes_[static_cast<std::size_t>(stack[--top])];
    if (box_distance2(x, nd.lo, nd.hi) >= best) continue;
    if (nd.left < 0) {
      for (int n = nd.first; n < nd.first + nd.count; ++n) {
        const int t = order_[static_cast<std::size_t>(n)];
        const auto& tri = s_.triangles[static_cast<std::size_t>(t)];
        const Vec3& a = s_.points[static_cast<std::size_t>(tri[0])];
        const Vec3& b = s_.points[static_cast<std::size_t>(tri[1])];
        const Vec3& c = s_.points[static_cast<std::size_t>(tri[2])];
        const TrianglePoint tp = closest_on_triangle(x, a, b, c);
        Vec3 q{};
        for (std::size_t d = 0; d < 3; ++d) q[d] = tp.bary[0] * a[d] + tp.bary[1] * b[d] + tp.bary[2] * c[d];
        const Vec3 e = sub(x, q);
        const double d2 = dot(e, e);
        if (d2 < best || (d2 == best && t < best_t)) {
          best = d2;
          best_t = t;
          best_p = tp;
        }
      }
      continue;
    }
    // Nearer child last on the stack, so it is searched first.
    const Node& l = nodes_[static_cast<std::size_t>(nd.left)];
    const Node& r = nodes_[static_cast<std::size_t>(nd.right)];
    const bool left_first = box_distance2(x, l.lo, l.hi) <= box_distance2(x, r.lo, r.hi);
    stack[top++] = left_first ? nd.right : nd.left;
    stack[top++] = left_first ? nd.left : nd.right;
  }
  SurfaceHit h;
  h.triangle = best_t;
  h.barycentric = best_p.bary;
  const auto& tri = s_.triangles[static_cast<std::size_t>(best_t)];
  for (std::size_t d = 0; d < 3; ++d)
    for (std::size_t k = 0; k < 3; ++k) h.point[d] += best_p.bary[k] * s_.points[static_cast<std::size_t>(tri[k])][d];
  const std::size_t T = static_cast<std::size_t>(best_t);
  Vec3 pseudo;
  if (best_p.feature == 0) {
    pseudo = face_normal_[T];
  } else if (best_p.feature <= 3) {
    pseudo = vertex_normal_[static_cast<std::size_t>(tri[static_cast<std::size_t>(best_p.feature - 1)])];
  } else {
    const std::size_t e = static_cast<std::size_t>(best_p.feature - 4);
    const Vec3& other = face_normal_[static_cast<std::size_t>(edge_triangle_[T][e])];
    pseudo = {face_normal_[T][0] + other[0], face_normal_[T][1] + other[1], face_normal_[T][2] + other[2]};
  }
  const Vec3 e = sub(x, h.point);
  const double dist = std::sqrt(best);
  const double scale = norm(sub(nodes_[0].hi, nodes_[0].lo));
  if (dist <= 1e-13 * scale) {  // on the surface: outside, with the triangle's normal
    h.normal = face_normal_[T];
    h.distance = 0;
    return h;
  }
  const double sign = dot(e, pseudo) < 0 ? -1.0 : 1.0;
  h.distance = sign * dist;
  h.normal = {sign * e[0] / dist, sign * e[1] / dist, sign * e[2] / dist};
  return h;
}

Vec3 SurfaceGeometry::interpolate(const std::vector<Vec3>& data, const SurfaceHit& hit) const {
  Vec3 out{};
  if (data.empty()) return out;
  const auto& tri = s_.triangles[static_cast<std::size_t>(hit.triangle)];
  for (std::size_t k = 0; k < 3; ++k)
    for (std::size_t d = 0; d < 3; ++d) out[d] += hit.barycentric[k] * data[static_cast<std::size_t>(tri[k])][d];
  return out;
}

}  // namespace finverse::cfd
