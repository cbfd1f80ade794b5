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

// An Error whose one line has been printed already: an MPI run's rank 0 says it before any rank
// exits, since the launcher ends the job at the first non-zero exit and could take the line with
// it (cfd/parallel/rank_pressure_system.hpp). Executables exit kExitError without repeating it.
class ReportedError : public Error {
 public:
  using Error::Error;
};

// Exit codes shared by every executable.
enum ExitCode : int {
  kExitOk = 0,
  kExitDifferent = 1,  // fin-diff: files differ; validation: a metric failed
  kExitError = 2,      // bad input, I/O failure, solver failure
};

}  // namespace finverse
