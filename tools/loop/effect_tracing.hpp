// Effect tracing (issue 34; DESIGN.md section 5.6): from the fitted model, rank the candidate
// effects by the score test of their sensitivities projected off the fitted parameters'
// (score_test.hpp: one model run per score direction, no refit), add the best, refit every
// parameter by Levenberg-Marquardt (fit/levenberg_marquardt.hpp) on the training frames, and
// keep it only when the BIC on the training frames improves AND the RMS error on the held-out
// frames falls; repeat until a candidate fails that rule, none is significant, or none is left.
// Each step records every candidate's score, the one tried, its fitted magnitude with a 95 %
// interval (fit/uncertainty.hpp), the trailing-edge RMS, BIC and held-out error before and after.
// J is the refit's own Jacobian in this residual's space (prediction - reconstruction per frame):
// materials.h5 keeps only J's singular values, and of fin-fit's eq. (2) increments, not of it.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fit/levenberg_marquardt.hpp"
#include "fit/parameter_space.hpp"
#include "loop/score_test.hpp"
#include "loop/traced_model.hpp"

namespace finverse::loop {

struct HeldOutSplit {
  std::vector<int> held_out;     // frame indices
  std::string kind;              // "last_cycle" | "interleaved" (less than two periods of frames)
};

// Frames of the last whole period held out when the frames span at least two periods (period > 0),
// else every other frame (odd indices), which is not independent of the fit: `kind` says so.
HeldOutSplit held_out_split(const std::vector<double>& times, double period);

struct TraceOptions {
  std::vector<int> held_out_frames;  // not used by any fit
  bool refit_base = true;            // refit the base parameters before the first ranking
  double alpha = 0.01;               // family-wise level of the score test (Bonferroni over candidates)
  int max_effects = 3;
  // A candidate whose sensitivity lies within this fraction of span(J) scores 0 (score_test.hpp):
  // what finite differences cannot tell from the fitted parameters' directions.
  double in_span_tolerance = 1e-8;
  fit::LmOptions lm;                 // refits; lm.fd_step also for the base Jacobian
  std::function<void(const std::string&)> progress;  // one line per stage (base refit, score, refit)
};

struct CandidateScore {
  std::string name;
  ScoreResult score;
  std::string failure;  // the model run that failed for this candidate (score then 0); empty: none
};

struct ModelState {
  double rss = 0;          // training |r|^2
  double bic = 0;          // training
  double held_out_rms = 0; // RMS of |r| per node-sample on the held-out frames
  double trailing_edge_rms = 0;  // all frames
  Eigen::VectorXd node_rms;      // per node, all frames [m] (TracedModel::node_rms)
  long training_rows = 0;
  int parameters = 0;
};

struct TraceStep {
  std::vector<CandidateScore> scores;  // ranked, best first
  std::string tried;                   // empty: none significant / none left
  bool accepted = false;
  std::vector<std::string> effect_parameter_names;
  Eigen::VectorXd magnitude, lower95, upper95;  // the tried effect's fitted parameters
  ModelState before, after;
  long evaluations = 0;
};

struct TraceResult {
  ModelState base_initial;              // at base_start, before any refit
  ModelState base;                      // the refitted base: before the first effect
  ModelState final_state;               // after the last accepted effect (= base when none)
  std::vector<TraceStep> steps;
  std::vector<std::string> added;
  fit::ParameterSpace space;            // base + added effects
  Eigen::VectorXd parameters;           // physical, final
  std::string stop_reason;
  long evaluations = 0;
};

// Throws InvalidInput for held-out frames out of range or all frames held out.
TraceResult trace_effects(const TracedModel& model, const TraceOptions& options);

}  // namespace finverse::loop
