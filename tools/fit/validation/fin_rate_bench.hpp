// Speed of an eq. (2) evaluation on the fin (issue 45, goal 8; results/bench/fit_fin_rate.json):
// the fit as `fin-fit run` sets it up on a case's stage files, evaluated at the same seeded points
// by three ways of solving the increment in one run: newton (QuasiStaticIncrement from the base),
// stored (the same converged increment from a reference solution,
// fem/stored_tangent_increment.hpp) and linear (Newton's first step on the base's stored tangent,
// fem/linear_increment.hpp; not converged). Graded: the stored route's seconds per evaluation on
// `threads` threads <= 0.1 and its increments within 1e-6 of Newton's. Reported: every route's
// rate and ratio, the stored route's iterations and fallbacks, the linear route's differences.
// The polish's own workload too: the references moved to a point, then one finite-difference
// Jacobian there on the stored route (its columns on the reference's tangent), against the same
// Jacobian factorising per column; graded: within 1e-4 of Newton's Jacobian.
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
