// The add-refit-test loop (loop/effect_tracing.hpp) on a linear model whose answer is known: the
// data contain one planted candidate column; the loop must rank it first, add it with an interval
// that holds the planted magnitude, and stop; with nothing planted (the control) add nothing.
#include <map>
#include <random>

#include <gtest/gtest.h>

#include "loop/effect_tracing.hpp"
#include "loop/errors.hpp"

namespace finverse::loop {
namespace {

fit::Parameter linear(const std::string& name) {
  fit::Parameter p;
  p.name = name;
  p.unit = "1";
  p.lower = -5;
  p.upper = 5;
  p.scale = fit::Scale::linear;
  return p;
}

class LinearModel : public TracedModel {
 public:
  LinearModel(const std::string& planted, double magnitude, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> g;
    const int m = kFrames * kRows;
    x_.resize(m, 2);
    for (int i = 0; i < m; ++i) x_.row(i) << g(rng), g(rng);
    for (const auto& name : candidates()) {
      Eigen::VectorXd z(m);
      for (int i = 0; i < m; ++i) z(i) = g(rng);
      z_[name] = z;
    }
    std::normal_distribution<double> noise(0, 0.05);
    y_ = x_ * Eigen::Vector2d(1.5, -0.7);
    if (!planted.empty()) y_ += magnitude * z_.at(planted);
    for (int i = 0; i < m; ++i) y_(i) += noise(rng);
  }
  static constexpr int kFrames = 40, kRows = 30;

  fit::ParameterSpace base_space() const override {
    return fit::ParameterSpace({linear("theta1"), linear("theta2")});
  }
  Eigen::VectorXd base_start() const override { return Eigen::Vector2d(1, 0); }
  std::vector<std::string> candidates() const override { return {"alpha", "beta", "gamma", "delta"}; }
  std::vector<fit::Parameter> effect_parameters(const std::string& c) const override {
    auto p = linear(c + "_amplitude");
    p.lower = -1;
    p.upper = 1;
    return {p};
  }
  std::vector<ScoreDirection> score_directions(const std::string&) const override {
    return {{Eigen::VectorXd::Constant(1, 0.1), 0.1}};
  }
  Eigen::VectorXd effect_off(const std::string&) const override { return Eigen::VectorXd::Zero(1); }
  int frame_count() const override { return kFrames; }
  Eigen::VectorXd residuals(const std::vector<std::string>& effects, const Eigen::VectorXd& p) const override {
    Eigen::VectorXd pred = x_ * p.head(2);
    for (std::size_t i = 0; i < effects.size(); ++i) pred += p(2 + static_cast<Eigen::Index>(i)) * z_.at(effects[i]);
    return pred - y_;
  }

 private:
  Eigen::MatrixXd x_;
  std::map<std::string, Eigen::VectorXd> z_;
  Eigen::VectorXd y_;
};

TraceOptions options() {
  TraceOptions o;
  std::vector<double> times(LinearModel::kFrames);
  for (int k = 0; k < LinearModel::kFrames; ++k) times[k] = 0.01 * k;
  const auto split = held_out_split(times, 0.1);
  EXPECT_EQ(split.kind, "last_cycle");
  EXPECT_EQ(split.held_out.size(), 10u);
  o.held_out_frames = split.held_out;
  o.lm.threads = 1;
  return o;
}

TEST(EffectTracing, PlantedCandidateIsAddedFirstWithItsMagnitude) {
  const LinearModel model("gamma", 0.2, 5);
  const auto result = trace_effects(model, options());
  ASSERT_FALSE(result.steps.empty());
  const auto& first = result.steps.front();
  EXPECT_EQ(first.scores.front().name, "gamma");
  EXPECT_EQ(first.tried, "gamma");
  EXPECT_TRUE(first.accepted);
  ASSERT_EQ(result.added.size(), 1u);
  EXPECT_EQ(result.added[0], "gamma");
  EXPECT_NEAR(first.magnitude(0), 0.2, 0.01);
  EXPECT_LT(first.lower95(0), 0.2);
  EXPECT_GT(first.upper95(0), 0.2);
  EXPECT_LT(first.after.held_out_rms, 0.5 * first.before.held_out_rms);
  EXPECT_LT(first.after.bic, first.before.bic);
  // The base parameters are refitted alongside.
  EXPECT_NEAR(result.parameters(0), 1.5, 0.01);
  EXPECT_NEAR(result.parameters(1), -0.7, 0.01);
}

// The report's residual maps: per node (here a 3-row block) before the first effect and after the
// last accepted one; the planted column spreads over every node, so each node's RMS falls.
TEST(EffectTracing, RecordsPerNodeRmsBeforeAndAfter) {
  const LinearModel model("gamma", 0.2, 5);
  const auto result = trace_effects(model, options());
  ASSERT_EQ(result.base.node_rms.size(), LinearModel::kRows / 3);
  ASSERT_EQ(result.final_state.node_rms.size(), LinearModel::kRows / 3);
  EXPECT_EQ(result.base.node_rms, result.steps.front().before.node_rms);
  EXPECT_EQ(result.final_state.node_rms, result.steps.front().after.node_rms);
  EXPECT_LT(result.final_state.node_rms.maxCoeff(), 0.5 * result.base.node_rms.minCoeff());
  // Mean square over nodes = the per-row-triple mean square over all frames.
  const Eigen::VectorXd r = model.residuals({"gamma"}, result.parameters);
  EXPECT_NEAR(result.final_state.node_rms.squaredNorm() / (LinearModel::kRows / 3),
              r.squaredNorm() / (r.size() / 3.0), 1e-12);
}

TEST(EffectTracing, ControlWithoutEffectAddsNothing) {
  const LinearModel model("", 0, 9);
  const auto result = trace_effects(model, options());
  EXPECT_TRUE(result.added.empty()) << result.added.front();
  ASSERT_FALSE(result.steps.empty());
  EXPECT_FALSE(result.stop_reason.empty());
}

TEST(EffectTracing, RefusesAllFramesHeldOut) {
  const LinearModel model("", 0, 1);
  TraceOptions o;
  for (int k = 0; k < LinearModel::kFrames; ++k) o.held_out_frames.push_back(k);
  EXPECT_THROW(trace_effects(model, o), InvalidInput);
  o.held_out_frames = {LinearModel::kFrames};
  EXPECT_THROW(trace_effects(model, o), InvalidInput);
}

TEST(EffectTracing, ShortRecordsInterleaveTheHeldOutFrames) {
  const auto split = held_out_split({0, 1, 2, 3, 4}, 10);
  EXPECT_EQ(split.kind, "interleaved");
  EXPECT_EQ(split.held_out, (std::vector<int>{1, 3}));
}

}  // namespace
}  // namespace finverse::loop
