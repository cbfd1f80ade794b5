// The cut-cell mass balance of the pressure correction (Seo & Mittal 2011, J. Comput. Phys.
// 230:7347, section 3; flow_solver.hpp): which cells carry it, the body's flux through each, and
// the balance's residual. Over the fluid part of a cell,
//     sum_f alpha_f A_f U_f - G_c = 0,     G_c = int_{body in cell} u_B . n dA,
// with the apertures alpha_f of cut_faces.hpp. A rigid 2-D body's G_c is written through the faces'
// fluid parts, G_c = sum_f alpha_f A_f u_B(xbar_f) . e_f (exact for a rigid field); a triangulated
// body's is integrated over its pieces in the cell (u_B linear over each triangle: exact at the
// piece's centroid); a fixed body has none.
#include <algorithm>
#include <cmath>
#include <functional>

#include "cfd/flow/flow_solver.hpp"

namespace finverse::cfd {

std::array<double, 6> polygon_box(const Polygon& p) {
  std::array<double, 6> b{1e300, -1e300, 1e300, -1e300, -1e300, 1e300};
  for (const auto& v : p.vertices()) {
    b[0] = std::min(b[0], v[0]);
    b[1] = std::max(b[1], v[0]);
    b[2] = std::min(b[2], v[1]);
    b[3] = std::max(b[3], v[1]);
  }
  return b;
}

void FlowSolver::place_cut_cells(CutFaces faces, const std::array<double, 6>& box,
                                 const std::vector<std::pair<std::array<int, 3>, double>>& piece_flux,
                                 const std::function<double(int, const Vec3&)>& wall_velocity,
                                 const std::vector<std::array<int, 3>>* split) {
  cut_ = std::move(faces);
  cut_cells_.clear();
  cut_flux_.clear();
  cut_slot_.assign(grid_.cells(), -1);
  const auto flat = [&](int i, int j, int k) {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(grid_.nx()) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(grid_.ny()) * static_cast<std::size_t>(k));
  };
  // The body's flux G_c by cell, accumulated in the order of a full scan.
  std::vector<std::pair<std::size_t, double>> flux;
  // Only the cells of the body's bounding box, one cell wider, can be cut.
  const auto range = [&](int a) {
    const Axis& ax = grid_.axis(a);
    const double lo = box[static_cast<std::size_t>(2 * a)], hi = box[static_cast<std::size_t>(2 * a + 1)];
    int first = 0, last = ax.size() - 1;
    while (first < last && ax.face(first + 1) < lo) ++first;
    while (last > first && ax.face(last) > hi) --last;
    return std::array<int, 2>{std::max(first - 1, 0), std::min(last + 1, ax.size() - 1)};
  };
  const auto rx = range(0), ry = range(1), rz = dim() == 3 ? range(2) : std::array<int, 2>{0, 0};
  // A rigid 2-D body's flux through its piece in a cell, from the faces' fluid parts.
  if (moving_)
    for (int j = ry[0]; j <= ry[1]; ++j)
      for (int i = rx[0]; i <= rx[1]; ++i) {
        // Cells with all faces open or all closed have none (the terms below cancel).
        bool open = false, closed = false;
        for (int d = 0; d < 2; ++d)
          for (int side = 0; side < 2; ++side) {
            const double a = cut_->aperture(d, i + (d == 0 ? side : 0), j + (d == 1 ? side : 0), 0);
            open = open || a > 0;
            closed = closed || a < 1;
          }
        if (!(open && closed)) continue;
        double g = 0;
        for (int d = 0; d < 2; ++d)
          for (int side = 0; side < 2; ++side) {
            int f[3] = {i, j, 0};
            f[d] += side;
            const double alpha = cut_->aperture(d, f[0], f[1], 0);
            if (alpha == 1) continue;  // whole faces: their terms cancel
            const double t = cut_->centroid(d, f[0], f[1], 0);
            const double x = d == 0 ? grid_.axis(0).face(f[0]) : t, y = d == 0 ? t : grid_.axis(1).face(f[1]);
            const double xc = d == 0 ? x : grid_.xc(f[0]), yc = d == 0 ? grid_.yc(f[1]) : y;
            // sum_f alpha u_B(fluid centroid) less sum_f u_B(face centre), which vanishes for a rigid
            // field: only the faces that are not whole contribute.
            const auto v = moving_->velocity(body_state_, x, y), vc = moving_->velocity(body_state_, xc, yc);
            g += (side ? 1.0 : -1.0) * face_area(d, f[0], f[1], 0) *
                 (alpha * v[static_cast<std::size_t>(d)] - vc[static_cast<std::size_t>(d)]);
          }
        if (g != 0) flux.push_back({flat(i, j, 0), g});
      }
  for (const auto& [cell, g] : piece_flux) flux.push_back({flat(cell[0], cell[1], cell[2]), g});
  // A body cell that holds fluid on both sides of the body would join the two through the body in
  // its single balance; it stays closed, as in the staircase balance. The fluid parts of its faces
  // then count as wall: their flux alpha A u_B moves into the neighbours' balances, which keeps
  // each of them consistent with the body's motion and the fluxes' sum unchanged (the closed cell's
  // own flux is dropped). A triangulated surface says which cells it splits (two sheets in the
  // cell: a plate thinner than the cell); a rim cell, whose fluid wraps around the edge, stays open.
  // Without that (a polygon), a body cell with fluid cells on two opposite sides (a body about two
  // cells thick, or its rim) is taken as split.
  std::vector<unsigned char> closed(grid_.cells(), 0);
  std::vector<unsigned char> splits;
  if (split) {
    splits.assign(grid_.cells(), 0);
    for (const auto& c : *split) splits[flat(c[0], c[1], c[2])] = 1;
  }
  for (int k = rz[0]; k <= rz[1]; ++k)
    for (int j = ry[0]; j <= ry[1]; ++j)
      for (int i = rx[0]; i <= rx[1]; ++i) {
        if (fluid(i, j, k)) continue;
        bool both_sides = false;  // fluid on both sides of the body in this cell
        if (split) both_sides = splits[flat(i, j, k)] != 0;
        else
          for (int d = 0; d < dim() && !both_sides; ++d) {
            int lo[3] = {i, j, k}, hi[3] = {i, j, k};
            --lo[d];
            ++hi[d];
            both_sides = lo[d] >= 0 && hi[d] < grid_.n(d) && fluid(lo[0], lo[1], lo[2]) && fluid(hi[0], hi[1], hi[2]);
          }
        if (!both_sides) continue;
        closed[flat(i, j, k)] = 1;
        for (int d = 0; d < dim(); ++d)
          for (int side = 0; side < 2; ++side) {
            int f[3] = {i, j, k};
            f[d] += side;
            if (f[d] == 0 || f[d] == grid_.n(d)) continue;
            double& alpha = cut_->aperture(d, f[0], f[1], f[2]);
            if (alpha == 0) continue;
            Vec3 x{grid_.xc(f[0]), grid_.yc(f[1]), grid_.zc(f[2])};
            x[static_cast<std::size_t>(d)] = grid_.axis(d).face(f[d]);
            const double q = alpha * face_area(d, f[0], f[1], f[2]) * (wall_velocity ? wall_velocity(d, x) : 0.0);
            alpha = 0;
            int n[3] = {i, j, k};
            n[d] += side ? 1 : -1;  // the neighbour across the face: its high face (side 0) or low face
            flux.push_back({flat(n[0], n[1], n[2]), side ? q : -q});
          }
      }
  // A face between two fluid cells stays whole: the momentum equations' cell-centred pressure
  // gradient spans it in full, and a projection whose face weight there differed from it would not
  // be a projection (measured: a box plate heaving in a stream, 3.8 cells thick, blew up within 14
  // steps where its trailing edge cut such faces). The solid part of such a face, which moves with
  // the wall, then counts as fluid of the two cells: its flux (1 - alpha) A u_B moves from the
  // surface pieces' balance to the face's, so both cells still balance the body's motion exactly.
  for (int d = 0; d < dim(); ++d)
    for (int k = rz[0]; k <= rz[1] + (d == 2); ++k)
      for (int j = ry[0]; j <= ry[1] + (d == 1); ++j)
        for (int i = rx[0]; i <= rx[1] + (d == 0); ++i) {
          const int f = d == 0 ? i : d == 1 ? j : k;
          if (f == 0 || f == grid_.n(d)) continue;
          double& alpha = cut_->aperture(d, i, j, k);
          int lo[3] = {i, j, k};
          --lo[d];
          if (alpha == 1 || !fluid(i, j, k) || !fluid(lo[0], lo[1], lo[2])) continue;
          Vec3 x{grid_.xc(i), grid_.yc(j), grid_.zc(k)};
          x[static_cast<std::size_t>(d)] = grid_.axis(d).face(f);
          const double q = (1 - alpha) * face_area(d, i, j, k) * (wall_velocity ? wall_velocity(d, x) : 0.0);
          alpha = 1;
          if (q == 0) continue;
          flux.push_back({flat(lo[0], lo[1], lo[2]), q});
          flux.push_back({flat(i, j, k), -q});
        }
  for (int k = rz[0]; k <= rz[1]; ++k)
    for (int j = ry[0]; j <= ry[1]; ++j)
      for (int i = rx[0]; i <= rx[1]; ++i) {
        bool some = false, partial = false;
        for (int d = 0; d < dim(); ++d)
          for (int side = 0; side < 2; ++side) {
            int f[3] = {i, j, k};
            f[d] += side;
            const double a = cut_->aperture(d, f[0], f[1], f[2]);
            some = some || a > 0;
            partial = partial || a < 1;
          }
        if (some && (partial || ib_->kind(i, j, k) != CellKind::Fluid)) {
          cut_slot_[flat(i, j, k)] = static_cast<int>(cut_cells_.size());
          cut_cells_.push_back({i, j, k});
          cut_flux_.push_back(0.0);
        }
      }
  // A cell with a flux is cut even where all its faces count as whole (a fluid cell between fluid
  // neighbours that the body pokes into): the fluxes add up to the body's net flux, zero, which the
  // pressure equation's solvability needs.
  for (const auto& [c, g] : flux) {
    if (closed[c]) continue;
    int& slot = cut_slot_[c];
    if (slot < 0) {
      slot = static_cast<int>(cut_cells_.size());
      const int i = static_cast<int>(c % static_cast<std::size_t>(grid_.nx()));
      const int j = static_cast<int>((c / static_cast<std::size_t>(grid_.nx())) % static_cast<std::size_t>(grid_.ny()));
      const int k = static_cast<int>(c / (static_cast<std::size_t>(grid_.nx()) * static_cast<std::size_t>(grid_.ny())));
      cut_cells_.push_back({i, j, k});
      cut_flux_.push_back(0.0);
    }
    cut_flux_[static_cast<std::size_t>(slot)] += g;
  }
}

double FlowSolver::cut_balance(std::size_t n, const std::function<double(int, int, int, int)>& U) const {
  const auto [i, j, k] = cut_cells_[n];
  double s = -cut_flux_[n];
  for (int d = 0; d < dim(); ++d)
    for (int side = 0; side < 2; ++side) {
      int f[3] = {i, j, k};
      f[d] += side;
      const double alpha = cut_->aperture(d, f[0], f[1], f[2]);
      if (alpha != 0) s += (side ? 1.0 : -1.0) * alpha * face_area(d, f[0], f[1], f[2]) * U(d, f[0], f[1], f[2]);
    }
  return s;
}

double FlowSolver::continuity_residual(const FaceField& U, int i, int j, int k) const {
  if (!cut_) return divergence(U, i, j, k);
  const int slot = cut_slot_[static_cast<std::size_t>(i) +
                             static_cast<std::size_t>(grid_.nx()) *
                                 (static_cast<std::size_t>(j) + static_cast<std::size_t>(grid_.ny()) * static_cast<std::size_t>(k))];
  if (slot < 0) return divergence(U, i, j, k);
  return cut_balance(static_cast<std::size_t>(slot), [&](int d, int a, int b, int c) { return U(d, a, b, c); }) /
         grid_.volume(i, j, k);
}

bool FlowSolver::cut_cell(int i, int j, int k) const {
  return cut_ && cut_slot_[static_cast<std::size_t>(i) +
                           static_cast<std::size_t>(grid_.nx()) *
                               (static_cast<std::size_t>(j) + static_cast<std::size_t>(grid_.ny()) * static_cast<std::size_t>(k))] >= 0;
}

}  // namespace finverse::cfd
