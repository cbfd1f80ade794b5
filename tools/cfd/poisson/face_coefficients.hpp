// Per-face coefficient beta of the variable-coefficient Poisson operator div(beta grad p).
//
// beta is 1 for the plain pressure Poisson equation, 1/rho for variable density, and 0 on the
// faces that the immersed-boundary method cuts off: every face of a solid cell gets beta = 0, so
// solid cells decouple from the fluid and the fluid sees a zero-flux wall there.
//
// Storage per axis, x fastest: x faces (nx+1) x ny x nz at index i + (nx+1)(j + ny k), face i
// between cells i-1 and i; likewise y faces nx x (ny+1) x nz and z faces nx x ny x (nz+1).
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include "cfd/grid/stretched_grid.hpp"

namespace finverse::cfd {

class FaceCoefficients {
 public:
  FaceCoefficients() = default;
  FaceCoefficients(const StretchedGrid& grid, double value);
  // beta evaluated at the face centres.
  FaceCoefficients(const StretchedGrid& grid, const std::function<double(double, double, double)>& beta);

  // Number of faces normal to axis d, and the flat index of face (i,j,k) normal to d (the face on
  // the low side of cell (i,j,k); i, j or k may equal n(d) for the last face).
  std::size_t faces(int d) const { return v_[static_cast<std::size_t>(d)].size(); }
  std::size_t index(int d, int i, int j, int k) const {
    const auto [fx, fy] = extent_xy(d);
    return static_cast<std::size_t>(i) +
           fx * (static_cast<std::size_t>(j) + fy * static_cast<std::size_t>(k));
  }
  double& operator()(int d, int i, int j, int k) { return v_[static_cast<std::size_t>(d)][index(d, i, j, k)]; }
  double operator()(int d, int i, int j, int k) const {
    return v_[static_cast<std::size_t>(d)][index(d, i, j, k)];
  }
  const std::vector<double>& values(int d) const { return v_[static_cast<std::size_t>(d)]; }

  // Sets beta = 0 on every face of each cell for which solid(i, j, k) holds: the immersed-boundary
  // mask. Returns the number of solid cells.
  std::size_t mask_cells(const std::function<bool(int, int, int)>& solid);

 private:
  std::array<std::size_t, 2> extent_xy(int d) const {
    return {static_cast<std::size_t>(n_[0] + (d == 0)), static_cast<std::size_t>(n_[1] + (d == 1))};
  }
  void allocate(const StretchedGrid& grid);

  std::array<int, 3> n_{};
  std::array<std::vector<double>, 3> v_;
};

}  // namespace finverse::cfd
