// Element-wise comparison of two arrays under a tolerance, with the statistics fin-diff prints:
// largest absolute and relative error, where the worst element sits, how many fail, and NaN
// mismatches (NaN in one file where the other has a number; NaN in both is equal).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/nd_array.hpp"
#include "core/tolerances.hpp"

namespace finverse {

struct Comparison {
  std::string object;      // "/points", "frame_000001.vtp: PointData/U", ...
  bool ok = true;
  std::string status;      // equal | within | DIFFERENT | NaN | SHAPE | DTYPE | MISSING | EXTRA
  std::string detail;      // shapes, dtypes, values that differ
  double max_abs = 0;
  double max_rel = 0;
  std::string where;       // index of the worst element, e.g. "[12,3,0]"
  std::size_t n_bad = 0;
  std::size_t n = 0;
  Tolerance tol;
};

Comparison compare_values(const std::string& object, const NdArray<double>& reference, const NdArray<double>& candidate,
                          Tolerance tol);
Comparison compare_strings(const std::string& object, const std::vector<std::string>& reference,
                           const std::vector<std::string>& candidate);
Comparison mismatch(const std::string& object, const std::string& status, const std::string& detail);

// The per-object table: object, status, max abs, max rel, where, tolerance. Only differing
// rows unless `all`.
std::string format_table(const std::vector<Comparison>& rows, bool all);

}  // namespace finverse
