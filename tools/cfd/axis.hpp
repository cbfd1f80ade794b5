// One axis of the non-uniform Cartesian grid: the face coordinates x_0 < x_1 < ... < x_n of n cells.
//
// The flow solver (DESIGN.md section 5.1) resolves the body on a uniform core and stretches the cells
// geometrically towards the far field, h_k = h * r^k with r <= r_max, so that the domain boundaries
// can sit far away at modest cost. Everything else on a cell-centred grid (centres, widths, distances
// between centres) follows from the faces, so the faces are the one stored quantity.
#pragma once

#include <cstddef>
#include <vector>

namespace finverse::cfd {

class Axis {
 public:
  Axis() = default;

  // From explicit, strictly increasing face coordinates (at least two).
  explicit Axis(std::vector<double> faces);

  // n equal cells on [lo, hi].
  static Axis uniform(double lo, double hi, int n);

  // Uniform cells of width close to h on [ulo, uhi] (the count is rounded so they tile it exactly),
  // then geometric growth outwards to lo and hi. On each side the fewest cells are used that reach
  // the boundary with ratio <= max_ratio; the ratio is then lowered so the last face lands on the
  // boundary exactly. Requires lo <= ulo < uhi <= hi, h > 0, max_ratio >= 1.
  static Axis stretched(double lo, double hi, double ulo, double uhi, double h, double max_ratio);

  // As stretched(), but with exactly n cells in total: the uniform core gets as many cells as it
  // can while both outer regions still close with ratio <= max_ratio; cells left over go to the
  // outer regions (lowering their ratio). Used where a cell count is prescribed (benchmarks,
  // multigrid-friendly sizes).
  static Axis stretched_count(double lo, double hi, double ulo, double uhi, int n, double max_ratio);

  // Every other face: the axis of the next multigrid level. Requires an even cell count.
  Axis coarsened() const;

  // Each cell split in two, the new faces placed by cubic interpolation of the face mapping
  // x(xi) (xi = face number): the finer grid samples the same smooth mapping, so a sequence of
  // refinements is a proper grid-convergence family (cell-width ratios tend to 1 as h^2).
  Axis refined() const;

  int size() const { return static_cast<int>(faces_.size()) - 1; }
  double lo() const { return faces_.front(); }
  double hi() const { return faces_.back(); }
  double length() const { return hi() - lo(); }
  double face(int i) const { return faces_[static_cast<std::size_t>(i)]; }
  double centre(int i) const { return 0.5 * (face(i) + face(i + 1)); }
  double width(int i) const { return face(i + 1) - face(i); }
  const std::vector<double>& faces() const { return faces_; }

  // Largest ratio of neighbouring cell widths (>= 1), a grid-quality measure.
  double max_stretch_ratio() const;
  double min_width() const;
  double max_width() const;

 private:
  std::vector<double> faces_;
};

}  // namespace finverse::cfd
