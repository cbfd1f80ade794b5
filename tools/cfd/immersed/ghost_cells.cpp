// Ghost-cell classification, probes and image-point stencils; see ghost_cells.hpp.
#include "cfd/immersed/ghost_cells.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "core/error.hpp"

namespace finverse::cfd {

namespace {
// Index c with centre(c) <= x < centre(c+1), or -1 when x is outside the centres' range.
int lower_centre(const Axis& a, double x) {
  const int n = a.size();
  if (n < 2 || x < a.centre(0) || x > a.centre(n - 1)) return -1;
  int lo = 0, hi = n - 1;  // centre(lo) <= x <= centre(hi)
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    (a.centre(mid) <= x ? lo : hi) = mid;
  }
  return lo;
}
}  // namespace

GhostCellSet::GhostCellSet(const StretchedGrid& grid, const Polygon& body)
    : GhostCellSet(grid, std::vector<SolidRegion>{SolidRegion{body, false}}) {}

GhostCellSet::GhostCellSet(const StretchedGrid& grid, const std::vector<SolidRegion>& regions) : grid_(grid) {
  classify(regions, regions, false);
}

GhostCellSet::GhostCellSet(const StretchedGrid& grid, const Polygon& body, const Polygon& kinds_from) : grid_(grid) {
  classify({SolidRegion{kinds_from, false}}, {SolidRegion{body, false}}, true);
}

void GhostCellSet::classify(const std::vector<SolidRegion>& kinds_from, const std::vector<SolidRegion>& regions,
                            bool frozen) {
  const StretchedGrid& grid = grid_;
  if (grid.dim() != 2) throw Error("immersed boundary: the polygon body needs a 2-D grid");
  if (regions.empty() || kinds_from.empty()) throw Error("immersed boundary: no solid region given");
  const int nx = grid.nx(), ny = grid.ny();
  kind_.assign(grid.cells(), CellKind::Fluid);
  // The crossing-number test is O(vertices) per cell; a centre outside a polygon's bounding box
  // (widened by a round-off margin) is outside it, so only the box's cells are tested. Every
  // coupling iteration of a moving body re-classifies (docs/studies/fsi_step_cost.md).
  for (const SolidRegion& r : kinds_from) {
    const std::array<double, 4> b = r.polygon.bounds();
    const double margin = 1e-9 * std::max(b[2] - b[0], b[3] - b[1]);
    const auto in_box = [&](double x, double y) {
      return x >= b[0] - margin && x <= b[2] + margin && y >= b[1] - margin && y <= b[3] + margin;
    };
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const double x = grid.xc(i), y = grid.yc(j);
        if (in_box(x, y) ? r.contains(x, y) : r.outside) kind_[static_cast<std::size_t>(i + nx * j)] = CellKind::Solid;
      }
  }
  const auto closest = [&](double x, double y) {
    SurfacePoint best = regions.front().closest(x, y);
    for (std::size_t r = 1; r < regions.size(); ++r) {
      const SurfacePoint s = regions[r].closest(x, y);
      if (std::abs(s.distance) < std::abs(best.distance)) best = s;
    }
    return best;
  };
  const auto fluid = [&](int i, int j) {
    return i >= 0 && j >= 0 && i < nx && j < ny && kind_[static_cast<std::size_t>(i + nx * j)] == CellKind::Fluid;
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (fluid(i, j) || !(fluid(i - 1, j) || fluid(i + 1, j) || fluid(i, j - 1) || fluid(i, j + 1))) continue;
      kind_[static_cast<std::size_t>(i + nx * j)] = CellKind::Ghost;
      GhostCell g;
      g.i = i;
      g.j = j;
      const double x = grid.xc(i), y = grid.yc(j);
      g.boundary = closest(x, y);
      g.image = {2 * g.boundary.point[0] - x, 2 * g.boundary.point[1] - y};
      if (frozen && g.boundary.distance > 0) {  // G midway between B and I
        g.image = {2 * x - g.boundary.point[0], 2 * y - g.boundary.point[1]};
        g.probe = g.boundary.distance;
      }
      const int i0 = lower_centre(grid.axis(0), g.image[0]), j0 = lower_centre(grid.axis(1), g.image[1]);
      if (i0 < 0 || j0 < 0)
        throw Error("immersed boundary: the image point of ghost cell (" + std::to_string(i) + ", " + std::to_string(j) +
                    ") lies outside the grid (body too close to the domain boundary)");
      g.stencil = {i0, j0};
      const double tx = (g.image[0] - grid.xc(i0)) / (grid.xc(i0 + 1) - grid.xc(i0));
      const double ty = (g.image[1] - grid.yc(j0)) / (grid.yc(j0 + 1) - grid.yc(j0));
      g.weights = {(1 - tx) * (1 - ty), tx * (1 - ty), (1 - tx) * ty, tx * ty};
      g.intercept = {g.boundary.point[0], g.boundary.point[1], 0.0};
      g.normal = {g.boundary.normal[0], g.boundary.normal[1], 0.0};
      g.image_point = {g.image[0], g.image[1], 0.0};
      ghosts_.push_back(g);
    }
  // Stencil fluidity is known only after every cell is classified.
  for (GhostCell& g : ghosts_) {
    const int i0 = g.stencil[0], j0 = g.stencil[1];
    g.stencil_all_fluid = fluid(i0, j0) && fluid(i0 + 1, j0) && fluid(i0, j0 + 1) && fluid(i0 + 1, j0 + 1);
    g.dirichlet = stencil(g.image, g.boundary, BoundaryCondition::Dirichlet, {g.i, g.j});
    g.neumann = stencil(g.image, g.boundary, BoundaryCondition::Neumann, {g.i, g.j});
    if (g.probe >= 0) {
      // Written in the form phi_G = 2 phi_B - S(phi, phi_B) that every user of the Dirichlet
      // stencil applies: S = 3/2 phi_B - phi_I / 2 gives phi_G = (phi_B + phi_I) / 2.
      for (int n = 0; n < g.dirichlet.count; ++n) g.dirichlet.weight[static_cast<std::size_t>(n)] *= -0.5;
      g.dirichlet.boundary_weight = 1.5 - 0.5 * g.dirichlet.boundary_weight;
    }
  }
}

// The fit is done in coordinates centred on x and scaled by the stencil's size, so the
// Vandermonde matrix is O(1); the image value is the interpolant at the origin, i.e. the first
// entry of the coefficient vector: w = V^{-T} e_1 (square, bilinear) or the least-squares
// w = V (V^T V)^{-1} e_1 (linear fallback).
PointStencil GhostCellSet::stencil(const std::array<double, 2>& x, const SurfacePoint& b, BoundaryCondition bc,
                                   std::array<int, 2> self) const {
  const int i0 = lower_centre(grid_.axis(0), x[0]), j0 = lower_centre(grid_.axis(1), x[1]);
  if (i0 < 0 || j0 < 0) throw Error("immersed boundary: interpolation point outside the grid's cell centres");
  const double hx = grid_.xc(i0 + 1) - grid_.xc(i0), hy = grid_.yc(j0 + 1) - grid_.yc(j0);
  PointStencil st;
  std::array<std::array<double, 2>, 4> xi{};
  bool dropped = false;
  for (int b2 = 0; b2 < 2; ++b2)
    for (int a = 0; a < 2; ++a) {
      const int i = i0 + a, j = j0 + b2;
      const CellKind k = kind(i, j);
      const bool is_self = i == self[0] && j == self[1];
      if (k == CellKind::Solid || is_self) {
        dropped = true;
        continue;
      }
      const auto n = static_cast<std::size_t>(st.count++);
      st.cell[n] = {i, j, 0};
      xi[n] = {(grid_.xc(i) - x[0]) / hx, (grid_.yc(j) - x[1]) / hy};
    }
  const bool use_b = dropped && bc != BoundaryCondition::None;
  const int rows = st.count + (use_b ? 1 : 0);
  const double bx = (b.point[0] - x[0]) / hx, by = (b.point[1] - x[1]) / hy;
  const auto fill = [&](int cols) {
    Eigen::MatrixXd V(rows, cols);
    for (int r = 0; r < st.count; ++r) {
      const auto& p = xi[static_cast<std::size_t>(r)];
      V(r, 0) = 1;
      V(r, 1) = p[0];
      V(r, 2) = p[1];
      if (cols == 4) V(r, 3) = p[0] * p[1];
    }
    if (use_b) {
      const int r = st.count;
      if (bc == BoundaryCondition::Dirichlet) {
        V(r, 0) = 1;
        V(r, 1) = bx;
        V(r, 2) = by;
        if (cols == 4) V(r, 3) = bx * by;
      } else {  // n . grad in physical units: d/dx = (1/hx) d/dxi
        const double nx = b.normal[0] / hx, ny = b.normal[1] / hy;
        V(r, 0) = 0;
        V(r, 1) = nx;
        V(r, 2) = ny;
        if (cols == 4) V(r, 3) = nx * by + ny * bx;
      }
    }
    return V;
  };
  Eigen::VectorXd w;
  bool done = false;
  if (rows == 4) {
    const Eigen::MatrixXd V = fill(4);
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(V.transpose());
    // Invertible and not nearly so (two points almost coinciding, e.g. B on top of a node).
    if (lu.isInvertible() && std::abs(lu.determinant()) > 1e-6) {
      w = lu.solve(Eigen::Vector4d(1, 0, 0, 0));
      done = true;
    }
  }
  if (!done) {
    if (rows < 3)
      throw Error("immersed boundary: fewer than three usable interpolation points near (" + std::to_string(x[0]) +
                  ", " + std::to_string(x[1]) + "); refine the grid around the body");
    const Eigen::MatrixXd V = fill(3);
    const Eigen::Matrix3d N = V.transpose() * V;
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(N);
    if (!lu.isInvertible())
      throw Error("immersed boundary: degenerate interpolation stencil near (" + std::to_string(x[0]) + ", " +
                  std::to_string(x[1]) + ")");
    w = V * lu.solve(Eigen::Vector3d(1, 0, 0));
  }
  for (int r = 0; r < st.count; ++r) st.weight[static_cast<std::size_t>(r)] = w(r);
  st.boundary_weight = use_b ? w(st.count) : 0.0;
  return st;
}

namespace {
// Gauss-Seidel sweeps over the ghost list in its fixed order (deterministic) until the largest
// change is below a relative 1e-14 of the field's scale near the body.
template <class Rule>
void sweep(const std::vector<GhostCell>& ghosts, Field& q, Rule rule) {
  for (int it = 0; it < 200; ++it) {
    double change = 0, scale = 0;
    for (std::size_t n = 0; n < ghosts.size(); ++n) {
      const GhostCell& g = ghosts[n];
      const double v = rule(n, g);
      change = std::max(change, std::abs(v - q(g.i, g.j, g.k)));
      scale = std::max(scale, std::abs(v));
      q(g.i, g.j, g.k) = v;
    }
    if (change <= 1e-14 * std::max(scale, 1e-300)) return;
  }
}
}  // namespace

void GhostCellSet::impose_dirichlet(Field& q, const std::vector<double>& boundary_value) const {
  sweep(ghosts_, q, [&](std::size_t n, const GhostCell& g) {
    const double ub = boundary_value.empty() ? 0.0 : boundary_value[n];
    return 2 * ub - g.dirichlet.apply(q, ub);
  });
}

void GhostCellSet::impose_neumann(Field& q) const {
  sweep(ghosts_, q, [&](std::size_t, const GhostCell& g) { return g.neumann.apply(q, 0.0); });
}

void GhostCellSet::impose_neumann(Field& q, const std::vector<double>& normal_derivative) const {
  if (normal_derivative.empty()) return impose_neumann(q);
  sweep(ghosts_, q, [&](std::size_t n, const GhostCell& g) {
    const double dn = normal_derivative[n];
    return g.neumann.apply(q, dn) - g.probe_length() * dn;
  });
}

void GhostCellSet::fill_solid(Field& q, double value) const {
  for (int k = 0; k < grid_.nz(); ++k)
    for (int j = 0; j < grid_.ny(); ++j)
      for (int i = 0; i < grid_.nx(); ++i)
        if (kind(i, j, k) == CellKind::Solid) q(i, j, k) = value;
}

double GhostCellSet::image_value(const Field& q, const GhostCell& g) const {
  if (grid_.dim() == 3) {
    int c0[3];
    double t[3];
    for (int d = 0; d < 3; ++d) {
      const Axis& a = grid_.axis(d);
      c0[d] = lower_centre(a, g.image_point[static_cast<std::size_t>(d)]);
      t[d] = (g.image_point[static_cast<std::size_t>(d)] - a.centre(c0[d])) / (a.centre(c0[d] + 1) - a.centre(c0[d]));
    }
    double s = 0;
    for (int n = 0; n < 8; ++n) {
      const int a = n & 1, b = (n >> 1) & 1, c = (n >> 2) & 1;
      s += (a ? t[0] : 1 - t[0]) * (b ? t[1] : 1 - t[1]) * (c ? t[2] : 1 - t[2]) * q(c0[0] + a, c0[1] + b, c0[2] + c);
    }
    return s;
  }
  const int i0 = g.stencil[0], j0 = g.stencil[1];
  return g.weights[0] * q(i0, j0, 0) + g.weights[1] * q(i0 + 1, j0, 0) + g.weights[2] * q(i0, j0 + 1, 0) +
         g.weights[3] * q(i0 + 1, j0 + 1, 0);
}

}  // namespace finverse::cfd
