// The tangent stiffness of a model at one fixed configuration as an explicit function of its
// element moduli and one Poisson ratio: the stored form behind a fast eq. (2) evaluation
// (issue 45). Corotational forces and tangents are linear in E at fixed nu (stiffness_field.hpp),
// and in nu every element is a combination of 1, nu, 1/(1 - nu^2), nu/(1 - nu^2) (plane stress,
// the shear modulus, a beam's E, the optimal membrane's beta0 = (1 - 4 nu^2)/2), so
//     K_e(E_e, nu) = E_e (B0_e + nu B1_e + B2_e / (1 - nu^2) + B3_e nu / (1 - nu^2)),  nu < 0.497.
// The B_e come from the model built at four Poisson ratios (one 4 x 4 solve per entry);
// form_error() checks a fifth. combine() weighs the stored element matrices and gathers them into
// the assembler's pattern: no element is evaluated. Derivation and checks:
// docs/studies/fit_evaluation_speed.md.
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
