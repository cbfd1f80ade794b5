// Three-node corotational flat shell triangle (membrane + bending, drilling freedoms), 6 DOF per
// node, sharing nodes with the corotational beams.
//
// Element-independent corotational (EICR) formulation: Rankin & Brogan (1986), J. Pressure Vessel
// Technol. 108:165; Felippa & Haugen (2005), "A unified formulation of small-strain corotational
// finite elements: I. Theory", Comput. Methods Appl. Mech. Engrg. 194:2285-2335 (FH below).
//
// Corotated frame Rr = [e1 e2 e3], origin at the current centroid: e1 along side 1-2,
// e3 = (x2 - x1) x (x3 - x1) / |.|, e2 = e3 x e1 (FH sec. 5.2, "side-aligned" frame). Why this
// frame: its spin is an exact, explicit function of the nodal translations (the G matrix below),
// which keeps the consistent tangent exact and cheap; the frames that are invariant to the node
// numbering (best fit by polar decomposition, Battini & Pacoste 2006 / Caselli & Bisegna 2013)
// differ from it only by an in-plane rotation of the order of the membrane shear strain, which is
// small in this small-strain setting (fins: strains < 1 %). The reference frame R0 is the same
// construction on the reference geometry.
//
// Deformational freedoms in Rr: u_bar_a = Rr^T (x_a - x_c) - R0^T (X_a - X_c) and
// theta_bar_a = log(Rr^T R_a R0). The local linear element (flat_shell_triangle.hpp) gives
// f_l = K_l d_l. With local components of the global variations dd_bar = E^T dd
// (E = blockdiag(Rr)), the frame spin w_r = G dd_bar, the projector P = I - T_c - S G (T_c removes
// the centroid translation, S_a = [-skew(x_bar_a); I]) and H = blockdiag(I, Ts^-1(theta_bar_a)):
//   f = E P^T H^T f_l
//   K = E [ P^T (H^T K_l H + K_M) P  - F_nm G  + G^T F_n P  - d(G^T v)/dx_bar P_t ] E^T
// K_M: d(Ts^-T m)/dtheta Ts^-1 per node (FH's K_GM; tangent_inverse_derivative); -F_nm G: rotation
// of the projected forces with the frame (K_GR); G^T F_n P: variation of the lever arms in S (K_GP);
// the last term is the variation of G itself acting on v = S^T H^T f_l, the out-of-balance moment
// of the unprojected local forces, which FH drop (it vanishes for an exactly equilibrated local
// element) but which is needed for a tangent that is exact away from that limit.
//
// Mass: consistent translational mass rho h A / 12 (1 + delta_ab) I; rotary inertia of the plate
// (rho h^3 / 12 per area, a fraction (h/l)^2 / 12 of the translational one) lumped as
// rho h^3 A / 36 I per node, made isotropic (including the drilling freedom) so that the mass
// matrix is configuration independent and positive definite. Gravity: rho h A / 3 g per node.
#pragma once

#include <array>

#include <Eigen/Core>

#include "fem/element.hpp"
#include "fem/flat_shell_triangle.hpp"
#include "fem/material.hpp"

namespace finverse::fem {

class CorotationalShell final : public Element {
 public:
  // The element keeps its own copy of the material, so every element may have its own E (the
  // inverse fit) and its own thickness. Corners in any order; the normal is (X2-X1) x (X3-X1).
  CorotationalShell(int node1, int node2, int node3, const Vec3& X1, const Vec3& X2,
                    const Vec3& X3, const Material& material, double thickness);

  std::string_view type() const override { return "corotational_shell"; }
  std::span<const int> nodes() const override { return nodes_; }
  std::span<const int> active_dofs() const override;
  void internal_force(const NodalState& state, VectorRef f, MatrixRef* K) const override;
  // Damps the rate of the local freedoms d_l with eta K_l (Kelvin-Voigt).
  void viscous_force(const NodalState& state, const Eigen::Ref<const Eigen::VectorXd>& v, double eta, VectorRef f,
                     MatrixRef* C) const override;
  void mass_matrix(const NodalState& state, MatrixRef M) const override;
  void gravity_force(const NodalState& state, const Vec3& g, VectorRef f) const override;
  double strain_energy(const NodalState& state) const override;
  double total_mass() const override { return mass_; }

  // Deformational freedoms d_l = [u_bar_a, theta_bar_a] (a = 1..3) in the corotated frame.
  Vec18 local_deformation(const NodalState& state) const;
  // Corotated frame [e1 e2 e3] at the given configuration.
  Mat3 corotated_frame(const NodalState& state) const;

  double area() const { return area_; }
  double thickness() const { return thickness_; }
  const Material& material() const { return material_; }
  const Mat3& reference_frame() const { return R0_; }
  const Mat18& local_stiffness() const { return kl_; }

 private:
  struct Kinematics;
  struct Projection;
  Kinematics kinematics(const NodalState& state) const;
  Projection projection(const Kinematics& k) const;

  std::array<int, 3> nodes_;
  Material material_;
  double thickness_ = 0;
  Mat3 R0_;
  std::array<Vec3, 3> xbar0_;  // reference corner coordinates in R0, relative to the centroid
  double area_ = 0;
  double mass_ = 0;
  Mat18 kl_;
};

}  // namespace finverse::fem
