// Speed of an eq. (2) evaluation on the fin (issue 45, goal 8; results/bench/fit_fin_rate.json):
// the fit as `fin-fit run` sets it up on a case's stage files (mesh, motion, loads, materials;
// the default case's fin mesh), evaluated at the same seeded points by three ways of solving the
// increment side by side in one run:
//   newton   the converged quasi-static increment from the base (QuasiStaticIncrement): element
//            evaluations, assemblies and about ten factorisations per increment;
//   stored   the same converged increment, solved from a reference solution at the materials
//            file's moduli on its stored tangent (fem/stored_tangent_increment.hpp): one
//            factorisation, Anderson-mixed force-only iterations, a true tangent when they stall;
//   linear   Newton's first step from each base's stored tangent (fem/linear_increment.hpp):
//            one weighted gather, one factorisation and one solve per instant; not converged.
// Graded: the converged (stored) route's seconds per evaluation on `threads` threads <= 0.1
// (10 evaluations per second) and its increments within 1e-6 of Newton's. Reported: every
// route's rate, the ratios, the stored route's iterations and fallbacks, and how far the linear
// increments and objective lie from Newton's at the same points.
#pragma once

#include <filesystem>

#include "core/summary.hpp"
#include "fit/io/file_fit.hpp"

namespace finverse::fit::validation {

struct FinRateOptions {
  io::FileFitOptions files;  // mesh, motion, loads, materials, base, instants (as fin-fit run)
  int points = 16;           // seeded points, each evaluated once per route
  double spread = 2.0;       // moduli within a factor `spread` of the materials file's (log-uniform)
  unsigned seed = 1;
  int threads = 2;
};

Summary run_fin_rate_bench(const FinRateOptions& options);

}  // namespace finverse::fit::validation
