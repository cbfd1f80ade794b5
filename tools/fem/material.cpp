// Validation of material constants (see material.hpp).
#include "fem/material.hpp"

#include <cmath>
#include <sstream>

#include "fem/errors.hpp"

namespace finverse::fem {

void validate(const Material& m) {
  auto fail = [&](const char* what, double value, const char* expected) {
    std::ostringstream os;
    os.precision(6);
    os << "material '" << m.name << "': " << what << " = " << value << ", expected " << expected;
    throw InvalidInput(os.str());
  };
  if (!std::isfinite(m.youngs_modulus) || m.youngs_modulus <= 0)
    fail("Young's modulus E", m.youngs_modulus, "a finite value > 0");
  if (!std::isfinite(m.poisson_ratio) || m.poisson_ratio <= -1.0 || m.poisson_ratio >= 0.5)
    fail("Poisson ratio nu", m.poisson_ratio, "-1 < nu < 0.5");
  // density 0 is rejected too: the dynamic solvers' mass matrix would be singular and no real
  // fin ray or membrane is massless (the materials JSON parser rejects it as well).
  if (!std::isfinite(m.density) || m.density <= 0) fail("density", m.density, "a finite value > 0");
}

}  // namespace finverse::fem
