// Linear-elastic isotropic material of a region (fin ray, membrane, ...). The corotational
// elements use it in their local frame, i.e. linear elasticity for small strains and large
// rotations (DESIGN.md section 5.2).
#pragma once

#include <string>

namespace finverse::fem {

struct Material {
  std::string name;
  double youngs_modulus = 0;  // E [Pa]
  double poisson_ratio = 0;   // nu [-]
  double density = 0;         // rho [kg/m^3]

  double shear_modulus() const { return youngs_modulus / (2.0 * (1.0 + poisson_ratio)); }
};

// Throws InvalidInput naming the material and the offending value unless E > 0 (finite),
// -1 < nu < 0.5 and density > 0 (finite). nu = 0.5 is excluded: the 2-D solid would lock and
// the shell's plane-stress law is still fine, but a bulk modulus of infinity is not a material.
void validate(const Material& material);

}  // namespace finverse::fem
