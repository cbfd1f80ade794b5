// Face coefficients beta and the immersed-boundary face mask; see face_coefficients.hpp.
#include "cfd/poisson/face_coefficients.hpp"

namespace finverse::cfd {

void FaceCoefficients::allocate(const StretchedGrid& g) {
  n_ = {g.nx(), g.ny(), g.nz()};
  for (int d = 0; d < 3; ++d) {
    std::size_t m = 1;
    for (int e = 0; e < 3; ++e) m *= static_cast<std::size_t>(n_[static_cast<std::size_t>(e)] + (e == d));
    v_[static_cast<std::size_t>(d)].assign(m, 0.0);
  }
}

FaceCoefficients::FaceCoefficients(const StretchedGrid& g, double value) {
  allocate(g);
  for (auto& v : v_) v.assign(v.size(), value);
}

FaceCoefficients::FaceCoefficients(const StretchedGrid& g,
                                   const std::function<double(double, double, double)>& beta) {
  allocate(g);
  for (int k = 0; k <= g.nz(); ++k)
    for (int j = 0; j <= g.ny(); ++j)
      for (int i = 0; i <= g.nx(); ++i) {
        const bool in_x = i < g.nx(), in_y = j < g.ny(), in_z = k < g.nz();
        const double x = in_x ? g.xc(i) : 0, y = in_y ? g.yc(j) : 0, z = in_z ? g.zc(k) : 0;
        if (in_y && in_z) (*this)(0, i, j, k) = beta(g.axis(0).face(i), y, z);
        if (in_x && in_z) (*this)(1, i, j, k) = beta(x, g.axis(1).face(j), z);
        if (in_x && in_y) (*this)(2, i, j, k) = beta(x, y, g.axis(2).face(k));
      }
}

std::size_t FaceCoefficients::mask_cells(const std::function<bool(int, int, int)>& solid) {
  std::size_t count = 0;
  for (int k = 0; k < n_[2]; ++k)
    for (int j = 0; j < n_[1]; ++j)
      for (int i = 0; i < n_[0]; ++i) {
        if (!solid(i, j, k)) continue;
        ++count;
        (*this)(0, i, j, k) = (*this)(0, i + 1, j, k) = 0;
        (*this)(1, i, j, k) = (*this)(1, i, j + 1, k) = 0;
        (*this)(2, i, j, k) = (*this)(2, i, j, k + 1) = 0;
      }
  return count;
}

}  // namespace finverse::cfd
