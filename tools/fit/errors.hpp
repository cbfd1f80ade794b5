// Exceptions of the inverse-fit library. One-line messages naming the file, dataset or flag
// (DESIGN.md section 3); executables print what() and exit with code 2. Derived from
// std::runtime_error, as fem's, so that finverse_fit builds without finverse_core.
#pragma once

#include <stdexcept>
#include <string>

namespace finverse::fit {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// Bad specification or data: inverted bounds, unknown parameter name, node counts that differ...
class InvalidInput : public Error {
 public:
  using Error::Error;
};

}  // namespace finverse::fit
