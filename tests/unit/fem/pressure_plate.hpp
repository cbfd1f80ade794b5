// The hybrid plate of data/cases/hybrid_plate.json with every material at one Poisson ratio,
// loaded by its pressure (the load factor is the time), for the tests of the stored tangent and
// the increments built on it: the pressure bends the soft plate well into the nonlinear range
// (tip deflection about a fifth of the chord).
#pragma once

#include <memory>
#include <string>

#include "fem/static_solver.hpp"
#include "fem/validation/hybrid_plate_model.hpp"

namespace finverse::fem::test_plates {

inline validation::HybridPlateCase pressure_plate_case(double nu) {
  validation::HybridPlateCase c;
  c.chord = 1.0, c.span = 1.0, c.thickness = 0.01;
  c.plate = {"plate", 1e5, nu, 10.0};
  const double E[3] = {1e8, 1e7, 5e7}, z[3] = {-0.5, 0.0, 0.5};
  for (int b = 0; b < 3; ++b) c.beams.push_back({"b" + std::to_string(b + 1), z[b], {"b", E[b], nu, 10.0}, 0.04, 0.02});
  c.pressure = 0.5;
  c.heave_amplitude = 0.1, c.frequency = 0.5, c.periods = 2, c.time_step = 0.005;
  return c;
}

// The plate on an n x n grid.
inline std::unique_ptr<Model> pressure_plate(double nu, int n = 4,
                                             validation::HybridPlateLoad load = validation::HybridPlateLoad::pressure) {
  return std::make_unique<Model>(std::move(validation::build_hybrid_plate(pressure_plate_case(nu), n, n, load).model));
}

// The static state under the pressure at load factor lambda (10 steps).
inline NodalState pressed_state(const Model& m, double lambda) {
  StaticSolver s(m, StaticOptions{.steps = 10});
  NodalState x = m.reference_state();
  s.solve(x, 0.0, lambda);
  return x;
}

}  // namespace finverse::fem::test_plates
