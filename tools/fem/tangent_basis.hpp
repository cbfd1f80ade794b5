// The tangent stiffness of a model at one fixed configuration as an explicit function of its
// element moduli and one Poisson ratio: the stored form behind a fast eq. (2) evaluation
// (issue 45, deliverable 5).
//
// With nu fixed, the corotational elements' forces and tangents (geometric stiffness included)
// are linear in E (stiffness_field.hpp). In nu: the shell's bending (DKT) and basic membrane
// stiffness are E/(1 - nu^2) (D0 + nu D1), its shear modulus E/(2 (1 + nu)) among them; the
// optimal membrane's higher-order part carries beta0 = (1 - 4 nu^2)/2 (Felippa) on top, which
// brings (1 - 4 nu^2)/(1 - nu^2) = 4 - 3/(1 - nu^2) and nu times it; a beam's axial and bending
// stiffness is E, its torsion G = E/(2 (1 + nu)) = E/2 (1 - nu)/(1 - nu^2). So every element's
// tangent is
//     K_e(E_e, nu) = E_e (B0_e + nu B1_e + B2_e / (1 - nu^2) + B3_e nu / (1 - nu^2))
// for nu < 0.497 (above it the membrane's beta0 is floored at 0.01). The four B_e come from the
// element tangents of the same model built at four Poisson ratios (same configuration, same
// time), each divided by its element modulus: one 4 x 4 solve for every entry. form_error()
// checks the form against a model at a fifth ratio: an element family outside it (the
// plane-strain solid's E/((1 + nu)(1 - 2 nu))) shows there as a large error.
// combine() then weighs the stored element matrices and gathers them into the assembler's
// free-DOF pattern: no element is evaluated, and the symbolic factorisation of the pattern is
// reused by the caller's solver.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "fem/assembly.hpp"
#include "fem/dof_map.hpp"
#include "fem/model.hpp"
#include "fem/nodal_state.hpp"

namespace finverse::fem {

class TangentBasis {
 public:
  // models: the same model (topology, constraints, element order) built at the Poisson ratios
  // nus: four distinct ratios, or one model and its ratio when nu is not varied (then combine()
  // takes that nu only). The first model must outlive the basis (the assembler's gather maps refer
  // to it). state: the configuration; time: the stiffness field's time; product (full length,
  // optional): a vector whose product K(E, nu) v combine() also returns (a prescribed increment).
  // Throws InvalidInput for mismatched models or ratios.
  TangentBasis(const std::vector<const Model*>& models, const std::vector<double>& nus, const NodalState& state,
               double time, const Eigen::VectorXd* product = nullptr);

  struct Scratch {
    std::vector<double> matrix, vector;
  };

  // K(E, nu) on the free DOFs (upper triangle, the assembler's pattern) into `matrix`; with kv,
  // also K(E, nu) v (full length) for the constructor's v. element_moduli: E_e for every element
  // (Model::element_youngs_modulus at the basis's time). Thread-safe (const; own scratch).
  void combine(const std::vector<double>& element_moduli, double nu, Assembler::SparseMatrix& matrix,
               Eigen::VectorXd* kv, Scratch& scratch) const;

  // Largest |K_basis - K_model| over the entries of the free block, relative to the largest
  // |K_model| entry, for `model` (same topology) at Poisson ratio nu, at the basis's state and time.
  double form_error(const Model& model, double nu) const;

  const DofMap& dofs() const { return *dofs_; }
  const Assembler& assembler() const { return *assembler_; }
  bool varies_poisson() const { return basis_count_ > 1; }
  static constexpr int kPoissonModels = 4;  // models a basis that varies nu is built from

 private:
  std::unique_ptr<DofMap> dofs_;
  std::unique_ptr<Assembler> assembler_;  // refers to the first model and *dofs_
  NodalState state_;
  double time_ = 0, fixed_nu_ = 0;
  int basis_count_ = 1;
  bool has_product_ = false;
  std::vector<std::vector<double>> matrices_, products_;  // [basis] element buffers
};

}  // namespace finverse::fem
