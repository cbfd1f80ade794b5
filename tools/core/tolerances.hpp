// Per-dataset comparison tolerances for fin-diff and the golden-file regression tests.
// A tolerance file is JSON:
//   {"default": {"atol": 1e-12, "rtol": 1e-9},
//    "datasets": {"/points": {"atol": 1e-6}, "/coefficients/*": {"rtol": 1e-3}},
//    "ignore": ["/quality/*"]}
// Patterns are shell globs (fnmatch) on the dataset path; the first matching entry wins.
// An element passes when |candidate - reference| <= atol + rtol * |reference| (numpy's rule).
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace finverse {

struct Tolerance {
  double atol = 0;
  double rtol = 0;
};

class Tolerances {
 public:
  Tolerances() = default;
  explicit Tolerances(Tolerance fallback) : default_(fallback) {}
  static Tolerances load(const std::filesystem::path& path);  // throws finverse::Error naming the file

  Tolerance for_object(const std::string& path) const;
  bool ignored(const std::string& path) const;
  void set_default(Tolerance t) { default_ = t; }
  void add(const std::string& pattern, Tolerance t) { rules_.emplace_back(pattern, t); }
  void ignore(const std::string& pattern) { ignore_.push_back(pattern); }

 private:
  Tolerance default_{0, 0};
  std::vector<std::pair<std::string, Tolerance>> rules_;
  std::vector<std::string> ignore_;
};

}  // namespace finverse
