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

  // Two nested uniform regions, for a body whose boundary layer needs finer cells than its wake:
  // cells of width ~h_core on [core_lo, core_hi], a geometric transition (ratio <= transition_ratio)
  // up to ~h_box, uniform cells of ~h_box out to [box_lo, box_hi], then geometric growth (ratio <=
  // max_ratio) to lo and hi. Every region is tiled exactly (widths adjusted by rounding the counts);
  // the total count is padded to a multiple of `multiple` (multigrid levels) by giving the
  // outermost regions more cells. max_ratio < 1 makes the outer cells shrink towards lo and hi
  // instead (by about that ratio per cell; padding cells soften it), for bounds that are walls with
  // boundary layers of their own. Requires lo <= box_lo <= core_lo < core_hi <= box_hi <= hi,
  // 0 < h_core <= h_box; a box side too close to the core for the transition plus one box cell is
  // moved out (within [lo, hi]; std::invalid_argument if the domain is too short).
  static Axis nested(double lo, double hi, double core_lo, double core_hi, double h_core, double box_lo, double box_hi,
                     double h_box, double transition_ratio, double max_ratio, int multiple = 1);

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
  // Across the interior face f (0 < f < size()): the distance between the centres of cells f - 1
  // and f, and the weight of cell f - 1 in the linear interpolation to the face (the face is not
  // midway between the centres on a stretched axis). Every kernel takes them from here, so that
  // line-wise and cell-wise evaluations of a stencil give the same bits.
  double centre_distance(int f) const { return centre(f) - centre(f - 1); }
  double lower_weight(int f) const { return width(f) / (width(f - 1) + width(f)); }
  // Width of the cell containing coordinate x (clamped to the axis): the local grid spacing of a
  // point on an immersed surface.
  double width_at(double x) const;
  const std::vector<double>& faces() const { return faces_; }

  // Largest ratio of neighbouring cell widths (>= 1), a grid-quality measure.
  double max_stretch_ratio() const;
  double min_width() const;
  double max_width() const;

 private:
  std::vector<double> faces_;
};

}  // namespace finverse::cfd
