// The element interface the assembly and all solvers see.
//
// An element couples a few nodes and uses some of each node's 6 DOFs (a beam or a flat shell
// uses all 6; a 2-D plane-strain solid only ux, uy). Element vectors/matrices are ordered node by
// node, and within a node in the order of active_dofs(). Rotational DOFs are spatial spins (see
// nodal_state.hpp). Elements are immutable during a solve and hold no history, so that many
// threads may evaluate different elements at once; a new element type (corotational triangle
// shell, plane-strain solid) is added by implementing this interface, the solvers stay as they are.
#pragma once

#include <span>
#include <string_view>

#include <Eigen/Core>

#include "fem/nodal_state.hpp"

namespace finverse::fem {

class Element {
 public:
  using VectorRef = Eigen::Ref<Eigen::VectorXd>;
  using MatrixRef = Eigen::Ref<Eigen::MatrixXd>;

  virtual ~Element() = default;

  virtual std::string_view type() const = 0;
  virtual std::span<const int> nodes() const = 0;
  virtual std::span<const int> active_dofs() const = 0;  // subset of 0..5, ascending
  int size() const { return static_cast<int>(nodes().size() * active_dofs().size()); }

  // Internal force f (size()) at the given configuration and, when K is non-null, the consistent
  // tangent dF/d(increment) for the multiplicative update. The tangent of a corotational element
  // is not exactly symmetric away from equilibrium; callers may symmetrise it.
  virtual void internal_force(const NodalState& state, VectorRef f, MatrixRef* K) const = 0;
  // Kelvin-Voigt (stiffness-proportional) damping force f_d = C v for the element velocity v
  // (size(), spatial spins for rotations) and, when C is non-null, the damping matrix
  // C = df_d/dv at this configuration. A corotational element takes C = eta B^T K_l B (B: the
  // map from global variations to its local deformational freedoms, K_l: its local stiffness),
  // so only the rate of deformation is damped and a rigid motion, however fast, is not; the
  // default, for elements without a corotated frame, is Rayleigh's K v with the current tangent.
  virtual void viscous_force(const NodalState& state, const Eigen::Ref<const Eigen::VectorXd>& v, double eta,
                             VectorRef f, MatrixRef* C) const {
    Eigen::MatrixXd K(size(), size());
    Eigen::VectorXd fi(size());
    MatrixRef Kr(K);
    internal_force(state, fi, &Kr);
    K = (0.5 * (K + K.transpose())).eval();
    f = eta * (K * v);
    if (C) *C = eta * K;
  }
  // Consistent mass matrix (size() x size()) at the given configuration.
  virtual void mass_matrix(const NodalState& state, MatrixRef M) const = 0;
  // Equivalent nodal force of the element's own weight under acceleration g (dead load).
  virtual void gravity_force(const NodalState& state, const Vec3& g, VectorRef f) const = 0;
  // Elastic strain energy at the given configuration.
  virtual double strain_energy(const NodalState& state) const = 0;
  // Total mass (for checks and reporting).
  virtual double total_mass() const = 0;
};

}  // namespace finverse::fem
