// Face-normal velocities of the collocated fractional-step solver (Zang, Street & Koseff 1994):
// one value per cell face, the normal component of the velocity on that face. These are the
// velocities that satisfy the discrete continuity equation exactly (to the Poisson solver's
// tolerance), and the ones that carry momentum in the conservative convective term.
//
// Layout as FaceCoefficients (face_coefficients.hpp): per axis d, x fastest, face i on the low
// side of cell i, i = 0..n(d). On a periodic axis face n(d) and face 0 are the same face; the
// solver keeps both copies equal.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "cfd/grid/stretched_grid.hpp"

namespace finverse::cfd {

class FaceField {
 public:
  FaceField() = default;
  explicit FaceField(const StretchedGrid& grid) {
    n_ = {grid.nx(), grid.ny(), grid.nz()};
    for (int d = 0; d < 3; ++d) {
      const std::size_t m = static_cast<std::size_t>(n_[0] + (d == 0)) * static_cast<std::size_t>(n_[1] + (d == 1)) *
                            static_cast<std::size_t>(n_[2] + (d == 2));
      v_[static_cast<std::size_t>(d)].assign(d < grid.dim() ? m : 0, 0.0);
    }
  }

  std::size_t index(int d, int i, int j, int k) const {
    const std::size_t fx = static_cast<std::size_t>(n_[0] + (d == 0));
    const std::size_t fy = static_cast<std::size_t>(n_[1] + (d == 1));
    return static_cast<std::size_t>(i) + fx * (static_cast<std::size_t>(j) + fy * static_cast<std::size_t>(k));
  }
  double& operator()(int d, int i, int j, int k) { return v_[static_cast<std::size_t>(d)][index(d, i, j, k)]; }
  double operator()(int d, int i, int j, int k) const { return v_[static_cast<std::size_t>(d)][index(d, i, j, k)]; }
  std::vector<double>& values(int d) { return v_[static_cast<std::size_t>(d)]; }
  const std::vector<double>& values(int d) const { return v_[static_cast<std::size_t>(d)]; }

 private:
  std::array<int, 3> n_{};
  std::array<std::vector<double>, 3> v_;
};

}  // namespace finverse::cfd
