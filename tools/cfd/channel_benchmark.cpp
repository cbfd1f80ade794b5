// Boundary conditions and solver options of the cylinder-in-a-channel benchmarks; see the header.
#include "cfd/channel_benchmark.hpp"

namespace finverse::cfd {

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
