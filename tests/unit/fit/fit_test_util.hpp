// Small builders shared by the fit unit tests: a parameter of a search space, and the hybrid
// plate of data/cases/hybrid_plate.json in memory (nondimensional: rho_f = U = chord = 1).
#pragma once

#include <string>

#include "fem/validation/hybrid_plate_model.hpp"
#include "fit/parameter_space.hpp"

namespace finverse::fit::test {

inline Parameter param(const std::string& name, double lo, double hi, Scale s = Scale::log10) {
  Parameter p;
  p.name = name;
  p.lower = lo;
  p.upper = hi;
  p.scale = s;
  return p;
}

inline fem::validation::HybridPlateCase hybrid_plate_case() {
  fem::validation::HybridPlateCase c;
  c.chord = 1.0, c.span = 1.0, c.thickness = 0.01;
  c.plate = {"plate", 1e5, 0.3, 10.0};
  const double E[3] = {1e8, 1e7, 5e7}, z[3] = {-0.5, 0.0, 0.5};
  for (int b = 0; b < 3; ++b)
    c.beams.push_back({"b" + std::to_string(b + 1), z[b], {"b", E[b], 0.3, 10.0}, 0.04, 0.02});
  c.heave_amplitude = 0.1, c.frequency = 0.5, c.periods = 2, c.time_step = 0.005;
  return c;
}

}  // namespace finverse::fit::test
