// The structural prediction against the reconstruction (model_prediction.hpp).
#include "loop/model_prediction.hpp"

#include <cmath>
#include <string>

#include "fit/errors.hpp"
#include "fit/node_weights.hpp"

namespace finverse::loop {

ModelPrediction::ModelPrediction(std::shared_ptr<const fit::ModelFactory> factory, fit::TargetMotion target,
                                 fem::RunOptions options)
    : factory_(std::move(factory)), target_(std::move(target)), options_(std::move(options)) {
  fit::check_target(target_);
  const auto model = factory_->build(factory_->default_parameters());
  if (target_.node_count() != model->node_count())
    throw fit::InvalidInput(target_.source + ": " + std::to_string(target_.node_count()) + " nodes, the model has " +
                            std::to_string(model->node_count()));
  if (!(options_.start_time < target_.times.front()))
    throw fit::InvalidInput(target_.source + ": the run's start time must precede the first frame");
  weights_ = fit::default_node_weights(*model, factory_->prescribed_nodes());
  nodes_ = fit::compared_nodes(weights_);
  points_ = fit::compared_points(*model, nodes_);
  sqrt_weights_.resize(static_cast<Eigen::Index>(nodes_.size()) * target_.frame_count());
  Eigen::Index i = 0;
  for (int k = 0; k < target_.frame_count(); ++k)
    for (int n : nodes_) sqrt_weights_(i++) = std::sqrt(weights_(n));
}

std::vector<fem::RunFrame> ModelPrediction::run(const Eigen::VectorXd& p) const {
  const auto model = factory_->build(p);
  return fem::run_structural_analysis(*model, options_, target_.times);
}

Eigen::VectorXd ModelPrediction::residuals(const Eigen::VectorXd& p) const {
  const auto frames = run(p);
  Eigen::VectorXd r(residual_count());
  Eigen::Index i = 0;
  for (std::size_t k = 0; k < frames.size(); ++k)
    for (int n : nodes_) {
      r.segment<3>(3 * i) = sqrt_weights_(i) * (frames[k].state.position[n] - target_.positions[k][n]);
      ++i;
    }
  return r;
}

}  // namespace finverse::loop
