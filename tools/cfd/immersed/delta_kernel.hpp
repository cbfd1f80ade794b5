// One-dimensional regularized delta kernels phi(r) (r in cell widths) of the zero-thickness
// immersed surface (DESIGN.md section 5.1; sheet_forcing.hpp): the 3-D kernel is the product
// phi(r_x) phi(r_y) phi(r_z), its weights interpolate the grid velocity to a Lagrangian marker and
// spread the marker's force back to the grid with the same weights.
//
//   roma3     Roma, Peskin & Berger 1999 (J. Comput. Phys. 153:509), support 3 cells, the kernel of
//             Uhlmann 2005 (J. Comput. Phys. 209:448); continuous, with kinks.
//   peskin4   Peskin 2002 (Acta Numerica 11:479) four-point kernel, support 4 cells; continuous, kinks.
//   smooth3   roma3 smoothed by a unit box (Yang, Zhang, Li & He 2009, J. Comput. Phys. 228:7821):
//             phi_s(r) = int_{r-1/2}^{r+1/2} phi(s) ds, support 4 cells, continuous first
//             derivative, so a marker crossing a grid line changes its weights smoothly and the
//             force oscillations of the kinked kernels are suppressed.
//   smooth4   peskin4 smoothed the same way, support 5 cells.
// Every kernel integrates to 1 and has zero first moment on a uniform grid (sum_i phi(r - i) = 1,
// sum_i (r - i) phi(r - i) = 0 for all r; the smoothed ones inherit both), tested in
// tests/unit/cfd/delta_kernel_test.cpp.
#pragma once

#include <string>

namespace finverse::cfd {

enum class DeltaKernel { Roma3, Peskin4, Smooth3, Smooth4 };

// The kernel named `name` (roma3, peskin4, smooth3, smooth4); finverse::Error naming the choices.
DeltaKernel delta_kernel_from_name(const std::string& name);
const char* delta_kernel_name(DeltaKernel k);

// phi(r), zero for |r| >= delta_kernel_half_support(k).
double delta_kernel(DeltaKernel k, double r);
double delta_kernel_half_support(DeltaKernel k);

}  // namespace finverse::cfd
