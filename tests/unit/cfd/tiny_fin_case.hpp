// Shared fixtures of the fin-run tests (test_fin_flow.cpp, test_fin_checkpoint.cpp): the heaving
// and pitching thin plate on a very coarse grid, a few steps long, so a whole fin-cfd fin run
// takes about a second.
#pragma once

#include "cfd/io/fin_flow_case.hpp"
#include "cfd/io/fin_input.hpp"
#include "cfd/validation/thin_plate_case.hpp"

namespace finverse::cfd::io::test {

// The plate as fin-cfd reads it (mesh.h5 + motion.h5 contents), closed-body thickness in chords.
inline FinInput tiny_plate(double thickness = 0.2) {
  ThinPlateSetup p;
  p.nx = 6;
  p.nz = 8;
  p.thickness = thickness * p.chord;
  const auto f = make_thin_plate(p);
  return make_fin_input(f.mesh, f.motion, "plate/mesh.h5", "plate/motion.h5");
}

// A 6-cells-per-chord grid around it; `periods` of the 0.2 s motion with outputs every 5 ms.
inline FinFlowOptions tiny_options(double periods) {
  FinFlowOptions o;
  o.reynolds = 100;
  o.speed = 0.1;
  o.cells_per_chord = 6;
  o.upstream = o.lateral = o.spanwise = 1;
  o.downstream = 1.5;
  o.wake = 0.5;
  o.stretch_ratio = 1.3;
  o.periods = periods;
  o.output_periods = 0;
  return o;
}

}  // namespace finverse::cfd::io::test
