// Tapered solid rectangular beam section (a fin ray): width b along the element's local y axis,
// thickness t along local z, each varying linearly from node 1 to node 2.
//
// Section constants at a point: A = b t, I_y = b t^3/12 (bending about y, the thin direction),
// I_z = t b^3/12, torsion constant J of a solid rectangle (Roark, 7th ed., table 10.7 case 4):
//   J = a c^3 [1/3 - 0.21 (c/a)(1 - c^4/(12 a^4))],  a = max(b,t), c = min(b,t)
// (error < 0.2 % for any aspect ratio). Integrals along the element use Gauss-Legendre points;
// the stiffness integrals are flexibilities (integrals of 1/EA, 1/EI, 1/GJ), see
// corotational_beam.hpp.
#pragma once

#include <array>
#include <span>

namespace finverse::fem {

struct SectionConstants {
  double area = 0;  // A
  double iy = 0;    // integral z^2 dA
  double iz = 0;    // integral y^2 dA
  double j = 0;     // Saint-Venant torsion constant
  double polar() const { return iy + iz; }  // polar moment, for torsional rotary inertia
};

SectionConstants rectangle(double width, double thickness);

struct TaperedRectangle {
  std::array<double, 2> width{};      // b at node 1, node 2 [m]
  std::array<double, 2> thickness{};  // t at node 1, node 2 [m]

  static TaperedRectangle uniform(double width, double thickness) {
    return {{width, width}, {thickness, thickness}};
  }
  // Section at xi in [0, 1] along the element.
  SectionConstants at(double xi) const;
  // Throws InvalidInput unless all dimensions are finite and > 0.
  void validate() const;
};

// Gauss-Legendre points and weights on [0, 1], n = 1..8.
struct GaussRule {
  std::span<const double> points;
  std::span<const double> weights;
};
GaussRule gauss_legendre_01(int n);

}  // namespace finverse::fem
