// Exceptions thrown by the structural FEM library. Each carries a one-line message that names the
// cause (DESIGN.md section 3, "Errors"); executables print what() and exit with code 2.
//
// They derive from std::runtime_error (not finverse::Error) so that finverse_fem builds with only
// Eigen/OpenMP/SuiteSparse; callers that want a single catch site catch std::runtime_error.
#pragma once

#include <stdexcept>
#include <string>

namespace finverse::fem {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// Bad model data: non-physical material, NaN load, a node index out of range, ...
class InvalidInput : public Error {
 public:
  using Error::Error;
};

// The (effective) stiffness matrix cannot be factorised: the structure has a free rigid-body
// mode, or the tangent lost definiteness beyond what the solver can handle.
class SingularMatrix : public Error {
 public:
  using Error::Error;
};

// Newton iterations (static or within a time step) did not reach the tolerances even after
// the allowed step cuts.
class NotConverged : public Error {
 public:
  using Error::Error;
};

}  // namespace finverse::fem
