// The seed paper's eq. (2): at each instant t_j the target shape is the base, taken to be in
// equilibrium, and the FEM's increment over [t_j, t_j + dt] under the load and root-motion
// increments (fem::QuasiStaticIncrement) is compared with the target's:
//     r_(j,i) = sqrt(w_i) (dx_FE^i(t_j) - dx_target^i(t_j)), instant-major.
// Base rotations come from a rigid fit of each node's 1-ring (state_from_positions.hpp), then
// relaxed to moment balance with the positions held (rotation_relaxation.hpp); the
// prescribed DOFs take the drive's values, so the root increment is exactly the drive's. Without
// loads, scaling every modulus leaves the increment unchanged (the identifiability trap).
// Thread-safe; models are cached per rebuild key so that a change of moduli alone re-targets a
// model in place (model_factory.hpp).
#pragma once

#include <Eigen/Core>
#include <atomic>
#include <list>
#include <memory>
#include <mutex>
#include <vector>

#include "fem/linear_increment.hpp"
#include "fem/quasi_static_increment.hpp"
#include "fem/static_solver.hpp"
#include "fem/stored_tangent_increment.hpp"
#include "fit/model_factory.hpp"
#include "fit/residual_function.hpp"
#include "fit/target_motion.hpp"

namespace finverse::fit {

struct QuasiStaticOptions {
  std::vector<double> instants{};  // t_j; empty: the target's middle frame
  double dt = 0;                 // increment; 0: the target's frame spacing
  Eigen::VectorXd node_weights{};  // one per node; empty: default_node_weights (node_weights.hpp)
  // One load step; an increment that still fails after 8 cuts scores as a failed evaluation
  // (the fit's optimisers take it as +inf) instead of cutting 14 times at ~25 Newton iterations
  // each (measured: 2 min for one failing evaluation on the tiny case's fin).
  fem::StaticOptions static_options{.steps = 1, .min_step_fraction = 1.0 / 256};
  int cached_models = 8;         // models kept for the in-place route; 0: build every evaluation
  // Base rotations relaxed to moment balance with the positions held, under the moduli of each
  // evaluation (rotation_relaxation.hpp); false: the 1-ring rigid fits as they are.
  bool relax_rotations = true;
  // The base as the stress-free reference of the increment (ModelFactory::rebased): the model is
  // rebuilt on each instant's shape, so no stress is carried from the reference mesh. For a
  // reconstructed shape that the FEM would not reach from the flat mesh (the synthetic trout's
  // membrane is stretched up to 60 % between its fanning rays) the carried stress is an
  // artefact whose geometric stiffness makes Newton fail; false (default): the base carries the
  // stress of its deformation from the mesh, exact for the FEM's own states (the twins).
  bool stress_free_base = false;
  // Eq. (2) with the structure's inertia (issue 45): the mass times the change of the target's
  // measured acceleration over the increment as a known load (measured_inertia.hpp); false: the
  // paper's form. Needs a target frame before each instant and one after its increment.
  bool inertia = false;
  // How the increment is solved: newton (QuasiStaticIncrement from the base, converged); stored
  // (converged too, from a reference solution at the factory's default parameters on its stored
  // tangent, fem/stored_tangent_increment.hpp; Newton where that iteration stalls); or linear
  // (Newton's first step from the base's tangent kept as stored element matrices,
  // fem/linear_increment.hpp: no element evaluation per evaluation, not converged). stored and
  // linear need a factory whose parameters are moduli and one Poisson ratio
  // (ModelFactory::moduli_and_poisson_only) and bases that do not depend on them
  // (stress_free_base, or relax_rotations false).
  enum class Solve { newton, stored, linear } solve = Solve::newton;
  // stored: near a reference, run on its own factorised tangent (StoredTangentOptions::
  // reuse_within); false only to measure what that saves (fit_fin_rate bench).
  bool reuse_reference_tangent = true;
};

// "newton" / "stored" / "linear"; throws InvalidInput naming the flag otherwise.
QuasiStaticOptions::Solve parse_increment_solve(const std::string& name);

class QuasiStaticObjective : public ResidualFunction {
 public:
  // Throws InvalidInput naming target.source: node count differing from the model's, an instant
  // whose [t_j, t_j + dt] leaves the target's span (or the loads' span when the model has
  // tabulated loads), dt <= 0, bad weights.
  QuasiStaticObjective(std::shared_ptr<const ModelFactory> factory, TargetMotion target,
                       QuasiStaticOptions options = {});
  ~QuasiStaticObjective() override;

  int parameter_count() const override { return factory_->parameter_count(); }
  int residual_count() const override { return 3 * static_cast<int>(nodes_.size() * instants_.size()); }
  Eigen::VectorXd residuals(const Eigen::VectorXd& physical) const override;
  const Eigen::VectorXd& sqrt_weights() const override { return sqrt_weights_; }
  std::optional<ResidualLayout> residual_layout() const override {
    return ResidualLayout{static_cast<int>(instants_.size()), points_};
  }
  std::vector<double> block_times() const override { return instants_; }

  // Solve::stored: moves the reference solution every evaluation starts from to p (at
  // construction: the factory's default parameters), so that evaluations near p converge in a few
  // iterations. Not to be called while evaluations run. Other routes: nothing.
  void expect_near(const Eigen::VectorXd& physical) const override;

  // dx_FE per instant, [instant][node] (every node): for diagnostics and plots.
  std::vector<std::vector<fem::Vec3>> increments(const Eigen::VectorXd& physical) const;

  const std::vector<double>& instants() const { return instants_; }
  double dt() const { return dt_; }
  const std::vector<int>& compared_nodes() const { return nodes_; }
  const Eigen::VectorXd& node_weights() const { return weights_; }
  // dx_target per instant, [instant][node].
  const std::vector<std::vector<fem::Vec3>>& target_increments() const { return target_dx_; }
  // The bases from the positions (1-ring rotations, the drive's root values), before relaxation.
  const std::vector<fem::NodalState>& base_states() const { return base_; }
  long model_builds() const { return builds_.load(); }  // models built so far (the lever's effect)
  long model_rekeys() const { return rekeys_.load(); }  // workspaces whose models were rebuilt in place
  // eq. (2) with inertia: the load change -M da per instant (full length); empty otherwise.
  const std::vector<Eigen::VectorXd>& inertial_load_changes() const { return load_change_; }
  // Solve::linear, stored: the largest relative error of the stored tangent's form (tangent_basis.hpp).
  double linear_form_error() const { return linear_form_error_; }
  // Solve::stored: increments solved so far, how many fell back to Newton, the stored
  // iteration's iterations in all (converged or not), and how many ran on the reference's own
  // tangent (near it).
  struct StoredCounts {
    long solves = 0, fallbacks = 0, iterations = 0, reuses = 0;
  };
  StoredCounts stored_counts() const {
    return {stored_solves_.load(), stored_fallbacks_.load(), stored_iterations_.load(), stored_reuses_.load()};
  }

 private:
  struct Workspace;
  void set_up_stored_tangents(const TargetMotion& target);
  std::vector<fem::Vec3> stored_increment(size_t instant, fem::QuasiStaticIncrement& increment,
                                          const Eigen::VectorXd& p, Workspace& workspace) const;
  const Eigen::VectorXd* load_change(size_t instant) const {
    return load_change_.empty() ? nullptr : &load_change_[instant];
  }
  std::unique_ptr<Workspace> acquire(const Eigen::VectorXd& physical) const;
  bool rekey(Workspace& workspace, const Eigen::VectorXd& key) const;
  std::unique_ptr<fem::StoredTangentIncrement> stored_at(size_t instant, const fem::Model& model, double nu,
                                                         const fem::StoredTangentIncrement* from = nullptr) const;
  double poisson_of(const Eigen::VectorXd& p) const {
    return factory_->poisson_index() < 0 ? 0.0 : p(factory_->poisson_index());
  }
  void release(std::unique_ptr<Workspace> workspace) const;

  std::shared_ptr<const ModelFactory> factory_;
  QuasiStaticOptions options_;
  std::vector<double> instants_;
  double dt_ = 0;
  Eigen::VectorXd weights_, sqrt_weights_;
  std::vector<int> nodes_;
  Eigen::Matrix3Xd points_;                           // the compared nodes' reference positions (residual_layout)
  std::vector<fem::NodalState> base_;                 // [instant]
  std::vector<std::shared_ptr<const ModelFactory>> rebased_;  // stress_free_base: [instant]
  std::vector<std::vector<fem::Vec3>> target_dx_;     // [instant][node]
  std::vector<Eigen::VectorXd> load_change_;          // inertia: [instant]
  // Solve::linear: the models at four Poisson ratios ([instant][4] with stress-free bases, else
  // [0][4] shared) and each instant's linearised increment, built once and shared by the threads.
  std::vector<std::vector<std::unique_ptr<fem::Model>>> linear_models_;
  std::vector<std::unique_ptr<fem::LinearIncrement>> linear_;
  // Solve::stored: [instant]; mutable: expect_near moves the references between evaluations.
  mutable std::vector<std::unique_ptr<fem::StoredTangentIncrement>> stored_;
  std::vector<double> basis_poisson_;  // the Poisson ratios of linear_models_
  double linear_form_error_ = 0;
  mutable std::atomic<long> stored_solves_{0}, stored_fallbacks_{0}, stored_iterations_{0}, stored_reuses_{0};
  mutable std::mutex mutex_;
  mutable std::list<std::unique_ptr<Workspace>> idle_;  // most recently used first
  mutable std::atomic<long> builds_{0}, rekeys_{0};
};

}  // namespace finverse::fit
