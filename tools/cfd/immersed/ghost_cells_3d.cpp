// The 3-D half of the ghost-cell set (ghost_cells.hpp): classification of the cells of a 3-D grid
// against a closed triangulated surface (surface_geometry.hpp), the ghost cells' probes, and the
// trilinear image-point stencils with the boundary-intercept substitution (Mittal et al. 2008,
// J. Comput. Phys. 227:4825, section 2.2, in three dimensions).
#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "cfd/immersed/ghost_cells.hpp"
#include "cfd/parallel/rank_share.hpp"
#include "core/error.hpp"

namespace finverse::cfd {

namespace {
// Index c with centre(c) <= x < centre(c+1), or -1 when x is outside the centres' range. A point
// within rounding (1e-9 of the end cell width) of the first or last centre counts as on it: the
// image point of a ghost cell in the first or last layer of a body that crosses that domain side
// (intercept on a surface normal to the side, e.g. the wall-to-wall cylinder of DFG 3D-1Z) lies
// on the ghost's own centre plane up to the rounding of the closest-point projection.
int lower_centre3(const Axis& a, double x) {
  const int n = a.size();
  if (n < 2) return -1;
  const double first = a.centre(0), last = a.centre(n - 1);
  if (x < first) x = x >= first - 1e-9 * a.width(0) ? first : x;
  if (x > last) x = x <= last + 1e-9 * a.width(n - 1) ? last : x;
  if (x < first || x > last) return -1;
  int lo = 0, hi = n - 1;
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    (a.centre(mid) <= x ? lo : hi) = mid;
  }
  return lo;
}

// Cells whose centres lie in [lo, hi] along an axis: [first, last] (empty when first > last).
std::array<int, 2> centre_range(const Axis& a, double lo, double hi) {
  int first = 0, last = a.size() - 1;
  while (first < a.size() && a.centre(first) < lo) ++first;
  while (last >= 0 && a.centre(last) > hi) --last;
  return {first, last};
}

// First centre index in [first, last] at or above x (last + 1 when none); centres increase.
int first_centre_from(const Axis& a, int first, int last, double x) {
  int lo = first, hi = last + 1;
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if (a.centre(mid) < x) lo = mid + 1;
    else hi = mid;
  }
  return lo;
}

// Marks Solid the centres of box r (inclusive index ranges along x, y, z) that lie inside the
// surface (negative signed distance). Only centres near a triangle get their own closest-point
// query; "near" is inside the triangle's bounding box grown by m, the largest spacing of
// neighbouring centres in the box. Two neighbouring centres that are both far from every
// triangle cannot have the surface between them (a crossing point would lie within m of both,
// so inside some triangle's grown box), so each connected region of far centres is wholly
// inside or wholly outside and one query decides it. For the fin's thin body this cuts the
// queries from every centre of its bounding box to a band a few cells thick. The result is
// that of querying every centre, whatever the thread count.
void mark_solid(const StretchedGrid& grid, const SurfaceGeometry& body, const std::array<std::array<int, 2>, 3>& r,
                std::vector<CellKind>& kind) {
  int n[3];
  for (int d = 0; d < 3; ++d) {
    n[d] = r[static_cast<std::size_t>(d)][1] - r[static_cast<std::size_t>(d)][0] + 1;
    if (n[d] <= 0) return;
  }
  double m = 0;
  for (int d = 0; d < 3; ++d)
    for (int c = r[static_cast<std::size_t>(d)][0]; c < r[static_cast<std::size_t>(d)][1]; ++c)
      m = std::max(m, grid.axis(d).centre(c + 1) - grid.axis(d).centre(c));
  m *= 1 + 1e-9;  // the box test must not lose a centre at distance m to rounding
  const auto box = [&](int a, int b, int c) {
    return static_cast<std::size_t>(a) +
           static_cast<std::size_t>(n[0]) *
               (static_cast<std::size_t>(b) + static_cast<std::size_t>(n[1]) * static_cast<std::size_t>(c));
  };
  const std::size_t total = box(0, 0, n[2]);
  std::vector<unsigned char> done(total, 0);  // near, or already assigned to a far region
  const auto& pts = body.surface().points;
  for (const auto& t : body.surface().triangles) {
    int from[3], to[3];
    bool empty = false;
    for (int d = 0; d < 3; ++d) {
      const auto D = static_cast<std::size_t>(d);
      const double c0 = pts[static_cast<std::size_t>(t[0])][D], c1 = pts[static_cast<std::size_t>(t[1])][D],
                   c2 = pts[static_cast<std::size_t>(t[2])][D];
      const double lo = std::min({c0, c1, c2}) - m, hi = std::max({c0, c1, c2}) + m;
      const Axis& a = grid.axis(d);
      from[d] = first_centre_from(a, r[D][0], r[D][1], lo) - r[D][0];
      to[d] = first_centre_from(a, r[D][0], r[D][1], std::nextafter(hi, hi + 1)) - 1 - r[D][0];
      empty = empty || from[d] > to[d];
    }
    if (empty) continue;
    for (int c = from[2]; c <= to[2]; ++c)
      for (int b = from[1]; b <= to[1]; ++b)
        for (int a = from[0]; a <= to[0]; ++a) done[box(a, b, c)] = 1;
  }
  const auto global = [&](std::size_t q, int& i, int& j, int& k) {
    i = r[0][0] + static_cast<int>(q % static_cast<std::size_t>(n[0]));
    j = r[1][0] + static_cast<int>(q / static_cast<std::size_t>(n[0]) % static_cast<std::size_t>(n[1]));
    k = r[2][0] + static_cast<int>(q / (static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1])));
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(grid.nx()) *
               (static_cast<std::size_t>(j) + static_cast<std::size_t>(grid.ny()) * static_cast<std::size_t>(k));
  };
  const auto inside = [&](int i, int j, int k) {
    return body.closest({grid.xc(i), grid.yc(j), grid.zc(k)}).distance < 0;
  };
  // The centres near the surface, each by its closest point (shared over whole-flow ranks).
  struct NearCentre {
    std::size_t q;
    bool solid;
  };
  std::vector<NearCentre> near;
  for (std::size_t q = 0; q < total; ++q)
    if (done[q]) near.push_back({q, false});
  shared_for_each(near, [&](NearCentre& c) {
    int i, j, k;
    global(c.q, i, j, k);
    c.solid = inside(i, j, k);
  });
  for (const NearCentre& c : near) {
    int i, j, k;
    if (c.solid) kind[global(c.q, i, j, k)] = CellKind::Solid;
  }
  // The far regions, each by a flood fill from its first centre.
  std::vector<std::size_t> stack;
  for (std::size_t seed = 0; seed < total; ++seed) {
    if (done[seed]) continue;
    int i, j, k;
    global(seed, i, j, k);
    const bool solid = inside(i, j, k);
    done[seed] = 1;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const std::size_t q = stack.back();
      stack.pop_back();
      const std::size_t c = global(q, i, j, k);
      if (solid) kind[c] = CellKind::Solid;
      const int a = i - r[0][0], b = j - r[1][0], e = k - r[2][0];
      const auto visit = [&](bool ok, std::size_t nb) {
        if (ok && !done[nb]) {
          done[nb] = 1;
          stack.push_back(nb);
        }
      };
      visit(a > 0, q - 1);
      visit(a + 1 < n[0], q + 1);
      visit(b > 0, q - static_cast<std::size_t>(n[0]));
      visit(b + 1 < n[1], q + static_cast<std::size_t>(n[0]));
      visit(e > 0, q - static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1]));
      visit(e + 1 < n[2], q + static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1]));
    }
  }
}
}  // namespace

GhostCellSet::GhostCellSet(const StretchedGrid& grid, const SurfaceGeometry& body) : grid_(grid) {
  if (grid.dim() != 3) throw Error("immersed boundary: a triangulated body needs a 3-D grid");
  const int nx = grid.nx(), ny = grid.ny(), nz = grid.nz();
  kind_.assign(grid.cells(), CellKind::Fluid);
  const Vec3 lo = body.lower(), hi = body.upper();
  // Only centres inside the surface's bounding box can be inside a body; a surface that encloses
  // the fluid (a pipe) has its solid everywhere outside, so every centre is classified.
  std::array<std::array<int, 2>, 3> r;
  for (int d = 0; d < 3; ++d)
    r[static_cast<std::size_t>(d)] =
        body.encloses_fluid()
            ? std::array<int, 2>{0, grid.axis(d).size() - 1}
            : centre_range(grid.axis(d), lo[static_cast<std::size_t>(d)], hi[static_cast<std::size_t>(d)]);
  const auto index = [&](int i, int j, int k) {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(nx) *
               (static_cast<std::size_t>(j) + static_cast<std::size_t>(ny) * static_cast<std::size_t>(k));
  };
  mark_solid(grid, body, r, kind_);
  const auto fluid = [&](int i, int j, int k) {
    return i >= 0 && j >= 0 && k >= 0 && i < nx && j < ny && k < nz && kind_[index(i, j, k)] == CellKind::Fluid;
  };
  for (int k = std::max(r[2][0], 0); k <= r[2][1]; ++k)
    for (int j = std::max(r[1][0], 0); j <= r[1][1]; ++j)
      for (int i = std::max(r[0][0], 0); i <= r[0][1]; ++i) {
        if (fluid(i, j, k) || !(fluid(i - 1, j, k) || fluid(i + 1, j, k) || fluid(i, j - 1, k) || fluid(i, j + 1, k) ||
                                fluid(i, j, k - 1) || fluid(i, j, k + 1)))
          continue;
        kind_[index(i, j, k)] = CellKind::Ghost;
        GhostCell g;
        g.i = i;
        g.j = j;
        g.k = k;
        ghosts_.push_back(g);
      }
  // Probes and stencils (after the classification is complete), one ghost per item; over the ranks
  // of a whole-flow run each rank computes its share (rank_share.hpp).
  shared_for_each(ghosts_, [&](GhostCell& g) {
    const Vec3 x{grid.xc(g.i), grid.yc(g.j), grid.zc(g.k)};
    const SurfaceHit h = body.closest(x);
    g.intercept = h.point;
    g.normal = h.normal;
    g.triangle = h.triangle;
    g.barycentric = h.barycentric;
    g.boundary.point = {h.point[0], h.point[1]};
    g.boundary.normal = {h.normal[0], h.normal[1]};
    g.boundary.distance = std::min(h.distance, 0.0);
    for (std::size_t d = 0; d < 3; ++d) g.image_point[d] = 2 * h.point[d] - x[d];
    g.image = {g.image_point[0], g.image_point[1]};
    int c0[3];
    for (int d = 0; d < 3; ++d) {
      c0[d] = lower_centre3(grid.axis(d), g.image_point[static_cast<std::size_t>(d)]);
      if (c0[d] < 0)
        throw Error("immersed boundary: the image point of ghost cell (" + std::to_string(g.i) + ", " +
                    std::to_string(g.j) + ", " + std::to_string(g.k) +
                    ") lies outside the grid (body too close to the domain boundary)");
    }
    g.stencil = {c0[0], c0[1]};
    g.stencil_all_fluid = true;
    for (int q = 0; q < 8; ++q)
      g.stencil_all_fluid = g.stencil_all_fluid && fluid(c0[0] + (q & 1), c0[1] + ((q >> 1) & 1), c0[2] + ((q >> 2) & 1));
    g.dirichlet = stencil(g.image_point, g.intercept, g.normal, BoundaryCondition::Dirichlet, {g.i, g.j, g.k});
    g.neumann = stencil(g.image_point, g.intercept, g.normal, BoundaryCondition::Neumann, {g.i, g.j, g.k});
  });
  find_near_wall_faces();
}

// A fluid cell whose centre lies close to the wall (distance delta from it along an axis, the wall
// between the centre and the cell's closed face to a ghost) gets from the ghost's Neumann value a
// cell gradient along that axis of (2 delta / h) times the one of its open face's half: as delta
// -> 0 the cell's velocity no longer feels its own pressure, the projection corrects its open face
// but not its centre, and that pair of cells grew a checkerboard 1.27x per step, whatever the
// step size, in the flap's junction (docs/studies/pipe_flow.md). Such faces are listed here, and
// the cell gradient counts them as closed (zero gradient), as the pressure equation itself does;
// at delta = h/2 both values agree, so the switch is continuous on a plane wall. delta is measured
// on the ghost's tangent plane along the axis; a plane nearly parallel to the axis (n.e <= 0.3)
// counts as close.
void GhostCellSet::find_near_wall_faces() {
  const int nx = grid_.nx(), ny = grid_.ny(), nz = grid_.nz();
  const int size[3] = {nx, ny, nz};
  for (const GhostCell& g : ghosts_) {
    const double xg[3] = {grid_.xc(g.i), grid_.yc(g.j), grid_.zc(g.k)};
    double depth = 0;  // n . (B - G) >= 0: the ghost's distance to its tangent plane
    for (std::size_t e = 0; e < 3; ++e) depth += g.normal[e] * (g.intercept[e] - xg[e]);
    for (int d = 0; d < 3; ++d)
      for (int s = -1; s <= 1; s += 2) {
        std::array<int, 3> c{g.i, g.j, g.k};
        c[static_cast<std::size_t>(d)] += s;
        if (c[static_cast<std::size_t>(d)] < 0 || c[static_cast<std::size_t>(d)] >= size[d] ||
            kind(c[0], c[1], c[2]) != CellKind::Fluid)
          continue;
        const Axis& a = grid_.axis(d);
        const double spacing = std::abs(a.centre(c[static_cast<std::size_t>(d)]) - xg[d]);
        const double ne = s * g.normal[static_cast<std::size_t>(d)];
        if (ne > 0.3 && spacing - depth / ne >= 0.5 * spacing) continue;
        near_wall_.push_back({c, d, -s});
      }
  }
}

// As the 2-D stencil: coordinates centred on x and scaled by the stencil's cell sizes; the image
// value is the first coefficient of the fit, w = V^{-T} e_1 (square, trilinear) or the
// least-squares w = V (V^T V)^{-1} e_1 of the linear fallback.
PointStencil GhostCellSet::stencil(const std::array<double, 3>& x, const std::array<double, 3>& b,
                                   const std::array<double, 3>& n, BoundaryCondition bc, std::array<int, 3> self) const {
  int c0[3];
  double h[3];
  for (int d = 0; d < 3; ++d) {
    const Axis& a = grid_.axis(d);
    c0[d] = lower_centre3(a, x[static_cast<std::size_t>(d)]);
    if (c0[d] < 0) throw Error("immersed boundary: interpolation point outside the grid's cell centres");
    h[d] = a.centre(c0[d] + 1) - a.centre(c0[d]);
  }
  PointStencil st;
  std::array<std::array<double, 3>, 8> xi{};
  bool dropped = false;
  for (int q = 0; q < 8; ++q) {
    const int i = c0[0] + (q & 1), j = c0[1] + ((q >> 1) & 1), k = c0[2] + ((q >> 2) & 1);
    if (kind(i, j, k) == CellKind::Solid || (i == self[0] && j == self[1] && k == self[2])) {
      dropped = true;
      continue;
    }
    const auto m = static_cast<std::size_t>(st.count++);
    st.cell[m] = {i, j, k};
    xi[m] = {(grid_.xc(i) - x[0]) / h[0], (grid_.yc(j) - x[1]) / h[1], (grid_.zc(k) - x[2]) / h[2]};
  }
  const bool use_b = dropped && bc != BoundaryCondition::None;
  const int rows = st.count + (use_b ? 1 : 0);
  const double bx = (b[0] - x[0]) / h[0], by = (b[1] - x[1]) / h[1], bz = (b[2] - x[2]) / h[2];
  const auto fill = [&](int cols) {
    Eigen::MatrixXd V(rows, cols);
    const auto value_row = [&](int r, double X, double Y, double Z) {
      V(r, 0) = 1;
      V(r, 1) = X;
      V(r, 2) = Y;
      V(r, 3) = Z;
      if (cols == 8) {
        V(r, 4) = X * Y;
        V(r, 5) = Y * Z;
        V(r, 6) = X * Z;
        V(r, 7) = X * Y * Z;
      }
    };
    for (int r = 0; r < st.count; ++r) {
      const auto& p = xi[static_cast<std::size_t>(r)];
      value_row(r, p[0], p[1], p[2]);
    }
    if (use_b) {
      const int r = st.count;
      if (bc == BoundaryCondition::Dirichlet) {
        value_row(r, bx, by, bz);
      } else {  // n . grad in physical units: d/dx = (1/hx) d/dxi
        const double nx = n[0] / h[0], ny = n[1] / h[1], nz = n[2] / h[2];
        V(r, 0) = 0;
        V(r, 1) = nx;
        V(r, 2) = ny;
        V(r, 3) = nz;
        if (cols == 8) {
          V(r, 4) = nx * by + ny * bx;
          V(r, 5) = ny * bz + nz * by;
          V(r, 6) = nx * bz + nz * bx;
          V(r, 7) = nx * by * bz + ny * bx * bz + nz * bx * by;
        }
      }
    }
    return V;
  };
  Eigen::VectorXd w;
  bool done = false;
  if (rows == 8) {
    const Eigen::MatrixXd V = fill(8);
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(V.transpose());
    if (lu.isInvertible() && std::abs(lu.determinant()) > 1e-6) {
      Eigen::VectorXd e = Eigen::VectorXd::Zero(8);
      e(0) = 1;
      w = lu.solve(e);
      done = true;
    }
  }
  if (!done) {
    if (rows < 4)
      throw Error("immersed boundary: fewer than four usable interpolation points near (" + std::to_string(x[0]) + ", " +
                  std::to_string(x[1]) + ", " + std::to_string(x[2]) + "); refine the grid around the body");
    const Eigen::MatrixXd V = fill(4);
    const Eigen::Matrix4d N = V.transpose() * V;
    const Eigen::FullPivLU<Eigen::Matrix4d> lu(N);
    if (!lu.isInvertible())
      throw Error("immersed boundary: degenerate interpolation stencil near (" + std::to_string(x[0]) + ", " +
                  std::to_string(x[1]) + ", " + std::to_string(x[2]) + ")");
    w = V * lu.solve(Eigen::Vector4d(1, 0, 0, 0));
  }
  for (int r = 0; r < st.count; ++r) st.weight[static_cast<std::size_t>(r)] = w(r);
  st.boundary_weight = use_b ? w(st.count) : 0.0;
  return st;
}

}  // namespace finverse::cfd
