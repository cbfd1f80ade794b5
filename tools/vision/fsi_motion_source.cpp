// The FSI motion source (issue 33, Deliver 1): affine binding of the render surface to the mesh's
// mid-surface triangles and periodic cubic Hermite interpolation in time (fsi_motion_source.hpp).
#include "vision/fsi_motion_source.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/error.hpp"
#include "core/stage_files.hpp"
#include "core/stage_identity.hpp"
#include "mesh/motion_transfer.hpp"

namespace finverse::vision {
namespace {

using V3 = std::array<double, 3>;
V3 sub(const V3& a, const V3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const V3& a, const V3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V3 cross(const V3& a, const V3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
V3 unit(const V3& a) {
  const double n = std::sqrt(dot(a, a));
  return n > 0 ? V3{a[0] / n, a[1] / n, a[2] / n} : V3{0, 0, 0};
}
V3 row(const NdArray<double>& a, std::size_t i) { return {a(i, 0), a(i, 1), a(i, 2)}; }

double wrap(double t, double T) {
  const double p = std::fmod(t, T);
  return p < 0 ? p + T : p;
}

}  // namespace

FsiMotion::FsiMotion(FsiSamples s, const FinSurface& surface) : label_(s.label), source_(s.source), period_(s.period) {
  const auto fail = [&](const std::string& what) { throw Error(label_ + ": " + what); };
  if (!(std::isfinite(period_) && period_ > 0)) fail("period T must be > 0");
  if (s.rest.rank() != 2 || s.rest.dim(1) != 3) fail("mesh points: expected [nv,3]");
  if (s.triangles.rank() != 2 || s.triangles.dim(1) != 3 || s.triangles.dim(0) == 0)
    fail("mesh triangles: expected a non-empty [ntri,3]");
  nv_ = s.rest.dim(0);
  const std::size_t nt = s.time.size();
  if (s.points.rank() != 3 || s.points.dim(2) != 3 || s.points.dim(0) != nt)
    fail("points: expected [nt,nv,3] with nt = " + std::to_string(nt) + " output times, got " + shape_string(s.points.shape));
  if (s.points.dim(1) != nv_)
    fail("points: " + std::to_string(s.points.dim(1)) + " nodes per frame, the mesh has " + std::to_string(nv_));
  for (std::size_t k = 1; k < nt; ++k)
    if (!(s.time[k] > s.time[k - 1])) fail("time: not strictly increasing at index " + std::to_string(k));

  // The samples of the last period; a sample exactly one period before the last one repeats its
  // phase and measures how periodic the simulated motion is.
  const double T = period_, tol = 1e-6 * T;
  std::vector<std::size_t> used;
  for (std::size_t k = 0; k < nt; ++k)
    if (s.time[k] > s.time.back() - T - tol) used.push_back(k);
  if (!used.empty() && std::abs(s.time[used.front()] - (s.time.back() - T)) <= tol && used.size() > 1) {
    const std::size_t a = used.front(), b = nt - 1;
    for (std::size_t i = 0; i < nv_; ++i) {
      double d2 = 0;
      for (int d = 0; d < 3; ++d) d2 += std::pow(s.points(b, i, d) - s.points(a, i, d), 2);
      periodicity_gap_ = std::max(periodicity_gap_, std::sqrt(d2));
    }
    used.erase(used.begin());
  }
  if (used.size() < 4) fail("time: " + std::to_string(used.size()) + " samples in the last period, at least 4 needed");
  std::vector<std::size_t> order(used.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::vector<double> ph(used.size());
  for (std::size_t j = 0; j < used.size(); ++j) ph[j] = wrap(s.time[used[j]], T);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return ph[a] < ph[b]; });
  const std::size_t n = used.size();
  for (std::size_t j : order) {
    phase_.push_back(ph[j]);
    NdArray<double> v({nv_, 3});
    std::copy_n(s.points.data.begin() + used[j] * nv_ * 3, nv_ * 3, v.data.begin());
    value_.push_back(std::move(v));
  }
  // Coverage: no gap between neighbouring phases (the wrap-around included) above twice the median.
  std::vector<double> gaps(n);
  for (std::size_t j = 0; j < n; ++j) gaps[j] = (j + 1 < n ? phase_[j + 1] : phase_[0] + T) - phase_[j];
  auto sorted = gaps;
  std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.end());
  const double median = sorted[n / 2], largest = *std::max_element(gaps.begin(), gaps.end());
  if (*std::min_element(gaps.begin(), gaps.end()) <= tol) fail("time: two samples of the last period share a phase");
  if (largest > 2.01 * median)
    fail("time: the samples " + std::to_string(s.time.front()) + ".." + std::to_string(s.time.back()) +
         " s leave a gap of " + std::to_string(largest / T) + " T in the period T = " + std::to_string(T) +
         " s (median spacing " + std::to_string(median / T) + " T): expected outputs over at least one full period");
  // Second-order slopes on the periodic, possibly non-uniform, sample set.
  for (std::size_t j = 0; j < n; ++j) {
    const std::size_t prev = (j + n - 1) % n, next = (j + 1) % n;
    const double h0 = gaps[prev], h1 = gaps[j];
    NdArray<double> m({nv_, 3});
    for (std::size_t i = 0; i < nv_ * 3; ++i)
      m.data[i] = (h0 * h0 * value_[next].data[i] - h1 * h1 * value_[prev].data[i] - (h0 * h0 - h1 * h1) * value_[j].data[i]) /
                  (h0 * h1 * (h0 + h1));
    slope_.push_back(std::move(m));
  }
  samples_used_ = n;
  t_first_ = s.time[used.front()];
  t_last_ = s.time.back();

  // Space: nearest triangle at rest, then unclamped affine coordinates in its plane.
  const auto nearest = mesh::bind_to_surface(s.rest, s.triangles, surface.rest);
  max_outside_ = nearest.max_distance;
  binding_.resize(surface.size());
  for (std::size_t v = 0; v < surface.size(); ++v) {
    const auto& tri = nearest.vertices[v];
    const V3 a = row(s.rest, tri[0]), e1 = sub(row(s.rest, tri[1]), a), e2 = sub(row(s.rest, tri[2]), a);
    const V3 nrm = unit(cross(e1, e2));
    const V3 q = sub(row(surface.rest, v), a);
    const double g11 = dot(e1, e1), g12 = dot(e1, e2), g22 = dot(e2, e2), det = g11 * g22 - g12 * g12;
    if (!(det > 0)) fail("mesh triangle with nodes " + std::to_string(tri[0]) + " " + std::to_string(tri[1]) + " " +
                         std::to_string(tri[2]) + " has no area");
    const double r1 = dot(e1, q), r2 = dot(e2, q);
    const double u = (g22 * r1 - g12 * r2) / det, w = (g11 * r2 - g12 * r1) / det;
    binding_[v] = {tri, {1 - u - w, u, w}, dot(q, nrm)};
  }
}

NdArray<double> FsiMotion::node_positions(double t) const {
  const double T = period_, p = wrap(t, T);
  const std::size_t n = phase_.size();
  // Interval [left, right) holding the phase p, periodic.
  const auto it = std::upper_bound(phase_.begin(), phase_.end(), p);
  std::size_t left, right;
  double p0, p1;
  if (it == phase_.begin()) {
    left = n - 1, right = 0, p0 = phase_[n - 1] - T, p1 = phase_[0];
  } else {
    left = static_cast<std::size_t>(it - phase_.begin()) - 1;
    right = (left + 1) % n;
    p0 = phase_[left];
    p1 = left + 1 < n ? phase_[left + 1] : phase_[0] + T;
  }
  const double h = p1 - p0, s = (p - p0) / h, s2 = s * s, s3 = s2 * s;
  const double h00 = 2 * s3 - 3 * s2 + 1, h10 = (s3 - 2 * s2 + s) * h, h01 = -2 * s3 + 3 * s2, h11 = (s3 - s2) * h;
  NdArray<double> out({nv_, 3});
  const auto &x0 = value_[left].data, &x1 = value_[right].data, &m0 = slope_[left].data, &m1 = slope_[right].data;
  for (std::size_t i = 0; i < nv_ * 3; ++i) out.data[i] = h00 * x0[i] + h10 * m0[i] + h01 * x1[i] + h11 * m1[i];
  return out;
}

NdArray<double> FsiMotion::positions(const FinSurface& surface, double t) const {
  if (surface.size() != binding_.size())
    throw Error(label_ + ": the motion was bound to a surface of " + std::to_string(binding_.size()) +
                " vertices, asked for one of " + std::to_string(surface.size()));
  const auto x = node_positions(t);
  NdArray<double> out({surface.size(), 3});
  for (std::size_t v = 0; v < binding_.size(); ++v) {
    const auto& b = binding_[v];
    const V3 a = row(x, b.nodes[0]), bb = row(x, b.nodes[1]), c = row(x, b.nodes[2]);
    const V3 nrm = unit(cross(sub(bb, a), sub(c, a)));
    for (int d = 0; d < 3; ++d)
      out(v, d) = b.weights[0] * a[d] + b.weights[1] * bb[d] + b.weights[2] * c[d] + b.normal_offset * nrm[d];
  }
  return out;
}

nlohmann::json FsiMotion::parameters() const {
  return {{"model", name()},
          {"source", label_},
          {"period_s", period_},
          {"frequency_hz", 1.0 / period_},
          {"samples_in_last_period", samples_used_},
          {"time_first_s", t_first_},
          {"time_last_s", t_last_},
          {"max_outside_distance_m", max_outside_},
          {"periodicity_gap_m", periodicity_gap_},
          {"interpolation", "periodic cubic Hermite in time; affine in the nearest rest mid-surface triangle"}};
}

FsiMotion read_fsi_motion(const std::filesystem::path& fsi_path, const std::filesystem::path& mesh_path,
                          const FinSurface& surface, double max_distance_over_chord) {
  const std::string both = fsi_path.string() + " with " + mesh_path.string();
  auto mesh = stage::read<stage::Mesh>(mesh_path);
  auto fsi = stage::read<stage::Fsi>(fsi_path);
  if (!fsi.period) throw Error(fsi_path.string() + ": root attribute T (the period, s) is missing: expected a periodic run");
  if (fsi.points.dim(1) != mesh.points.dim(0))
    throw Error(both + ": /points has " + std::to_string(fsi.points.dim(1)) + " nodes per frame, " + mesh_path.string() +
                " has " + std::to_string(mesh.points.dim(0)) + " nodes: not the mesh the FSI ran on");
  const double c = surface.chord > 0 ? surface.chord : mesh.chord.value_or(1.0);
  if (!fsi.reference_points.data.empty()) {
    double worst = 0;
    for (std::size_t i = 0; i < mesh.points.data.size() && i < fsi.reference_points.data.size(); ++i)
      worst = std::max(worst, std::abs(fsi.reference_points.data[i] - mesh.points.data[i]));
    if (fsi.reference_points.data.size() != mesh.points.data.size() || worst > 1e-6 * c)
      throw Error(both + ": /reference_points differ from the mesh's /points by up to " + std::to_string(worst / c) +
                  " c: not the mesh the FSI ran on");
  }
  check_made_from(fsi_path, mesh_path);
  FsiSamples s{std::move(mesh.points), std::move(mesh.triangles), std::move(fsi.time.data), std::move(fsi.points),
               *fsi.period, both, "fsi"};
  FsiMotion motion(std::move(s), surface);
  if (motion.max_outside_distance() > max_distance_over_chord * c)
    throw Error(both + ": the truth surface lies up to " + std::to_string(motion.max_outside_distance() / c) +
                " c from the mesh's mid-surface (allowed " + std::to_string(max_distance_over_chord) +
                " c): not the same fin template");
  return motion;
}

FsiMotion read_fem_motion(const std::filesystem::path& motion_path, const std::filesystem::path& mesh_path,
                          const FinSurface& surface, double max_distance_over_chord) {
  const std::string both = motion_path.string() + " with " + mesh_path.string();
  auto mesh = stage::read<stage::Mesh>(mesh_path);
  auto m = stage::read<stage::Motion>(motion_path);
  if (!m.period) throw Error(motion_path.string() + ": root attribute T (the period, s) is missing: expected a periodic run");
  if (m.points.dim(1) != mesh.points.dim(0))
    throw Error(both + ": /points has " + std::to_string(m.points.dim(1)) + " nodes per frame, " + mesh_path.string() +
                " has " + std::to_string(mesh.points.dim(0)) + " nodes: not the mesh the run was on");
  check_made_from(motion_path, mesh_path);
  const double c = surface.chord > 0 ? surface.chord : mesh.chord.value_or(1.0);
  FsiSamples s{std::move(mesh.points), std::move(mesh.triangles), std::move(m.time.data), std::move(m.points),
               *m.period, both, "fem"};
  FsiMotion motion(std::move(s), surface);
  if (motion.max_outside_distance() > max_distance_over_chord * c)
    throw Error(both + ": the truth surface lies up to " + std::to_string(motion.max_outside_distance() / c) +
                " c from the mesh's mid-surface (allowed " + std::to_string(max_distance_over_chord) +
                " c): not the same fin template");
  return motion;
}

}  // namespace finverse::vision
