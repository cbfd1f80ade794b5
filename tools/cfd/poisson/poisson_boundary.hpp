// Boundary conditions of the pressure Poisson problem on the faces of the rectangular domain.
//
// Per side one type: Neumann (prescribed outward normal derivative dp/dn, zero by default: the
// usual pressure condition of the fractional-step method), Dirichlet (prescribed p, e.g. an outflow
// reference pressure) or periodic (both sides of an axis). Values, where given, are one per boundary
// face; the faces of a side are numbered with the first tangential axis fastest:
// x sides j + ny k, y sides i + nx k, z sides i + nx j.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include "cfd/grid/stretched_grid.hpp"

namespace finverse::cfd {

enum class Side { XLo = 0, XHi = 1, YLo = 2, YHi = 3, ZLo = 4, ZHi = 5 };
enum class BcType { Neumann, Dirichlet, Periodic };

inline int side_axis(Side s) { return static_cast<int>(s) / 2; }
inline bool side_is_high(Side s) { return static_cast<int>(s) % 2 == 1; }

struct BoundaryConditions {
  std::array<BcType, 6> type{BcType::Neumann, BcType::Neumann, BcType::Neumann,
                             BcType::Neumann, BcType::Neumann, BcType::Neumann};

  static BoundaryConditions all(BcType t) {
    BoundaryConditions b;
    b.type.fill(t);
    return b;
  }
  BcType& operator[](Side s) { return type[static_cast<std::size_t>(s)]; }
  BcType operator[](Side s) const { return type[static_cast<std::size_t>(s)]; }
  bool periodic(int axis) const { return type[static_cast<std::size_t>(2 * axis)] == BcType::Periodic; }
  // Throws unless periodic sides come in pairs.
  void validate() const;
};

// Number of faces on a side of the grid.
std::size_t side_faces(const StretchedGrid& grid, Side s);

struct BoundaryValues {
  // Per side: empty means zero on every face; otherwise side_faces() values.
  std::array<std::vector<double>, 6> value;

  const std::vector<double>& operator[](Side s) const { return value[static_cast<std::size_t>(s)]; }
  std::vector<double>& operator[](Side s) { return value[static_cast<std::size_t>(s)]; }

  // Samples fn at the centres of the faces of side s (z = 0 for 2-D grids' z coordinate is the
  // single cell's centre).
  void sample(const StretchedGrid& grid, Side s, const std::function<double(double, double, double)>& fn);
};

}  // namespace finverse::cfd
