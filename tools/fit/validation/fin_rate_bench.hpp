// Speed of an eq. (2) evaluation on the fin (issue 45, goal 8; results/bench/fit_fin_rate.json):
// the fit as `fin-fit run` sets it up on a case's stage files (mesh, motion, loads, materials;
// the default case's fin mesh), evaluated at the same seeded points by the two ways of solving
// the increment side by side in one run:
//   newton   the converged quasi-static increment (QuasiStaticIncrement): element evaluations,
//            assemblies and factorisations per Newton iteration;
//   linear   its first Newton step from each base's stored tangent (fem/linear_increment.hpp):
//            one weighted gather, one factorisation and one solve per instant.
// Graded: linear evaluations per second on `threads` threads >= 10. Reported: newton's rate, the
// ratio, and how far the linear increments and objective lie from Newton's at the same points.
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
