// Parallel, deterministic assembly of internal forces, mass/stiffness products and the sparse
// (effective) stiffness matrix.
//
// Two phases: (1) every element writes its vector/matrices into its own slot of a flat buffer
// (OpenMP over elements; slots never overlap); (2) every global vector entry and every nonzero of
// the matrix is the sum of its element contributions in element order (OpenMP over rows/columns).
// No atomics, no per-thread partial sums: the result is bit-identical for any thread count
// (DESIGN.md section 3, "Determinism"). The price is memory for one matrix per element, which is
// small for beams (1.2 kB) and shells (2.6 kB). Loops too short to pay for a parallel region
// (< 64 elements, < 4096 DOFs, < 16384 nonzeros) run serially -- on a loaded machine a barrier
// can cost milliseconds.
//
// The matrix holds the upper triangle of the free-DOF block of k_coeff*K + m_coeff*M, with K
// symmetrised element by element: the corotational tangent is non-symmetric only through terms
// proportional to the out-of-balance moments (Simo & Vu-Quoc 1986; Battini & Pacoste 2002 sec. 4),
// which vanish at equilibrium, so Newton with the symmetric part still converges quadratically
// near the solution while we keep the cheaper symmetric factorisation (LDL^T / Cholesky instead
// of LU). Its sparsity pattern is fixed at construction, so the symbolic factorisation is reused.
// With full_matrix the whole free block is assembled and K is not symmetrised: the consistent
// non-symmetric tangent, for an LU solver (dead end moments, where the skew part does not vanish
// at equilibrium; StaticOptions::unsymmetric_tangent).
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "fem/dof_map.hpp"
#include "fem/model.hpp"

namespace finverse::fem {

struct AssemblyRequest {
  bool matrix = false;                // assemble k_coeff*K + m_coeff*M on the free DOFs
  double stiffness_coefficient = 1.0;
  double mass_coefficient = 0.0;
  const Eigen::VectorXd* mass_times = nullptr;       // full-length vector a: also compute M a
  const Eigen::VectorXd* stiffness_times = nullptr;  // full-length vector v: also compute K v
  double time = 0;  // evaluates the model's stiffness field (per-element E, E(t)) at this time
  // Kelvin-Voigt damping (Element::viscous_force) with coefficient viscosity at this full-length
  // velocity: also compute the damping force f_d = C v, and add damping_coefficient * C to the
  // matrix (C scaled by the stiffness field, like K).
  const Eigen::VectorXd* viscous_velocity = nullptr;
  double viscosity = 0;
  double damping_coefficient = 0;
};

class Assembler {
 public:
  using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  Assembler(const Model& model, const DofMap& dofs, bool full_matrix = false);

  // Always computes the internal force; the rest as requested.
  void assemble(const NodalState& state, const AssemblyRequest& request);

  const Eigen::VectorXd& internal_force() const { return f_int_; }        // full length
  const Eigen::VectorXd& mass_product() const { return f_mass_; }         // full length
  const Eigen::VectorXd& stiffness_product() const { return f_stiff_; }   // full length
  const Eigen::VectorXd& damping_force() const { return f_visc_; }        // full length
  const SparseMatrix& matrix() const { return matrix_; }  // upper (or full), free DOFs
  bool full_matrix() const { return full_; }

  double strain_energy(const NodalState& state, double time = 0) const;
  // 1/2 v^T M v with M at the given configuration.
  double kinetic_energy(const NodalState& state, const Eigen::VectorXd& velocity);

  const DofMap& dofs() const { return dofs_; }
  const Model& model() const { return model_; }

  // The element-by-element buffers behind the last assembly, for callers that recombine element
  // matrices themselves (tangent_basis.hpp): element e's stiffness (as assembled: symmetrised
  // unless full_matrix, times its stiffness-field scale) is the column-major n x n block at
  // element_stiffness()[matrix_offset(e)], n = model().element(e).size(); its vectors (internal
  // force, K v) sit at vector_offset(e). element_stiffness() holds the last assembly that asked
  // for the matrix or for K v.
  const std::vector<double>& element_stiffness() const { return ke_; }
  const std::vector<double>& element_stiffness_product() const { return fk_; }  // K_e v_e (stiffness_times)
  int matrix_offset(int element) const { return mat_offset_[element]; }
  int vector_offset(int element) const { return vec_offset_[element]; }
  int matrix_buffer_size() const { return mat_offset_.back(); }
  int vector_buffer_size() const { return vec_offset_.back(); }
  // Element vectors / matrices laid out as those buffers, summed into the global full-length
  // vector / the free-DOF matrix (pattern and summation order of assemble(): bit-identical).
  void gather_vector(const std::vector<double>& buffer, Eigen::VectorXd& out) const;
  void gather_matrix(const std::vector<double>& buffer, SparseMatrix& out) const;
  const SparseMatrix& pattern() const { return matrix_; }

 private:
  const Model& model_;
  const DofMap& dofs_;
  bool full_ = false;
  std::vector<int> vec_offset_, mat_offset_;  // per element
  std::vector<double> fe_, fm_, fk_, fd_, ke_, me_, ce_;
  // Vector gather: contributions of global dof g are vec_src_[vec_ptr_[g] .. vec_ptr_[g+1]).
  std::vector<int> vec_ptr_, vec_src_;
  // Matrix gather: contributions of nonzero k are mat_src_[mat_ptr_[k] .. mat_ptr_[k+1]).
  std::vector<int> mat_ptr_, mat_src_;
  SparseMatrix matrix_;
  Eigen::VectorXd f_int_, f_mass_, f_stiff_, f_visc_;
};

// Smallest force residual that can be resolved: a translation is only known to round-off of the
// position (eps |x|), a rotation to eps, so |r| cannot be pushed below about
// 10 eps sqrt(n) max(K_tt |x|, K_rr) (K_tt, K_rr: largest translational / rotational diagonal
// entries). Newton tolerances are floored at this so that stiff models (EA L^2/EI ~ 1e7) under
// small loads converge instead of chasing round-off.
double roundoff_force_floor(const Assembler::SparseMatrix& upper, const DofMap& dofs,
                            double position_scale);

}  // namespace finverse::fem
