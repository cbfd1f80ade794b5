// The structural model's prediction compared with the reconstruction frame by frame (issue 34):
// r_(k,i) = sqrt(w_i) (x_model^i(t_k) - x_target^i(t_k)), frame-major, three components per
// compared node, as the fit's eq. (1) objective (fit/dynamic_objective.hpp) but for any analysis
// of fem::run_structural_analysis: a quasi-static sequence (what fin-fem run does by default and
// what the fit's eq. (2) assumes: the fin's dynamic solve needs ~64 sub-steps per frame from
// rest, docs/studies/fin_fsi.md) or the dynamic run. Weights: fit/node_weights.hpp.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "fem/structural_run.hpp"
#include "fit/model_factory.hpp"
#include "fit/residual_function.hpp"
#include "fit/target_motion.hpp"

namespace finverse::loop {

class ModelPrediction : public fit::ResidualFunction {
 public:
  // options.start_time must precede the first target frame. Throws fit::InvalidInput for node
  // counts that differ (naming target.source).
  ModelPrediction(std::shared_ptr<const fit::ModelFactory> factory, fit::TargetMotion target, fem::RunOptions options);

  int parameter_count() const override { return factory_->parameter_count(); }
  int residual_count() const override { return 3 * static_cast<int>(nodes_.size()) * target_.frame_count(); }
  Eigen::VectorXd residuals(const Eigen::VectorXd& physical) const override;
  const Eigen::VectorXd& sqrt_weights() const override { return sqrt_weights_; }
  std::optional<fit::ResidualLayout> residual_layout() const override {
    return fit::ResidualLayout{target_.frame_count(), points_};
  }

  std::vector<fem::RunFrame> run(const Eigen::VectorXd& physical) const;
  const std::vector<int>& compared_nodes() const { return nodes_; }
  const Eigen::VectorXd& node_weights() const { return weights_; }

 private:
  std::shared_ptr<const fit::ModelFactory> factory_;
  fit::TargetMotion target_;
  fem::RunOptions options_;
  Eigen::VectorXd weights_, sqrt_weights_;
  std::vector<int> nodes_;
  Eigen::Matrix3Xd points_;  // the compared nodes' reference positions (residual_layout)
};

}  // namespace finverse::loop
