// Two-node corotational 3-D beam with a tapered rectangular section.
//
// Formulation: Battini & Pacoste (2002), "Co-rotational beam elements with warping effects in
// instability problems", Comput. Methods Appl. Mech. Engrg. 191:1755-1789, section 3 (also
// Battini's thesis, KTH 2002, ch. 3): element-independent corotational frame built from the chord
// and the mean of the nodal y axes; local rotations theta_bar_i = log(Rr^T R_i R0); the consistent
// tangent K_g = B^T (Ba^T K_l Ba + Kh) B + D N - E Q G^T E^T + E G a r (their eqs. (49)-(56)).
// Large rotations, small strains; nodal rotations updated multiplicatively.
//
// Local element: linear Euler-Bernoulli, stiffness obtained by inverting the exact flexibility of
// the beam under end forces (the bending moment is linear along a load-free element, the axial
// force and torque constant):
//   1/k_a = int dx/EA,  1/k_t = int dx/GJ,  F_b = int b b^T / EI dx,  b = [xi - 1, xi]
// integrated with Gauss-Legendre points. For a uniform section this is the classical 4EI/L, 2EI/L
// stiffness; for a tapered ray it is exact to quadrature accuracy (a displacement-based cubic
// element would not be), so a ray needs few elements.
// Why Euler-Bernoulli and not Timoshenko: fin rays are slender (length/thickness > 20, shear
// flexibility below 0.5 %), the validation references (elastica, Euler-Bernoulli frequencies) are
// shear-rigid, and the flexibility form needs no shear-locking treatment. Shear flexibility could
// be added as int 1/(kGA) dx / L^2 to F_b if thick rays ever matter.
//
// Mass: consistent mass of the same element (linear axial/torsion, cubic Hermite bending
// interpolation; translational and rotary inertia rho*A, rho*I_y, rho*I_z, rho*(I_y+I_z)),
// integrated with Gauss points for the varying section and rotated with the current corotated
// frame: M = E M_l E^T. Gyroscopic terms and the derivative of E with respect to the
// configuration are neglected (exact in the linear range; see generalized_alpha.hpp).
#pragma once

#include <array>

#include <Eigen/Core>

#include "fem/beam_section.hpp"
#include "fem/element.hpp"
#include "fem/material.hpp"

namespace finverse::fem {

class CorotationalBeam final : public Element {
 public:
  using Vec12 = Eigen::Matrix<double, 12, 1>;
  using Mat12 = Eigen::Matrix<double, 12, 12>;

  struct Options {
    int stiffness_gauss_points = 4;
    int mass_gauss_points = 5;  // exact for a linearly tapered width x thickness (degree 8)
  };

  // y_axis_hint: a vector not parallel to the element that fixes the section's local y axis
  // (the width direction): e2 = normalised component of the hint orthogonal to the chord.
  CorotationalBeam(int node1, int node2, const Vec3& X1, const Vec3& X2, const Vec3& y_axis_hint,
                   const Material& material, const TaperedRectangle& section, Options options);
  CorotationalBeam(int node1, int node2, const Vec3& X1, const Vec3& X2, const Vec3& y_axis_hint,
                   const Material& material, const TaperedRectangle& section)
      : CorotationalBeam(node1, node2, X1, X2, y_axis_hint, material, section, Options{}) {}

  std::string_view type() const override { return "corotational_beam"; }
  std::span<const int> nodes() const override { return nodes_; }
  std::span<const int> active_dofs() const override;
  void internal_force(const NodalState& state, VectorRef f, MatrixRef* K) const override;
  // Damps the rate of [u_bar, theta_bar_1, theta_bar_2] with eta k_l (Kelvin-Voigt).
  void viscous_force(const NodalState& state, const Eigen::Ref<const Eigen::VectorXd>& v, double eta, VectorRef f,
                     MatrixRef* C) const override;
  void mass_matrix(const NodalState& state, MatrixRef M) const override;
  void gravity_force(const NodalState& state, const Vec3& g, VectorRef f) const override;
  double strain_energy(const NodalState& state) const override;
  double total_mass() const override { return mass_; }

  // Local deformation [u_bar, theta_bar_1, theta_bar_2] and its conjugate local forces
  // [N, m_1, m_2] (moments in the corotated frame).
  struct Local {
    double elongation = 0;
    Vec3 theta1 = Vec3::Zero(), theta2 = Vec3::Zero();
    double axial_force = 0;
    Vec3 moment1 = Vec3::Zero(), moment2 = Vec3::Zero();
  };
  Local local_state(const NodalState& state) const;

  double reference_length() const { return l0_; }
  const Mat3& reference_frame() const { return R0_; }  // columns e1 (axis), e2 (width), e3
  const Material& material() const { return material_; }
  const TaperedRectangle& section() const { return section_; }
  // 7x7 local stiffness of [u_bar, theta_bar_1, theta_bar_2].
  const Eigen::Matrix<double, 7, 7>& local_stiffness() const { return kl_; }
  // 12x12 mass in the corotated frame (local translations and rotations of both nodes).
  const Mat12& local_mass() const { return ml_; }

 private:
  struct Kinematics;
  struct Projection;
  Kinematics kinematics(const NodalState& state) const;
  Projection projection(const Kinematics& k) const;

  std::array<int, 2> nodes_;
  Material material_;
  TaperedRectangle section_;
  Mat3 R0_;
  double l0_ = 0;
  double mass_ = 0;
  Eigen::Matrix<double, 7, 7> kl_;
  Mat12 ml_;
  std::array<double, 2> gravity_share_{};  // int rho A N_i dx for linear N_i
};

}  // namespace finverse::fem
