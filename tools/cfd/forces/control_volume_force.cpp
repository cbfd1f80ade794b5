// Control-volume momentum balance for the force on a fixed immersed body; see control_volume_force.hpp.
#include "cfd/forces/control_volume_force.hpp"

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
    : ControlVolumeForce(grid, ghosts, {x0, x1, y0, y1, 0, 0}) {}

ControlVolumeForce::ControlVolumeForce(const StretchedGrid& grid, const GhostCellSet& ghosts,
                                       const std::array<double, 6>& box)
    : grid_(grid), ghosts_(&ghosts) {
  const int dim = grid.dim();
  if (ghosts.dim() != dim) throw Error("control volume: the ghost cells belong to a grid of another dimension");
  bool ok = true;
  for (int a = 0; a < 3; ++a) {
    const auto A = static_cast<std::size_t>(a);
    if (a >= dim) {
      lo_[A] = 0;
      hi_[A] = 1;
      continue;
    }
    lo_[A] = nearest_face(grid.axis(a), box[2 * A]);
    hi_[A] = nearest_face(grid.axis(a), box[2 * A + 1]);
    // Faces strictly inside the domain (both neighbours exist) and at least 4 cells across.
    ok = ok && lo_[A] >= 1 && hi_[A] <= grid.axis(a).size() - 1 && hi_[A] - lo_[A] >= 4;
  }
  if (!ok) {
    std::string b;
    for (int a = 0; a < dim; ++a)
      b += (a ? " x [" : "[") + std::to_string(box[static_cast<std::size_t>(2 * a)]) + ", " +
           std::to_string(box[static_cast<std::size_t>(2 * a + 1)]) + "]";
    throw Error("control volume: " + b + " must lie inside the domain and span 4 cells along every axis");
  }
  // The two layers of cells inside every side and the layer outside must be fluid: the faces'
  // interpolation and differences then use fluid values only.
  const auto near_side = [&](int a, int c) {
    const auto A = static_cast<std::size_t>(a);
    return a < dim && (c <= lo_[A] + 1 || c >= hi_[A] - 2);
  };
  const int k0 = dim == 3 ? lo_[2] - 1 : 0, k1 = dim == 3 ? hi_[2] : 0;
  for (int k = k0; k <= k1; ++k)
    for (int j = lo_[1] - 1; j <= hi_[1]; ++j)
      for (int i = lo_[0] - 1; i <= hi_[0]; ++i) {
        if (!(near_side(0, i) || near_side(1, j) || near_side(2, k))) continue;
        if (dim == 3 ? ghosts.solid(i, j, k) : ghosts.solid(i, j))
          throw Error("control volume: the body reaches within two cells of the box's boundary (cell " +
                      std::to_string(i) + ", " + std::to_string(j) + (dim == 3 ? ", " + std::to_string(k) : "") + ")");
      }
}

ControlVolumeSample ControlVolumeForce::evaluate(double t, const Field& u, const Field& v, const FaceField& U,
                                                 const Field& p, double nu) const {
  if (grid_.dim() != 2) throw Error("control volume: a 3-D box needs the w velocity");
  return integrate(t, {&u, &v, nullptr}, U, p, nu);
}

ControlVolumeSample ControlVolumeForce::evaluate(double t, const Field& u, const Field& v, const Field& w,
                                                 const FaceField& U, const Field& p, double nu) const {
  return integrate(t, {&u, &v, grid_.dim() == 3 ? &w : nullptr}, U, p, nu);
}

ControlVolumeSample ControlVolumeForce::integrate(double t, const std::array<const Field*, 3>& q, const FaceField& U,
                                                  const Field& p, double nu) const {
  const int dim = grid_.dim();
  ControlVolumeSample s;
  s.t = t;
  // Fluid momentum, in a fixed order (bitwise reproducible).
  for (int k = lo_[2]; k < hi_[2]; ++k)
    for (int j = lo_[1]; j < hi_[1]; ++j)
      for (int i = lo_[0]; i < hi_[0]; ++i)
        if (ghosts_->kind(i, j, k) == CellKind::Fluid) {
          const double V = grid_.volume(i, j, k);
          for (int c = 0; c < dim; ++c)
            s.momentum[static_cast<std::size_t>(c)] += V * (*q[static_cast<std::size_t>(c)])(i, j, k);
        }
  // The faces normal to axis a at lo (n = -e_a) and hi (n = +e_a), each between the cells below
  // and above it along a; t1 < t2 the tangential axes (2-D: t2 = z, one layer).
  for (int a = 0; a < dim; ++a) {
    const auto A = static_cast<std::size_t>(a);
    const int t1 = a == 0 ? 1 : 0, t2 = a == 2 ? 1 : 2;
    const auto T1 = static_cast<std::size_t>(t1), T2 = static_cast<std::size_t>(t2);
    const Axis& ax = grid_.axis(a);
    for (const int f : {lo_[A], hi_[A]}) {
      const double sign = f == lo_[A] ? -1.0 : 1.0;
      const double wa = ax.width(f - 1), wb = ax.width(f), dist = ax.centre_distance(f);
      for (int m2 = lo_[T2]; m2 < hi_[T2]; ++m2)
        for (int m1 = lo_[T1]; m1 < hi_[T1]; ++m1) {
          int below[3], above[3];
          below[a] = f - 1;
          above[a] = f;
          below[t1] = above[t1] = m1;
          below[t2] = above[t2] = m2;
          const double A_f = grid_.axis(t1).width(m1) * (t2 < dim ? grid_.axis(t2).width(m2) : 1.0);
          const double un = sign * U(a, above[0], above[1], above[2]);
          const double pf = to_face(p(below[0], below[1], below[2]), wa, p(above[0], above[1], above[2]), wb);
          for (int c = 0; c < dim; ++c) {
            const Field& w = *q[static_cast<std::size_t>(c)];
            const double lo = w(below[0], below[1], below[2]), hi = w(above[0], above[1], above[2]);
            const double wf = to_face(lo, wa, hi, wb);
            const double dwdn = sign * (hi - lo) / dist;
            s.flux[static_cast<std::size_t>(c)] += A_f * (wf * un + (c == a ? sign * pf : 0.0) - nu * dwdn);
          }
        }
    }
  }
  return s;
}

std::vector<std::array<double, 3>> control_volume_forces(const std::vector<ControlVolumeSample>& s, double rho) {
  const std::size_t n = s.size();
  if (n < 2) throw Error("control volume: need at least two samples for the time derivative");
  std::vector<std::array<double, 3>> F(n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t a = k == 0 ? 0 : k - 1, b = k + 1 == n ? k : k + 1;
    const double dt = s[b].t - s[a].t;
    if (!(dt > 0)) throw Error("control volume: sample times must increase");
    for (std::size_t c = 0; c < 3; ++c)
      F[k][c] = -rho * ((s[b].momentum[c] - s[a].momentum[c]) / dt + s[k].flux[c]);
  }
  return F;
}

}  // namespace finverse::cfd
