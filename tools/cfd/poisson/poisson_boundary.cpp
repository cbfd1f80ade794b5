// Boundary-condition bookkeeping; see poisson_boundary.hpp.
#include "cfd/poisson/poisson_boundary.hpp"

#include <stdexcept>

namespace finverse::cfd {

void BoundaryConditions::validate() const {
  for (int d = 0; d < 3; ++d) {
    const bool lo = type[static_cast<std::size_t>(2 * d)] == BcType::Periodic;
    const bool hi = type[static_cast<std::size_t>(2 * d + 1)] == BcType::Periodic;
    if (lo != hi) throw std::invalid_argument("BoundaryConditions: periodic sides must come in pairs");
  }
}

std::size_t side_faces(const StretchedGrid& g, Side s) {
  const auto n = [&](int d) { return static_cast<std::size_t>(g.n(d)); };
  switch (side_axis(s)) {
    case 0: return n(1) * n(2);
    case 1: return n(0) * n(2);
    default: return n(0) * n(1);
  }
}

void BoundaryValues::sample(const StretchedGrid& g, Side s,
                            const std::function<double(double, double, double)>& fn) {
  auto& v = (*this)[s];
  v.resize(side_faces(g, s));
  const int a = side_axis(s);
  const double wall = side_is_high(s) ? g.axis(a).hi() : g.axis(a).lo();
  std::size_t m = 0;
  if (a == 0) {
    for (int k = 0; k < g.nz(); ++k)
      for (int j = 0; j < g.ny(); ++j) v[m++] = fn(wall, g.yc(j), g.zc(k));
  } else if (a == 1) {
    for (int k = 0; k < g.nz(); ++k)
      for (int i = 0; i < g.nx(); ++i) v[m++] = fn(g.xc(i), wall, g.zc(k));
  } else {
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) v[m++] = fn(g.xc(i), g.yc(j), wall);
  }
}

}  // namespace finverse::cfd
