// Rotations of a base state known by its positions, relaxed to moment balance (eq. (2)'s base).
// Video gives node positions only; state_from_positions.hpp estimates each node's rotation by a
// rigid fit of its 1-ring, which is the local tangent rotation to O(h). On the fin the rays are
// three orders stiffer than the membrane, so an O(h) error of a ray node's rotation is a large
// bending moment: the base then sits far from equilibrium and the quasi-static increment from it
// is biased (measured on the trout twin: objective at the true moduli 2.0e-6 m with the 1-ring
// rotations, 4.9e-8 m relaxed) and needs ~12 Newton iterations instead of 5-7. Relaxing the
// rotations with every translation held at the tracked position -- the rotations the structure
// itself takes with those positions, a static solve over the rotational DOFs -- leaves the
// positions untouched and removes the moment imbalance, so "the base is taken to be in
// equilibrium" (seed paper sec. 2.2) is needed for the forces only. The relaxed rotations depend
// on the moduli (the ray/membrane stiffness ratio), so the objective relaxes with the moduli it
// evaluates: one held model per workspace, its translations prescribed at every instant's base.
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
