// Static load levels (issue 45, deliverable 7): a structure loaded in steps and measured at rest
// at every level -- a test rig, or another FEM code's static analysis. The model's static
// equilibrium at each level, reached by load control from the unloaded reference through the
// levels in order (the target's times are the levels; the loads' nodal forces at those times),
// is compared with the measured positions:
//     r_(k,i) = sqrt(w_i) (x_FE^i(level k) - x_target^i(level k)),  level-major.
// Unlike eq. (2) no base is taken from the data, so a measured shape's small differences from the
// model's own are not multiplied into the increments (6-10x on another code's hybrid plate,
// docs/studies/fit_structural_data.md). The first level may be the unloaded state.
// Thread-safe; models are cached per rebuild key as QuasiStaticObjective's are.
#pragma once

#include <Eigen/Core>
#include <list>
#include <memory>
#include <mutex>
#include <vector>

#include "fem/static_solver.hpp"
#include "fit/model_factory.hpp"
#include "fit/residual_function.hpp"
#include "fit/target_motion.hpp"

namespace finverse::fit {

struct StaticObjectiveOptions {
  double start_level = 0;          // load factor / time of the unloaded reference (loads zero there)
  Eigen::VectorXd node_weights{};  // one per node; empty: default_node_weights (node_weights.hpp)
  // Load steps from the reference to the first level, and between levels; Newton cuts steps itself.
  fem::StaticOptions static_options{.steps = 4, .min_step_fraction = 1.0 / 256};
  int cached_models = 4;
};

class StaticObjective : public ResidualFunction {
 public:
  // Throws InvalidInput naming target.source: node count differing from the model's, a level not
  // after start_level, a level beyond the loads' times.
  StaticObjective(std::shared_ptr<const ModelFactory> factory, TargetMotion target,
                  StaticObjectiveOptions options = {});
  ~StaticObjective() override;

  int parameter_count() const override { return factory_->parameter_count(); }
  int residual_count() const override { return 3 * static_cast<int>(nodes_.size() * target_.times.size()); }
  Eigen::VectorXd residuals(const Eigen::VectorXd& physical) const override;
  const Eigen::VectorXd& sqrt_weights() const override { return sqrt_weights_; }
  std::optional<ResidualLayout> residual_layout() const override {
    return ResidualLayout{static_cast<int>(target_.times.size()), points_};
  }
  std::vector<double> block_times() const override { return target_.times; }

  // The model's positions at every level, [level][node].
  std::vector<std::vector<fem::Vec3>> positions(const Eigen::VectorXd& physical) const;
  const std::vector<int>& compared_nodes() const { return nodes_; }

 private:
  struct Workspace;
  std::unique_ptr<Workspace> acquire(const Eigen::VectorXd& physical) const;
  void release(std::unique_ptr<Workspace> workspace) const;

  std::shared_ptr<const ModelFactory> factory_;
  TargetMotion target_;
  StaticObjectiveOptions options_;
  Eigen::VectorXd weights_, sqrt_weights_;
  std::vector<int> nodes_;
  Eigen::Matrix3Xd points_;  // the compared nodes' reference positions (residual_layout)
  mutable std::mutex mutex_;
  mutable std::list<std::unique_ptr<Workspace>> idle_;
};

}  // namespace finverse::fit
