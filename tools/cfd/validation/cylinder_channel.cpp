// Boundary conditions and solver options of the cylinder-in-a-channel benchmarks; see the header.
#include "cfd/validation/cylinder_channel.hpp"

#include <algorithm>
#include <cmath>

namespace finverse::cfd {

int round8(double n) { return std::max(8, 8 * static_cast<int>(std::lround(n / 8))); }

StretchedGrid channel_grid(const ChannelGridSpec& s) {
  const double wall_ratio = s.wall_ratio > 0 ? s.wall_ratio : s.ratio;
  if (s.h_core > 0 && s.h_core < s.h)
    return StretchedGrid(
        Axis::nested(0, s.length, s.core_x0, s.core_x1, s.h_core, s.box_x0, s.box_x1, s.h, 1.1, s.ratio, 8),
        Axis::nested(0, s.height, s.core_y0, s.core_y1, s.h_core, s.box_y0, s.box_y1, s.h, 1.1, wall_ratio, 8));
  const int nx = round8(Axis::stretched(0, s.length, s.box_x0, s.box_x1, s.h, s.ratio).size());
  const int ny = round8(Axis::stretched(0, s.height, s.box_y0, s.box_y1, s.h, wall_ratio).size());
  return StretchedGrid(Axis::stretched_count(0, s.length, s.box_x0, s.box_x1, nx, s.ratio),
                       Axis::stretched_count(0, s.height, s.box_y0, s.box_y1, ny, wall_ratio));
}

FlowBoundary channel_benchmark_boundary(double um, double ramp_time) {
  FlowBoundary b;
  b[Side::XLo].type = FlowBcType::Inlet;
  b[Side::XLo].profile = InletProfile::Parabolic;
  b[Side::XLo].speed = um;
  b[Side::XLo].ramp_time = ramp_time;
  b[Side::XHi].type = FlowBcType::ConvectiveOutlet;
  return b;
}

FlowOptions channel_benchmark_options(double nu, double cfl, double h, double um) {
  FlowOptions opt;
  opt.nu = nu;
  opt.cfl = cfl;
  opt.dt_max = cfl * h / um;
  opt.helmholtz_rtol = 1e-10;
  opt.poisson.rtol = 1e-9;
  return opt;
}

}  // namespace finverse::cfd
