// Cost of one Newton iteration of the static solver against the number of DOFs (the FEM
// benchmark, results/bench/fem.json): the hybrid plate (hybrid_plate_model.hpp) on n x n grids,
// a first load step solved to set up the symbolic factorisation, then a second solve from the
// reference state timed and divided by its iterations (assembly + numeric factorisation + solve,
// as inside the fit's GA). The growth exponent p of t ~ DOF^p is fitted by least squares on the
// logarithms.
#pragma once

#include <vector>

#include "fem/sparse_solver.hpp"
#include "fem/validation/hybrid_plate_model.hpp"

namespace finverse::fem::validation {

struct NewtonScalingPoint {
  int n = 0;           // grid cells per side
  int free_dofs = 0;
  int iterations = 0;  // of the timed solve
  double seconds_per_iteration = 0;
};

std::vector<NewtonScalingPoint> newton_scaling(const HybridPlateCase& c, const std::vector<int>& sizes,
                                               SolverBackend backend);

// Least-squares slope of log(seconds_per_iteration) against log(free_dofs).
double growth_exponent(const std::vector<NewtonScalingPoint>& points);

}  // namespace finverse::fem::validation
