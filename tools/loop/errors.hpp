// Exceptions of the closing-the-loop library (issue 34). One-line messages naming the file,
// dataset or flag and what was expected (DESIGN.md section 3); fin-loop prints what() and exits 2.
#pragma once

#include <stdexcept>
#include <string>

namespace finverse::loop {

class InvalidInput : public std::runtime_error {
 public:
  explicit InvalidInput(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace finverse::loop
