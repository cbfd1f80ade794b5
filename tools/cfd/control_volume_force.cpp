// Control-volume momentum balance for the force on a fixed immersed body; see control_volume_force.hpp.
#include "cfd/control_volume_force.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace finverse::cfd {

namespace {
// Index of the face of axis a nearest to x.
int nearest_face(const Axis& a, double x) {
  const auto& f = a.faces();
  const auto it = std::lower_bound(f.begin(), f.end(), x);
  int k = static_cast<int>(it - f.begin());
  if (k > 0 && (k == a.size() + 1 || x - f[static_cast<std::size_t>(k - 1)] < f[static_cast<std::size_t>(k)] - x)) --k;
  return std::clamp(k, 0, a.size());
}

// Linear interpolation of cell values a (cell wa wide) and b (wb wide) to their common face.
double to_face(double a, double wa, double b, double wb) { return (wb * a + wa * b) / (wa + wb); }
}  // namespace

ControlVolumeForce::ControlVolumeForce(const StretchedGrid& grid, const GhostCellSet& ghosts, double x0, double x1,
                                       double y0, double y1)
    : grid_(grid), ghosts_(&ghosts) {
  if (grid.dim() != 2) throw Error("control volume: 2-D grids only");
  i0_ = nearest_face(grid.axis(0), x0);
  i1_ = nearest_face(grid.axis(0), x1);
  j0_ = nearest_face(grid.axis(1), y0);
  j1_ = nearest_face(grid.axis(1), y1);
  // Faces strictly inside the domain (both neighbours exist) and at least 4 cells across.
  if (i0_ < 1 || j0_ < 1 || i1_ > grid.nx() - 1 || j1_ > grid.ny() - 1 || i1_ - i0_ < 4 || j1_ - j0_ < 4)
    throw Error("control volume: rectangle [" + std::to_string(x0) + ", " + std::to_string(x1) + "] x [" +
                std::to_string(y0) + ", " + std::to_string(y1) + "] must lie inside the domain and span 4 cells");
  // The two layers of cells inside every side and the layer outside must be fluid: the faces'
  // interpolation and differences then use fluid values only.
  const auto check = [&](int i, int j) {
    if (ghosts.solid(i, j))
      throw Error("control volume: the body reaches within two cells of the rectangle's boundary (cell " +
                  std::to_string(i) + ", " + std::to_string(j) + ")");
  };
  for (int i = i0_ - 1; i <= i1_; ++i)
    for (int j : {j0_ - 1, j0_, j0_ + 1, j1_ - 2, j1_ - 1, j1_}) check(i, j);
  for (int j = j0_ - 1; j <= j1_; ++j)
    for (int i : {i0_ - 1, i0_, i0_ + 1, i1_ - 2, i1_ - 1, i1_}) check(i, j);
}

ControlVolumeSample ControlVolumeForce::evaluate(double t, const Field& u, const Field& v, const FaceField& U,
                                                 const Field& p, double nu) const {
  ControlVolumeSample s;
  s.t = t;
  // Fluid momentum, in a fixed order (bitwise reproducible).
  for (int j = j0_; j < j1_; ++j)
    for (int i = i0_; i < i1_; ++i)
      if (ghosts_->kind(i, j) == CellKind::Fluid) {
        const double V = grid_.volume(i, j, 0);
        s.momentum[0] += V * u(i, j, 0);
        s.momentum[1] += V * v(i, j, 0);
      }
  const Field* q[2] = {&u, &v};
  // x faces at i0 (n = -x) and i1 (n = +x): cells (f-1, j) | (f, j).
  for (const int f : {i0_, i1_}) {
    const double sign = f == i0_ ? -1.0 : 1.0;
    const double wa = grid_.dx(f - 1), wb = grid_.dx(f), dist = grid_.xc(f) - grid_.xc(f - 1);
    for (int j = j0_; j < j1_; ++j) {
      const double A = grid_.dy(j);
      const double un = sign * U(0, f, j, 0);
      const double pf = to_face(p(f - 1, j, 0), wa, p(f, j, 0), wb);
      for (int c = 0; c < 2; ++c) {
        const Field& w = *q[c];
        const double wf = to_face(w(f - 1, j, 0), wa, w(f, j, 0), wb);
        const double dwdn = sign * (w(f, j, 0) - w(f - 1, j, 0)) / dist;
        s.flux[static_cast<std::size_t>(c)] += A * (wf * un + (c == 0 ? sign * pf : 0.0) - nu * dwdn);
      }
    }
  }
  // y faces at j0 (n = -y) and j1 (n = +y): cells (i, f-1) | (i, f).
  for (const int f : {j0_, j1_}) {
    const double sign = f == j0_ ? -1.0 : 1.0;
    const double wa = grid_.dy(f - 1), wb = grid_.dy(f), dist = grid_.yc(f) - grid_.yc(f - 1);
    for (int i = i0_; i < i1_; ++i) {
      const double A = grid_.dx(i);
      const double un = sign * U(1, i, f, 0);
      const double pf = to_face(p(i, f - 1, 0), wa, p(i, f, 0), wb);
      for (int c = 0; c < 2; ++c) {
        const Field& w = *q[c];
        const double wf = to_face(w(i, f - 1, 0), wa, w(i, f, 0), wb);
        const double dwdn = sign * (w(i, f, 0) - w(i, f - 1, 0)) / dist;
        s.flux[static_cast<std::size_t>(c)] += A * (wf * un + (c == 1 ? sign * pf : 0.0) - nu * dwdn);
      }
    }
  }
  return s;
}

std::vector<std::array<double, 2>> control_volume_forces(const std::vector<ControlVolumeSample>& s, double rho) {
  const std::size_t n = s.size();
  if (n < 2) throw Error("control volume: need at least two samples for the time derivative");
  std::vector<std::array<double, 2>> F(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t a = k == 0 ? 0 : k - 1, b = k + 1 == n ? k : k + 1;
    const double dt = s[b].t - s[a].t;
    if (!(dt > 0)) throw Error("control volume: sample times must increase");
    for (std::size_t c = 0; c < 2; ++c)
      F[k][c] = -rho * ((s[b].momentum[c] - s[a].momentum[c]) / dt + s[k].flux[c]);
  }
  return F;
}

}  // namespace finverse::cfd
