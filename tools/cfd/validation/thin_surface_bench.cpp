// The cost of a thin body in the flow (see thin_surface_bench.hpp).
#include "cfd/validation/thin_surface_bench.hpp"

#include <chrono>

#include "cfd/io/fin_flow_case.hpp"
#include "cfd/io/fin_input.hpp"
#include "cfd/validation/thin_plate_case.hpp"

namespace finverse::cfd::validation {

ThinSurfaceBench run_thin_surface_bench(double periods, int cells_per_chord) {
  io::ThinPlateSetup p;
  p.thickness = 2.0 / cells_per_chord * p.chord;  // the closed body two cells thick
  const io::ThinPlateFiles files = io::make_thin_plate(p);
  const io::FinInput in = io::make_fin_input(files.mesh, files.motion, "plate mesh", "plate motion");
  io::FinFlowOptions o;
  o.reynolds = 100;
  o.speed = 0.1;
  o.cells_per_chord = cells_per_chord;
  o.periods = periods;
  o.output_periods = 0;
  o.output_interval = p.period / 100;
  ThinSurfaceBench b;
  io::FinFlowStats st;
  o.surface = "sheet";
  io::run_fin_flow(in, o, st);
  b.sheet_s_per_step = st.wall_seconds / static_cast<double>(st.steps);
  b.steps = st.steps;
  b.cells = static_cast<long>(st.grid.cells());
  o.surface = "closed";
  io::run_fin_flow(in, o, st);
  b.closed_s_per_step = st.wall_seconds / static_cast<double>(st.steps);
  // No body: the same grid, boundaries, step and solver options as fin-cfd fin's.
  FlowBoundary bnd;
  bnd[Side::XLo].type = FlowBcType::Inlet;
  bnd[Side::XLo].speed = st.U;
  bnd[Side::XHi].type = FlowBcType::ConvectiveOutlet;
  for (Side s : {Side::YLo, Side::YHi, Side::ZLo, Side::ZHi}) bnd[s].type = FlowBcType::Slip;
  FlowOptions fo;
  fo.nu = st.nu;
  fo.dt = st.dt;
  fo.helmholtz_rtol = 1e-8;
  fo.poisson.rtol = o.poisson_rtol;
  FlowSolver f;
  f.setup(st.grid, bnd, fo);
  const double U = st.U;
  f.initialise([U](double, double, double, double) { return std::array<double, 3>{U, 0, 0}; });
  const auto t0 = std::chrono::steady_clock::now();
  for (long n = 0; n < st.steps; ++n) f.step();
  b.empty_s_per_step =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / static_cast<double>(st.steps);
  return b;
}

}  // namespace finverse::cfd::validation
