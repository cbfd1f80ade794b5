// Construction of stretched axes: a uniform core plus geometric growth h_k = h r^k outside it.
//
// With m outer cells the first of width h*r and the last h*r^m, the outer length is
// L(m, r) = h (r + r^2 + ... + r^m); for fixed m it grows monotonically with r, so the ratio that
// closes a given length exactly is found by bisection.
#include "cfd/grid/stretched_axis.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace finverse::cfd {

namespace {

double geometric_length(double h, double r, int m) {
  double len = 0, w = h;
  for (int k = 0; k < m; ++k) {
    w *= r;
    len += w;
  }
  return len;
}

// Fewest cells that cover length L growing from h with ratio at most r_max (r_max < 1: the
// fewest that reach L while shrinking by r_max per cell).
int cells_needed(double L, double h, double r_max) {
  if (L <= 0) return 0;
  if (r_max < 1 && h * r_max / (1 - r_max) < L * (1 - 1e-12))
    throw std::invalid_argument("Axis: cells shrinking with ratio " + std::to_string(r_max) +
                                " from width " + std::to_string(h) + " cannot reach the domain bound " +
                                std::to_string(L) + " away");
  int m = 0;
  double len = 0, w = h;
  while (len < L * (1 - 1e-12)) {
    w *= r_max;
    len += w;
    ++m;
    if (m > 100000) throw std::invalid_argument("Axis: stretching cannot reach the domain bound");
  }
  return m;
}

// Ratio r such that m cells growing from h cover exactly L (r < 1 is possible when m h > L).
double closing_ratio(double L, double h, int m) {
  double a = 1e-3, b = 1.0;
  while (geometric_length(h, b, m) < L) b *= 2;
  for (int it = 0; it < 200; ++it) {
    const double c = 0.5 * (a + b);
    (geometric_length(h, c, m) < L ? a : b) = c;
  }
  return 0.5 * (a + b);
}

// Appends the faces of m cells growing from width h with ratio r, going from x0 in direction dir.
std::vector<double> outer_faces(double x0, double h, double r, int m, double dir) {
  std::vector<double> f;
  double x = x0, w = h;
  for (int k = 0; k < m; ++k) {
    w *= r;
    x += dir * w;
    f.push_back(x);
  }
  return f;
}

Axis assemble(double lo, double hi, double ulo, double uhi, int nu, int mlo, int mhi) {
  const double h = (uhi - ulo) / nu;
  const double rlo = mlo > 0 ? closing_ratio(ulo - lo, h, mlo) : 1.0;
  const double rhi = mhi > 0 ? closing_ratio(hi - uhi, h, mhi) : 1.0;
  std::vector<double> left = outer_faces(ulo, h, rlo, mlo, -1.0);
  std::vector<double> faces(left.rbegin(), left.rend());
  for (int i = 0; i <= nu; ++i) faces.push_back(ulo + i * h);
  for (double x : outer_faces(uhi, h, rhi, mhi, +1.0)) faces.push_back(x);
  // Snap the ends: the bisection closes the length to rounding, the domain bounds are exact.
  faces.front() = lo;
  faces.back() = hi;
  return Axis(std::move(faces));
}

void check_box(double lo, double hi, double ulo, double uhi, double max_ratio) {
  if (!(lo <= ulo && ulo < uhi && uhi <= hi))
    throw std::invalid_argument("Axis: need lo <= uniform_lo < uniform_hi <= hi");
  if (!(max_ratio >= 1.0)) throw std::invalid_argument("Axis: max stretch ratio must be >= 1");
}

}  // namespace

Axis::Axis(std::vector<double> faces) : faces_(std::move(faces)) {
  if (faces_.size() < 2) throw std::invalid_argument("Axis: need at least two faces");
  for (std::size_t i = 1; i < faces_.size(); ++i)
    if (!(faces_[i] > faces_[i - 1]))
      throw std::invalid_argument("Axis: faces must increase strictly (at index " +
                                  std::to_string(i) + ")");
}

Axis Axis::uniform(double lo, double hi, int n) {
  if (n < 1 || !(hi > lo)) throw std::invalid_argument("Axis::uniform: need n >= 1 and hi > lo");
  std::vector<double> f(static_cast<std::size_t>(n) + 1);
  for (int i = 0; i <= n; ++i) f[static_cast<std::size_t>(i)] = lo + (hi - lo) * i / n;
  f.back() = hi;
  return Axis(std::move(f));
}

Axis Axis::stretched(double lo, double hi, double ulo, double uhi, double h, double max_ratio) {
  check_box(lo, hi, ulo, uhi, max_ratio);
  if (!(h > 0)) throw std::invalid_argument("Axis::stretched: spacing must be positive");
  const int nu = std::max(1, static_cast<int>(std::lround((uhi - ulo) / h)));
  const double hu = (uhi - ulo) / nu;
  return assemble(lo, hi, ulo, uhi, nu, cells_needed(ulo - lo, hu, max_ratio),
                  cells_needed(hi - uhi, hu, max_ratio));
}

Axis Axis::stretched_count(double lo, double hi, double ulo, double uhi, int n, double max_ratio) {
  check_box(lo, hi, ulo, uhi, max_ratio);
  for (int nu = n; nu >= 1; --nu) {
    const double h = (uhi - ulo) / nu;
    int mlo = cells_needed(ulo - lo, h, max_ratio);
    int mhi = cells_needed(hi - uhi, h, max_ratio);
    int spare = n - nu - mlo - mhi;
    if (spare < 0) continue;
    // Spare cells go to the outer side that is longer in units of h, one at a time, so both
    // sides end with similar ratios; a side of zero length gets none.
    while (spare > 0) {
      const double llo = (ulo - lo) / h - mlo, lhi = (hi - uhi) / h - mhi;
      if (ulo > lo && (llo >= lhi || !(hi > uhi))) ++mlo;
      else if (hi > uhi) ++mhi;
      else break;
      --spare;
    }
    if (spare > 0) continue;  // no outer region to take them: fewer uniform cells cannot help
    return assemble(lo, hi, ulo, uhi, nu, mlo, mhi);
  }
  throw std::invalid_argument("Axis::stretched_count: " + std::to_string(n) +
                              " cells cannot span the domain with the given max ratio");
}

Axis Axis::nested(double lo, double hi, double core_lo, double core_hi, double h_core, double box_lo, double box_hi,
                  double h_box, double transition_ratio, double max_ratio, int multiple) {
  // A ratio below 1 shrinks the outer cells towards lo and hi (walls with boundary layers of their
  // own); the shrinking series must still be able to reach the bounds.
  check_box(lo, hi, box_lo, box_hi, std::max(max_ratio, 1.0));
  if (!(max_ratio > 0)) throw std::invalid_argument("Axis::nested: max ratio must be > 0");
  if (!(box_lo <= core_lo && core_lo < core_hi && core_hi <= box_hi))
    throw std::invalid_argument("Axis::nested: need box_lo <= core_lo < core_hi <= box_hi");
  if (!(h_core > 0 && h_box >= h_core)) throw std::invalid_argument("Axis::nested: need 0 < h_core <= h_box");
  if (!(transition_ratio > 1) || multiple < 1)
    throw std::invalid_argument("Axis::nested: need transition ratio > 1 and multiple >= 1");
  const int nc = std::max(1, static_cast<int>(std::lround((core_hi - core_lo) / h_core)));
  const double hc = (core_hi - core_lo) / nc;
  // m transition cells hc r^k (k = 1..m) with r = (h_box / hc)^(1 / (m + 1)) <= transition_ratio, so
  // that the first box cell continues the geometric sequence.
  const double growth = std::max(1.0, h_box / hc);
  const int m = std::max(0, static_cast<int>(std::ceil(std::log(growth) / std::log(transition_ratio) - 1e-9)) - 1);
  const double r = std::pow(growth, 1.0 / (m + 1));
  // Faces from the core edge outwards (distances), ending exactly at the box edge; returns the
  // width of the last cell.
  const auto side = [&](double length, std::vector<double>& dist) {
    double x = 0, w = hc;
    for (int k = 0; k < m; ++k) {
      w *= r;
      x += w;
      dist.push_back(x);
    }
    const double rest = length - x;
    if (m > 0 && rest < 0.5 * h_box * (1 - 1e-12)) return -(x + h_box);  // the box length this side needs
    if (rest <= 1e-12 * std::max(length, h_box)) return w;
    const int n = std::max(1, static_cast<int>(std::lround(rest / h_box)));
    for (int i = 1; i <= n; ++i) dist.push_back(x + rest * i / n);
    dist.back() = length;
    return rest / n;
  };
  std::vector<double> dl, dr;
  double wl = side(core_lo - box_lo, dl), wr = side(box_hi - core_hi, dr);
  // A box too short for the transition is widened on that side, as far as the domain allows.
  if (wl < 0) {
    box_lo = core_lo + wl;
    dl.clear();
    wl = box_lo >= lo ? side(core_lo - box_lo, dl) : -1.0;
  }
  if (wr < 0) {
    box_hi = core_hi - wr;
    dr.clear();
    wr = box_hi <= hi ? side(box_hi - core_hi, dr) : -1.0;
  }
  if (wl < 0 || wr < 0)
    throw std::invalid_argument("Axis::nested: the domain has no room for the transition (" + std::to_string(m) +
                                " cells) plus one box cell beyond the core");
  int mlo = cells_needed(box_lo - lo, wl, max_ratio), mhi = cells_needed(hi - box_hi, wr, max_ratio);
  int spare = (multiple - (nc + static_cast<int>(dl.size() + dr.size()) + mlo + mhi) % multiple) % multiple;
  for (; spare > 0; --spare) {
    if (box_lo > lo && ((box_lo - lo) / wl - mlo >= (hi - box_hi) / wr - mhi || !(hi > box_hi))) ++mlo;
    else if (hi > box_hi) ++mhi;
    else throw std::invalid_argument("Axis::nested: no outer region to pad the cell count to a multiple of " +
                                     std::to_string(multiple));
  }
  std::vector<double> faces;
  if (mlo > 0) {
    const std::vector<double> o = outer_faces(box_lo, wl, closing_ratio(box_lo - lo, wl, mlo), mlo, -1.0);
    faces.assign(o.rbegin(), o.rend());
  }
  for (auto it = dl.rbegin(); it != dl.rend(); ++it) faces.push_back(core_lo - *it);
  for (int i = 0; i <= nc; ++i) faces.push_back(i == nc ? core_hi : core_lo + hc * i);
  for (double d : dr) faces.push_back(core_hi + d);
  if (mhi > 0)
    for (double x : outer_faces(box_hi, wr, closing_ratio(hi - box_hi, wr, mhi), mhi, +1.0)) faces.push_back(x);
  faces.front() = lo;
  faces.back() = hi;
  return Axis(std::move(faces));
}

Axis Axis::coarsened() const {
  if (size() % 2 != 0) throw std::logic_error("Axis::coarsened: odd cell count");
  std::vector<double> f;
  for (int i = 0; i <= size(); i += 2) f.push_back(face(i));
  return Axis(std::move(f));
}

Axis Axis::refined() const {
  const int n = size();
  const auto x = [&](int i) { return face(i); };
  std::vector<double> f;
  f.reserve(static_cast<std::size_t>(2 * n + 1));
  for (int i = 0; i < n; ++i) {
    f.push_back(x(i));
    double mid;
    if (n < 3) mid = 0.5 * (x(i) + x(i + 1));
    // Four-point Lagrange interpolation at xi = i + 1/2, one-sided at the ends.
    else if (i == 0) mid = (5 * x(0) + 15 * x(1) - 5 * x(2) + x(3)) / 16;
    else if (i == n - 1) mid = (5 * x(n) + 15 * x(n - 1) - 5 * x(n - 2) + x(n - 3)) / 16;
    else mid = (-x(i - 1) + 9 * x(i) + 9 * x(i + 1) - x(i + 2)) / 16;
    f.push_back(mid);
  }
  f.push_back(x(n));
  return Axis(std::move(f));
}

double Axis::max_stretch_ratio() const {
  double r = 1;
  for (int i = 1; i < size(); ++i) {
    const double q = width(i) / width(i - 1);
    r = std::max({r, q, 1 / q});
  }
  return r;
}

double Axis::width_at(double x) const {
  const auto it = std::upper_bound(faces_.begin(), faces_.end(), x);
  return width(std::clamp(static_cast<int>(it - faces_.begin()) - 1, 0, size() - 1));
}

double Axis::min_width() const {
  double w = width(0);
  for (int i = 1; i < size(); ++i) w = std::min(w, width(i));
  return w;
}

double Axis::max_width() const {
  double w = width(0);
  for (int i = 1; i < size(); ++i) w = std::max(w, width(i));
  return w;
}

}  // namespace finverse::cfd
