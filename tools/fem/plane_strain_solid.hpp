// Nine-node (biquadratic Lagrange, Q9) plane-strain solid, total Lagrangian, St. Venant-Kirchhoff.
//
// Formulation (Bathe, "Finite Element Procedures", 2nd ed., sec. 6.2.3; Belytschko, Liu & Moran,
// "Nonlinear Finite Elements for Continua and Structures", sec. 4.9): with reference gradients
// G_a = dN_a/dX, the deformation gradient F = sum_a x_a G_a^T, Green-Lagrange strain
// E = (F^T F - I)/2 and second Piola-Kirchhoff stress S = lambda tr(E) I + 2 mu E (plane strain:
// E_zz = 0, so the in-plane law is the 3-D one restricted to x, y, and S_zz = lambda tr(E)).
//   f_a  = int F S G_a dV0
//   K_ab = int B_a^T D B_b dV0 + int (G_a^T S G_b) I dV0        (material + geometric part)
// with B the 3x2 Voigt operator of dE (E_xx, E_yy, 2E_xy) built from F. The tangent is the exact
// derivative of f, symmetric; the response is frame-invariant (rigid rotations give f = 0).
// Mass: consistent, M_ab = int rho N_a N_b dV0 I. Gravity is a dead load from the reference
// configuration; only its in-plane (x, y) components act on a plane-strain slice.
// Volumes are per `thickness` of depth (1 m by default, i.e. forces in N per metre).
//
// Why Q9: the Turek-Hron flag and the fin-like plates are slender and bending-dominated. A
// bilinear Q4 element cannot represent the linear through-thickness bending strain without
// parasitic shear, so it locks (its tip deflection converges from far below and needs many
// elements through the thickness); the biquadratic field of Q9 contains pure bending exactly,
// so one element through the thickness already carries the bending stress and the error falls as
// h^4 in displacement-type quantities. Q9 with full 3x3 Gauss integration has no spurious modes
// (unlike the serendipity Q8 with reduced integration), and nu = 0.4 is far from the
// incompressible limit, so volumetric locking is not a concern. The structured flag mesh maps to
// quadrilaterals naturally; the curved clamped edge is represented by the quadratic geometry.
//
// Node order: corners counter-clockwise (0..3), mid-sides 4 (0-1), 5 (1-2), 6 (2-3), 7 (3-0),
// centre 8. The element lies in a plane z = const of the global frame; it uses DOFs ux, uy.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "fem/element.hpp"
#include "fem/material.hpp"

namespace finverse::fem {

class PlaneStrainSolid final : public Element {
 public:
  static constexpr int kNodes = 9;
  static constexpr int kGauss = 9;  // 3 x 3
  using Mat2 = Eigen::Matrix2d;
  using Vec2 = Eigen::Vector2d;

  // Throws InvalidInput for a bad material, a thickness <= 0, nodes not in one plane z = const,
  // or a non-positive Jacobian at a Gauss point (inverted or badly distorted element).
  PlaneStrainSolid(const std::array<int, kNodes>& nodes, const std::array<Vec3, kNodes>& X,
                   const Material& material, double thickness = 1.0);

  std::string_view type() const override { return "plane_strain_q9"; }
  std::span<const int> nodes() const override { return nodes_; }
  std::span<const int> active_dofs() const override;
  void internal_force(const NodalState& state, VectorRef f, MatrixRef* K) const override;
  void mass_matrix(const NodalState& state, MatrixRef M) const override;
  void gravity_force(const NodalState& state, const Vec3& g, VectorRef f) const override;
  double strain_energy(const NodalState& state) const override;
  double total_mass() const override { return material_.density * volume_; }

  // Stress at one Gauss point: reference position, second Piola-Kirchhoff S, Cauchy sigma
  // (in-plane) and the out-of-plane Cauchy stress sigma_zz that keeps E_zz = 0.
  struct PointStress {
    Vec2 X;
    Mat2 second_piola_kirchhoff;
    Mat2 cauchy;
    double cauchy_zz = 0;
  };
  std::array<PointStress, kGauss> stresses(const NodalState& state) const;

  double volume() const { return volume_; }
  double lame_lambda() const { return lambda_; }
  double lame_mu() const { return mu_; }
  const Material& material() const { return material_; }

  // Q9 shape functions and their derivatives with respect to (xi, eta) at a point of [-1,1]^2.
  static Eigen::Matrix<double, kNodes, 1> shape(double xi, double eta);
  static Eigen::Matrix<double, kNodes, 2> shape_derivatives(double xi, double eta);

 private:
  using Positions = Eigen::Matrix<double, kNodes, 2>;
  Positions current_positions(const NodalState& state) const;

  std::array<int, kNodes> nodes_;
  Material material_;
  double thickness_;
  double lambda_, mu_;
  double volume_ = 0;
  // Per Gauss point: dN/dX (9 x 2), N, weight * det(J) * thickness, reference position.
  std::array<Eigen::Matrix<double, kNodes, 2>, kGauss> grad_;
  std::array<Eigen::Matrix<double, kNodes, 1>, kGauss> N_;
  std::array<double, kGauss> weight_;
  std::array<Vec2, kGauss> Xg_;
};

}  // namespace finverse::fem
