// The one error type that crosses library boundaries. Its message is a single line that names
// the file, dataset or flag at fault and what was expected (DESIGN.md section 3, "Errors");
// executables print it and exit non-zero.
#pragma once

#include <stdexcept>
#include <string>

namespace finverse {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// Exit codes shared by every executable.
enum ExitCode : int {
  kExitOk = 0,
  kExitDifferent = 1,  // fin-diff: files differ; validation: a metric failed
  kExitError = 2,      // bad input, I/O failure, solver failure
};

}  // namespace finverse
