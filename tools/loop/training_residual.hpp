// The training frames' rows of a traced model's residual (traced_model.hpp) with a list of effects
// on, as a fit::ResidualFunction: what every refit of the effect tracer and of fin-loop flap's
// closures minimises. Frames are equal blocks of rows_per_frame rows (3 per point), frame-major.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "fit/residual_function.hpp"
#include "loop/traced_model.hpp"

namespace finverse::loop {

class TrainingResidual : public fit::ResidualFunction {
 public:
  TrainingResidual(const TracedModel& model, std::vector<std::string> effects, int n, std::vector<int> frames,
                   long rows_per_frame)
      : model_(model), effects_(std::move(effects)), n_(n), frames_(std::move(frames)), rows_(rows_per_frame) {
    sqrt_w_ = Eigen::VectorXd::Ones(residual_count() / 3);
  }
  int parameter_count() const override { return n_; }
  int residual_count() const override { return static_cast<int>(rows_ * static_cast<long>(frames_.size())); }
  Eigen::VectorXd residuals(const Eigen::VectorXd& physical) const override {
    return pick(model_.residuals(effects_, physical));
  }
  const Eigen::VectorXd& sqrt_weights() const override { return sqrt_w_; }
  // The training frames' rows of a whole residual.
  Eigen::VectorXd pick(const Eigen::VectorXd& all) const {
    Eigen::VectorXd r(residual_count());
    for (std::size_t j = 0; j < frames_.size(); ++j)
      r.segment(static_cast<Eigen::Index>(j) * rows_, rows_) = all.segment(frames_[j] * rows_, rows_);
    return r;
  }

 private:
  const TracedModel& model_;
  std::vector<std::string> effects_;
  int n_;
  std::vector<int> frames_;
  long rows_;
  Eigen::VectorXd sqrt_w_;
};

}  // namespace finverse::loop
