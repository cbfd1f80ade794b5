// Rotations of a base state known by its positions, relaxed to moment balance (eq. (2)'s base).
// The 1-ring rigid fits (state_from_positions.hpp) are the tangent rotation to O(h), a large
// bending moment on rays a thousand times stiffer than the membrane. Relaxing the free rotations
// with every translation held removes that moment imbalance and leaves the positions untouched.
// The result depends on the moduli, so the objective relaxes under the moduli it evaluates.
// Measured effect: docs/studies/fit_on_the_fin.md.
#pragma once

#include <memory>
#include <vector>

#include "fem/model.hpp"
#include "fem/nodal_state.hpp"
#include "fem/static_solver.hpp"

namespace finverse::fit {

class RotationRelaxation {
 public:
  // `model` (kept by reference, modified): every free translational DOF is prescribed, at each
  // instants[j], at bases[j]'s position (the prescription of the instant nearest the time asked).
  // Prescribed rotations (the root) keep their own functions.
  RotationRelaxation(fem::Model& model, const std::vector<double>& instants,
                     const std::vector<fem::NodalState>& bases, fem::StaticOptions options = {.steps = 1});
  // The base at instants[j] with its free rotations in moment balance under the model's current
  // moduli; positions unchanged. Throws fem::NotConverged / fem::SingularMatrix.
  fem::NodalState relax(const fem::NodalState& base, double t);

 private:
  std::unique_ptr<fem::StaticSolver> solver_;
};

// One-off form: `model` is modified (a model built for this purpose).
fem::NodalState relax_rotations(fem::Model& model, const fem::NodalState& base, double t,
                                const fem::StaticOptions& options = {.steps = 1});

}  // namespace finverse::fit
