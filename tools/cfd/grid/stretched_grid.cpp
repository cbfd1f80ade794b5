// StretchedGrid: tensor product of axes; see stretched_grid.hpp.
#include "cfd/grid/stretched_grid.hpp"

#include <algorithm>
#include <stdexcept>
#include <vector>

namespace finverse::cfd {

StretchedGrid::StretchedGrid(Axis x, Axis y)
    : dim_(2), axes_{std::move(x), std::move(y), Axis::uniform(0.0, 1.0, 1)} {}

StretchedGrid::StretchedGrid(Axis x, Axis y, Axis z)
    : dim_(3), axes_{std::move(x), std::move(y), std::move(z)} {}

double StretchedGrid::max_aspect_ratio() const {
  // The extreme ratio pairs a cell's longest and shortest sides; checking every cell is cheap
  // next to anything done with the grid and avoids guessing where it occurs.
  double worst = 1;
  for (int k = 0; k < nz(); ++k)
    for (int j = 0; j < ny(); ++j)
      for (int i = 0; i < nx(); ++i) {
        double lo = std::min(dx(i), dy(j)), hi = std::max(dx(i), dy(j));
        if (dim_ == 3) lo = std::min(lo, dz(k)), hi = std::max(hi, dz(k));
        worst = std::max(worst, hi / lo);
      }
  return worst;
}

StretchedGrid StretchedGrid::coarsened(const std::array<bool, 3>& coarsen) const {
  auto c = [&](int d) { return coarsen[static_cast<std::size_t>(d)] ? axis(d).coarsened() : axis(d); };
  if (dim_ == 2) return StretchedGrid(c(0), c(1));
  return StretchedGrid(c(0), c(1), c(2));
}

StretchedGrid StretchedGrid::block(int j0, int j1, int k0, int k1) const {
  if (j0 < 0 || j1 > ny() || j0 >= j1 || k0 < 0 || k1 > nz() || k0 >= k1)
    throw std::invalid_argument("StretchedGrid::block: the lines must lie inside the grid");
  const auto slice = [&](int d, int a, int b) {
    const auto& f = axis(d).faces();
    return Axis(std::vector<double>(f.begin() + a, f.begin() + b + 1));
  };
  if (dim_ == 2) return StretchedGrid(axis(0), slice(1, j0, j1));
  return StretchedGrid(axis(0), slice(1, j0, j1), slice(2, k0, k1));
}

}  // namespace finverse::cfd
