// What the effect tracer (effect_tracing.hpp) needs of a model, apart from any FEM: the base
// fit's parameters, the candidate effects with their parameters, and the residual
// (prediction - data) of the base model with a list of effects switched on. The fin's
// implementation runs the structural FEM with the effects of tools/fem/effects
// (fin_traced_model.hpp); the unit tests use linear models whose answer is known.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "fit/parameter_space.hpp"

namespace finverse::loop {

// One perturbation of a candidate for its score test: the candidate's parameters (physical) set
// to `parameters`, the sensitivity being (r(parameters) - r(off)) / step.
// central: (r(parameters) - r(2 off - parameters)) / (2 step) instead, one more model run: a
// model whose candidates lie in span(J) to first order (the flap's density against E) would
// otherwise score on the one-sided difference's curvature term alone.
struct ScoreDirection {
  Eigen::VectorXd parameters;
  double step = 1;
  bool central = false;
};

class TracedModel {
 public:
  virtual ~TracedModel() = default;

  virtual fit::ParameterSpace base_space() const = 0;
  virtual Eigen::VectorXd base_start() const = 0;  // physical, e.g. materials.h5's best
  virtual std::vector<std::string> candidates() const = 0;
  // Parameters a candidate adds to the fit (names unique across candidates and the base).
  virtual std::vector<fit::Parameter> effect_parameters(const std::string& candidate) const = 0;
  // The candidate's directions for the score (one model run each; their count is the test's q).
  virtual std::vector<ScoreDirection> score_directions(const std::string& candidate) const = 0;
  // The candidate's parameters to start its refit from, given the one-step estimate along its
  // score directions (default: off + sum_j step_j (direction_j - off) / h_j, clamped to bounds).
  virtual Eigen::VectorXd effect_start(const std::string& candidate, const Eigen::VectorXd& step) const;
  // The candidate's parameters with the effect off.
  virtual Eigen::VectorXd effect_off(const std::string& candidate) const = 0;

  virtual int frame_count() const = 0;
  // prediction - data with `effects` on: `physical` = base parameters then each effect's, in the
  // order of `effects`. frame_count() equal blocks, frame-major, each a multiple of 3 rows.
  // Thread-safe. Throws (e.g. fem::NotConverged) when the model fails for these parameters.
  virtual Eigen::VectorXd residuals(const std::vector<std::string>& effects, const Eigen::VectorXd& physical) const = 0;
  // Reference positions of the points of a frame block, in row order (3 rows each), so that the
  // score test can estimate how the residual is correlated (fit/correlated_residual.hpp). Empty
  // (the default): the residual's rows are taken as independent.
  virtual Eigen::Matrix3Xd frame_points() const { return {}; }
  // Data each 3-row point carries: 3 (a tracked position), or 1 where only one coordinate is
  // measured and the other two rows are structural zeros (the flap's centreline), so that the
  // score test's variance and the BIC count data, not rows.
  virtual int data_per_point() const { return 3; }
  // RMS over the trailing edge of a residual vector as residuals() returns it (default: all rows).
  virtual double trailing_edge_rms(const Eigen::VectorXd& r) const;
  // Per node, the RMS over frames of |residual| [m] (the report's residual maps). Default: one
  // "node" per 3-row block of a frame. The fin: every mesh node, NaN where none is compared.
  virtual Eigen::VectorXd node_rms(const Eigen::VectorXd& r) const;
};

}  // namespace finverse::loop
