// The fin as a traced model (traced_model.hpp; issue 34): the structural FEM of the fitted fin
// (fit/fin_parameters.hpp: materials.h5's best values, the measured loads, the reconstruction's
// root motion, as fin-fem run) compared with the reconstruction at every frame
// (model_prediction.hpp), with any candidate effect of
// tools/fem/effects switched on (effect_model_factory.hpp). The refitted base parameters are a
// chosen subset of materials.h5's; the others stay at their best values.
//
// Score directions: an effect with an amplitude and a phase (active stiffening, root curvature)
// is tested in two directions, amplitude h at phase 0 and at phase pi/2 (q = 2: the sine and the
// cosine part), its refit starting from amplitude hypot(c1, c2) and phase atan2(c2, c1) of the
// one-step estimate; every other parameter in one direction, off + h; h = relative_step times
// the parameter's range.
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fem/effects/structural_effect.hpp"
#include "fem/structural_run.hpp"
#include "fit/fin_parameters.hpp"
#include "loop/model_prediction.hpp"
#include "loop/traced_model.hpp"

namespace finverse::loop {

struct FinTraceSetup {
  std::shared_ptr<const fit::FinModelFactory> base;  // parameter_names(): every materials.h5 parameter
  Eigen::VectorXd best;                               // their values (materials.h5 /best)
  fit::ParameterSpace refit;                          // the subset refitted (bounds from materials.h5)
  std::vector<nlohmann::json> candidates;             // make_effect() specs
  fem::FinLayout layout;                              // timing set
  fit::TargetMotion target;                           // the reconstruction's compared frames
  fem::RunOptions run;                                // quasi-static or dynamic, start_time set
  std::vector<int> trailing_edge_nodes;
  double relative_step = 0.01;
};

// Candidate name of a spec: its "name", with ":<group>" when a group other than "all" is set.
std::string candidate_name(const nlohmann::json& spec);

class FinTracedModel : public TracedModel {
 public:
  // Throws fem::InvalidInput for a bad spec, InvalidInput for a refit name materials.h5 lacks or
  // two candidates of one name.
  explicit FinTracedModel(FinTraceSetup setup);

  fit::ParameterSpace base_space() const override { return setup_.refit; }
  Eigen::VectorXd base_start() const override;
  std::vector<std::string> candidates() const override { return names_; }
  std::vector<fit::Parameter> effect_parameters(const std::string& candidate) const override;
  std::vector<ScoreDirection> score_directions(const std::string& candidate) const override;
  Eigen::VectorXd effect_start(const std::string& candidate, const Eigen::VectorXd& step) const override;
  Eigen::VectorXd effect_off(const std::string& candidate) const override;
  int frame_count() const override { return setup_.target.frame_count(); }
  Eigen::VectorXd residuals(const std::vector<std::string>& effects, const Eigen::VectorXd& physical) const override;
  double trailing_edge_rms(const Eigen::VectorXd& r) const override;
  Eigen::VectorXd node_rms(const Eigen::VectorXd& r) const override;
  Eigen::Matrix3Xd frame_points() const override { return objective({})->residual_layout()->points; }

  const nlohmann::json& spec(const std::string& candidate) const { return specs_.at(candidate); }
  // Node positions predicted by the model (every node, every compared frame) for a residual file.
  std::vector<fem::RunFrame> run(const std::vector<std::string>& effects, const Eigen::VectorXd& physical) const;

 private:
  std::shared_ptr<const ModelPrediction> objective(const std::vector<std::string>& effects) const;
  Eigen::VectorXd full_parameters(const std::vector<std::string>& effects, const Eigen::VectorXd& physical) const;
  bool has_phase(const std::string& candidate) const;

  FinTraceSetup setup_;
  std::vector<std::string> names_;
  std::map<std::string, nlohmann::json> specs_;
  std::map<std::string, std::vector<fem::EffectParameter>> params_;
  std::vector<int> refit_index_;  // position of each refit parameter in the base vector
  mutable std::mutex mutex_;
  mutable std::map<std::string, std::shared_ptr<const ModelPrediction>> objectives_;
  // Trailing-edge rows of the residual per frame block and the node weights to unweight them.
  mutable std::vector<std::pair<long, double>> te_rows_;
  mutable long rows_per_frame_ = 0;
  // Each compared node's mesh index and square-rooted weight (residual rows 3j..3j+2), and the
  // mesh's node count.
  mutable std::vector<std::pair<int, double>> compared_;
  mutable Eigen::Index mesh_nodes_ = 0;
};

}  // namespace finverse::loop
