// The non-uniform (stretched) cell-centred Cartesian grid of the flow solver, in 2-D or 3-D.
//
// A tensor product of three axes (DESIGN.md section 5.1): each axis has a uniform core around the
// body and geometric stretching outside it. In 2-D the z axis is a single cell of unit width, so
// volumes are areas and face "areas" are lengths, and every 3-D formula holds unchanged.
#pragma once

#include <array>
#include <cstddef>

#include "cfd/grid/stretched_axis.hpp"

namespace finverse::cfd {

class StretchedGrid {
 public:
  StretchedGrid() = default;
  // 2-D grid; z is one cell of unit width.
  StretchedGrid(Axis x, Axis y);
  StretchedGrid(Axis x, Axis y, Axis z);

  int dim() const { return dim_; }
  const Axis& axis(int d) const { return axes_[static_cast<std::size_t>(d)]; }
  int n(int d) const { return axis(d).size(); }
  int nx() const { return n(0); }
  int ny() const { return n(1); }
  int nz() const { return n(2); }
  std::size_t cells() const {
    return static_cast<std::size_t>(nx()) * static_cast<std::size_t>(ny()) *
           static_cast<std::size_t>(nz());
  }

  double xc(int i) const { return axes_[0].centre(i); }
  double yc(int j) const { return axes_[1].centre(j); }
  double zc(int k) const { return axes_[2].centre(k); }
  double dx(int i) const { return axes_[0].width(i); }
  double dy(int j) const { return axes_[1].width(j); }
  double dz(int k) const { return axes_[2].width(k); }
  double volume(int i, int j, int k) const { return dx(i) * dy(j) * dz(k); }
  // Area of the face normal to axis d at (i,j,k): the product of the two tangential widths.
  double face_area(int d, int i, int j, int k) const {
    switch (d) {
      case 0: return dy(j) * dz(k);
      case 1: return dx(i) * dz(k);
      default: return dx(i) * dy(j);
    }
  }

  // Largest cell aspect ratio (longest over shortest side, over the active axes).
  double max_aspect_ratio() const;

  // The next multigrid level: axes with coarsen[d] set are halved (their cell count must be even).
  StretchedGrid coarsened(const std::array<bool, 3>& coarsen) const;
  // Cells j in [j0, j1), k in [k0, k1) and all of x: one MPI rank's block (cfd/parallel). Its faces
  // are the whole grid's, so widths, centres and areas are the same numbers bit for bit.
  StretchedGrid block(int j0, int j1, int k0, int k1) const;

 private:
  int dim_ = 0;
  std::array<Axis, 3> axes_;
};

}  // namespace finverse::cfd
