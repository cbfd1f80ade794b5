// The structural model as a function of the fit's physical parameter vector p (DESIGN.md section
// 5.4): the objectives of eqs. (1) and (2) call build(p) for every evaluation, since the Poisson
// ratio enters the elements' constitutive matrices and a new nu means new elements.
//
// The in-place route (the speed lever): moduli enter the corotational elements linearly
// (stiffness_field.hpp), so a model built for one p can be re-targeted to any p' that differs only
// in moduli by Model::set_*_youngs_modulus, keeping the assembler and the solver's symbolic
// factorisation. A factory that supports it maps p to a rebuild key (p with every in-place
// parameter replaced by a fixed value); models are built only for keys and then brought to p by
// set_moduli(). Results then depend on p alone, not on which cached model served the evaluation
// (the fit's byte-identical reruns need that).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fem/model.hpp"
#include "fit/target_motion.hpp"

namespace finverse::fit {

struct RayleighDamping {
  double mass = 0;       // a_M [1/s]
  double stiffness = 0;  // a_K [s]
};

class ModelFactory {
 public:
  virtual ~ModelFactory() = default;

  virtual std::vector<std::string> parameter_names() const = 0;
  virtual int parameter_count() const { return static_cast<int>(parameter_names().size()); }
  // The model for physical parameters p (size parameter_count()). Thread-safe: const and
  // self-contained. Throws InvalidInput (wrong size) or fem::InvalidInput (non-physical values).
  virtual std::unique_ptr<fem::Model> build(const Eigen::VectorXd& physical) const = 0;
  // Parameters the objectives build their topology, node weights and base states from
  // (the drive and connectivity do not depend on p): e.g. the materials file's values.
  virtual Eigen::VectorXd default_parameters() const = 0;
  // Nodes whose motion is prescribed (root / leading edge): excluded from the residuals.
  virtual std::vector<int> prescribed_nodes() const = 0;
  // Damping of the dynamic objective (the model itself carries none).
  virtual RayleighDamping damping() const { return {}; }

  // In-place route (see above). Default: none, every distinct p is built.
  // rebuild_key(p): p with the in-place parameters fixed; build(rebuild_key(p)) followed by
  // set_moduli(model, p) is the model for p.
  virtual Eigen::VectorXd rebuild_key(const Eigen::VectorXd& physical) const { return physical; }
  // Sets the moduli of a model built by build(rebuild_key(physical)) to those of `physical`.
  virtual void set_moduli(fem::Model& /*model*/, const Eigen::VectorXd& /*physical*/) const {}

  // The linearised increment's premise (fem/linear_increment.hpp): the models of any two p differ
  // only in element moduli, which set_moduli() brings to p on a model built for any p, and in
  // one Poisson ratio, parameter poisson_index() (-1: nu is not a parameter). Default: not so.
  virtual bool moduli_and_poisson_only() const { return false; }
  virtual int poisson_index() const { return -1; }

  // The same factory with its reference (stress-free) configuration moved to `positions`, one per
  // node, the drive re-referenced with it (eq. (2) with a stress-free base). Null: not supported.
  virtual std::shared_ptr<const ModelFactory> rebased(const std::vector<fem::Vec3>& /*positions*/) const {
    return nullptr;
  }
};

// The objectives' common start: checks the factory (InvalidInput "<what>: no model factory") and
// the target (check_target), builds the model at the default parameters and refuses a target of
// another node count (naming target.source). Returns that nominal model.
std::unique_ptr<fem::Model> nominal_model_for(const ModelFactory* factory, const TargetMotion& target,
                                              const std::string& what);

// The nodes of a model with all three translations prescribed or fixed (a helper for factories).
std::vector<int> translation_prescribed_nodes(const fem::Model& model);

}  // namespace finverse::fit
