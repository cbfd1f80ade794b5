// A rectangle of the grid's lines along x: the part of a field a kernel computes or a solver reads.
// On MPI ranks that each hold the whole flow, a rank's own block of lines (cfd/parallel); else all
// of them (grid_loops.hpp).
#pragma once

#include "cfd/grid/stretched_grid.hpp"

namespace finverse::cfd {

// The lines y in [j0, j1), z in [k0, k1), each all of x.
struct LineRange {
  int j0 = 0, j1 = 0, k0 = 0, k1 = 0;
  int ny() const { return j1 - j0; }
  int nz() const { return k1 - k0; }
  bool contains(int j, int k) const { return j >= j0 && j < j1 && k >= k0 && k < k1; }
  friend bool operator==(const LineRange&, const LineRange&) = default;
};

inline LineRange all_lines(const StretchedGrid& g) { return {0, g.ny(), 0, g.nz()}; }

// The smallest range holding both.
inline LineRange span(const LineRange& a, const LineRange& b) {
  return {a.j0 < b.j0 ? a.j0 : b.j0, a.j1 > b.j1 ? a.j1 : b.j1, a.k0 < b.k0 ? a.k0 : b.k0, a.k1 > b.k1 ? a.k1 : b.k1};
}

}  // namespace finverse::cfd
