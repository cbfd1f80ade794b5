// One-dimensional regularized delta kernels phi(r), r in cell widths, of the zero-thickness surface
// (sheet_forcing.hpp); the 3-D weight is phi(r_x) phi(r_y) phi(r_z). roma3: Roma, Peskin & Berger
// 1999 (support 3); peskin4: Peskin 2002 (support 4); smooth3/smooth4: those box-smoothed as Yang,
// Zhang, Li & He 2009 propose (C2, so weights change smoothly as a marker crosses a grid line).
// All sum to 1 with zero first moment on a uniform grid. Choice: docs/studies/thin_surface.md.
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
