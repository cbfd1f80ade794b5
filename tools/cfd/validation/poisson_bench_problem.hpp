// The pressure-Poisson benchmark problem, defined once so that finverse's multigrid and the
// peer solvers (hypre PFMG / BoomerAMG in fin-poisson-hypre) solve the same matrix and the same
// right-hand side: a fin-sized uniform core [-0.5,1.5] x [-0.5,0.5] x [-0.25,1.25] stretched
// geometrically to a box of a few chord lengths, all-Neumann boundaries (the fractional-step
// pressure), optionally a sphere masked out as an immersed body, and a smooth source with a
// nonzero mean (which exercises the compatibility projection).
#pragma once

#include "cfd/poisson/poisson_boundary.hpp"
#include "cfd/poisson/face_coefficients.hpp"
#include "cfd/grid/field.hpp"
#include "cfd/grid/stretched_grid.hpp"

namespace finverse::cfd {

struct PoissonBenchProblem {
  StretchedGrid grid;
  FaceCoefficients beta;
  BoundaryConditions bc;
  Field source;  // f of div(beta grad p) = f
};

// n cells per axis, maximum stretch ratio `ratio`; ratio 1 gives the uniform grid of the same box
// (cells of aspect ratio up to 1.7), the reference for how much the stretching costs.
PoissonBenchProblem make_poisson_bench_problem(int n, double ratio, bool mask);

}  // namespace finverse::cfd
