// The add-refit-test loop over candidate effects (effect_tracing.hpp).
#include "loop/effect_tracing.hpp"
#include "loop/training_residual.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>
#include <sstream>

#include "fit/residual_function.hpp"
#include "fit/uncertainty.hpp"
#include "loop/errors.hpp"
#include "loop/information_criterion.hpp"

namespace finverse::loop {
namespace {

struct Split {
  std::vector<int> training, held_out;
  long rows_per_frame = 0;
};

double rms_rows(const Eigen::VectorXd& r) { return r.size() ? std::sqrt(r.squaredNorm() / (r.size() / 3.0)) : 0.0; }

Eigen::VectorXd pick_frames(const Eigen::VectorXd& all, const std::vector<int>& frames, long rows) {
  Eigen::VectorXd r(rows * static_cast<long>(frames.size()));
  for (std::size_t j = 0; j < frames.size(); ++j) r.segment(j * rows, rows) = all.segment(frames[j] * rows, rows);
  return r;
}

ModelState state_of(const TracedModel& model, const Eigen::VectorXd& all, const Split& split, int parameters) {
  ModelState s;
  const Eigen::VectorXd train = pick_frames(all, split.training, split.rows_per_frame);
  const Eigen::VectorXd held = pick_frames(all, split.held_out, split.rows_per_frame);
  s.rss = train.squaredNorm();
  s.training_rows = train.size() * model.data_per_point() / 3;  // data, not rows
  s.parameters = parameters;
  s.bic = bic(s.rss, s.training_rows, parameters);
  s.held_out_rms = rms_rows(held);
  s.trailing_edge_rms = model.trailing_edge_rms(all);
  s.node_rms = model.node_rms(all);
  return s;
}

fit::ParameterSpace extended(const fit::ParameterSpace& space, const std::vector<fit::Parameter>& more) {
  auto p = space.parameters();
  p.insert(p.end(), more.begin(), more.end());
  return fit::ParameterSpace(p, "effect parameters");
}

// Every remaining candidate's score at the current fit: one model run per score direction
// (sensitivity (r_c - r) / h), the score test off span(J), robust when the layout is given.
void score_candidates(const TracedModel& model, const std::vector<std::string>& effects,
                      const Eigen::VectorXd& parameters, const std::vector<std::string>& remaining,
                      const Eigen::VectorXd& r, const Eigen::MatrixXd& basis, int fitted,
                      const fit::ResidualLayout* layout, double in_span_tolerance,
                      const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& training,
                      const std::string& step_name, TraceStep& step,
                      const std::function<void(const std::string&)>& say) {
  for (const auto& c : remaining) {
    const auto dirs = model.score_directions(c);
    Eigen::MatrixXd s(r.size(), static_cast<Eigen::Index>(dirs.size()));
    auto with = effects;
    with.push_back(c);
    std::string failure;
    try {
      for (std::size_t j = 0; j < dirs.size(); ++j) {
        Eigen::VectorXd p(parameters.size() + dirs[j].parameters.size());
        p << parameters, dirs[j].parameters;
        ++step.evaluations;
        const Eigen::VectorXd plus = training(model.residuals(with, p));
        if (!dirs[j].central) {
          s.col(static_cast<Eigen::Index>(j)) = (plus - r) / dirs[j].step;
          continue;
        }
        p.tail(dirs[j].parameters.size()) = 2 * model.effect_off(c) - dirs[j].parameters;
        ++step.evaluations;
        s.col(static_cast<Eigen::Index>(j)) = (plus - training(model.residuals(with, p))) / (2 * dirs[j].step);
      }
    } catch (const std::exception& e) {
      // A model that fails with the candidate on is reported, and the candidate not ranked.
      failure = e.what();
      s.setZero();
    }
    const double data = static_cast<double>(r.size()) * model.data_per_point() / 3.0;
    step.scores.push_back({c, score_test(r, basis, fitted, s, in_span_tolerance, layout, data), failure});
    if (!failure.empty()) say("step " + step_name + ": " + c + " failed: " + failure);
    const ScoreResult& score = step.scores.back().score;
    std::ostringstream line;
    line << "step " << step_name << ": " << c << " score " << score.statistic << " (q " << dirs.size() << ", p "
         << score.p_value << (score.correlated ? ", correlated residual" : "") << ")";
    say(line.str());
  }
}

}  // namespace

HeldOutSplit held_out_split(const std::vector<double>& times, double period) {
  HeldOutSplit s;
  const int nf = static_cast<int>(times.size());
  if (nf >= 2 && period > 0 && times.back() - times.front() >= 2 * period * (nf - 1.0) / nf) {
    const double start = times.back() - period * (nf - 1.0) / nf - 1e-9 * period;
    for (int k = 0; k < nf; ++k)
      if (times[k] > start) s.held_out.push_back(k);
    s.kind = "last_cycle";
    return s;
  }
  for (int k = 1; k < nf; k += 2) s.held_out.push_back(k);
  s.kind = "interleaved";
  return s;
}

namespace {

// The training and held-out frames, and the rows of a frame's block from a residual `all`.
Split split_frames(const TracedModel& model, const std::vector<int>& held_out, const Eigen::VectorXd& all) {
  const int nf = model.frame_count();
  Split split;
  std::set<int> held(held_out.begin(), held_out.end());
  for (int k : held)
    if (k < 0 || k >= nf) throw InvalidInput("trace: held-out frame " + std::to_string(k) + " out of range");
  for (int k = 0; k < nf; ++k) (held.count(k) ? split.held_out : split.training).push_back(k);
  if (split.training.empty()) throw InvalidInput("trace: every frame is held out; nothing left to fit");
  if (all.size() % nf != 0 || (all.size() / nf) % 3 != 0)
    throw InvalidInput("trace: the model's residual is not frame_count() blocks of 3-vectors");
  split.rows_per_frame = all.size() / nf;
  return split;
}

}  // namespace

TraceResult trace_effects(const TracedModel& model, const TraceOptions& options) {
  auto say = [&](const std::string& line) {
    if (options.progress) options.progress(line);
  };
  TraceResult out;
  out.space = model.base_space();
  out.parameters = model.base_start();
  std::vector<std::string> effects;
  Eigen::VectorXd all = model.residuals(effects, out.parameters);
  ++out.evaluations;
  const Split split = split_frames(model, options.held_out_frames, all);
  // Where each residual sits, for the score test's correlation (empty: taken as independent).
  const Eigen::Matrix3Xd points = model.frame_points();
  if (points.cols() > 0 && 3 * points.cols() != split.rows_per_frame)
    throw InvalidInput("trace: the model's frame points (" + std::to_string(points.cols()) +
                       ") do not match its residual's frame block (" + std::to_string(split.rows_per_frame) + " rows)");
  const fit::ResidualLayout training_layout{static_cast<int>(split.training.size()), points};
  const fit::ResidualLayout* layout = points.cols() > 0 ? &training_layout : nullptr;
  out.base_initial = state_of(model, all, split, out.space.size());

  auto options_lm = options.lm;
  Eigen::MatrixXd jacobian;
  {
    TrainingResidual f(model, effects, out.space.size(), split.training, split.rows_per_frame);
    const Eigen::VectorXd z0 = out.space.to_scaled(out.parameters);
    if (options.refit_base) {
      const auto lm = fit::levenberg_marquardt(out.space, f, z0, options_lm);
      out.evaluations += lm.evaluations;
      out.parameters = out.space.to_physical(lm.z);
      jacobian = lm.jacobian;
      all = model.residuals(effects, out.parameters);
      ++out.evaluations;
    } else {
      jacobian = fit::finite_difference_jacobian(out.space, f, z0, f.pick(all), options_lm.fd_step, options_lm.central,
                                                 options_lm.threads, &out.evaluations);
    }
  }
  ModelState current = state_of(model, all, split, out.space.size());
  out.base = current;
  {
    std::ostringstream s;
    s << (options.refit_base ? "base refitted" : "base Jacobian") << ": training |r|^2 " << current.rss
      << ", held-out RMS " << current.held_out_rms << " m, trailing edge RMS " << current.trailing_edge_rms << " m ("
      << out.evaluations << " model runs)";
    say(s.str());
  }

  std::vector<std::string> remaining = model.candidates();
  while (true) {
    if (static_cast<int>(out.added.size()) >= options.max_effects) {
      out.stop_reason = "max_effects reached";
      break;
    }
    if (remaining.empty()) {
      out.stop_reason = "no candidate left";
      break;
    }
    if (current.training_rows <= out.space.size()) {
      out.stop_reason = "no residual degree of freedom left to test a candidate";
      break;
    }
    TraceStep step;
    step.before = current;
    const Eigen::VectorXd r = pick_frames(all, split.training, split.rows_per_frame);
    const Eigen::MatrixXd basis = orthonormal_basis(jacobian);
    score_candidates(
        model, effects, out.parameters, remaining, r, basis, out.space.size(), layout, options.in_span_tolerance,
        [&](const Eigen::VectorXd& all_c) { return pick_frames(all_c, split.training, split.rows_per_frame); },
        std::to_string(out.steps.size() + 1), step, say);
    std::stable_sort(step.scores.begin(), step.scores.end(), [](const auto& a, const auto& b) {
      return a.score.statistic > b.score.statistic;
    });
    const auto& best = step.scores.front();
    if (!(best.score.p_value * static_cast<double>(remaining.size()) < options.alpha)) {
      out.stop_reason = "no candidate significant (score test)";
      out.evaluations += step.evaluations;
      out.steps.push_back(std::move(step));
      break;
    }
    step.tried = best.name;
    const auto more = model.effect_parameters(best.name);
    const fit::ParameterSpace space = extended(out.space, more);
    auto with = effects;
    with.push_back(best.name);
    TrainingResidual f(model, with, space.size(), split.training, split.rows_per_frame);
    // The one-step estimate is linear; where the model is not, halve it (up to three times)
    // until it beats the current fit, so the refit never starts worse than without the effect.
    Eigen::VectorXd p0(space.size());
    for (int halving = 0; halving <= 3; ++halving) {
      p0 << out.parameters, model.effect_start(best.name, best.score.step * std::ldexp(1.0, -halving));
      double rss = INFINITY;
      try {
        rss = f.residuals(p0).squaredNorm();
      } catch (const std::exception&) {
      }
      ++step.evaluations;
      if (rss < current.rss) break;
    }
    const auto lm = fit::levenberg_marquardt(space, f, space.to_scaled(p0), options_lm);
    step.evaluations += lm.evaluations;
    const Eigen::VectorXd p = space.to_physical(lm.z);
    const Eigen::VectorXd all_after = model.residuals(with, p);
    ++step.evaluations;
    step.after = state_of(model, all_after, split, space.size());
    const int first = out.space.size();
    const int ne = static_cast<int>(more.size());
    step.magnitude = p.segment(first, ne);
    step.lower95 = Eigen::VectorXd::Constant(ne, NAN);
    step.upper95 = Eigen::VectorXd::Constant(ne, NAN);
    if (lm.jacobian.size() != 0) {
      const auto u = fit::compute_uncertainty(space, lm.z, lm.residuals, lm.jacobian, {}, layout);
      step.lower95 = u.lower95.segment(first, ne);
      step.upper95 = u.upper95.segment(first, ne);
    }
    for (const auto& q : more) step.effect_parameter_names.push_back(q.name);
    step.accepted = step.after.bic < step.before.bic && step.after.held_out_rms < step.before.held_out_rms;
    {
      std::ostringstream line;
      line << "step " << out.steps.size() + 1 << ": " << best.name << " refitted: BIC " << step.before.bic << " -> "
           << step.after.bic << ", held-out RMS " << step.before.held_out_rms << " -> " << step.after.held_out_rms
           << " m: " << (step.accepted ? "added" : "rejected");
      say(line.str());
    }
    out.evaluations += step.evaluations;
    const bool accepted = step.accepted;
    out.steps.push_back(std::move(step));
    if (!accepted) {
      out.stop_reason = "BIC or held-out error did not improve";
      break;
    }
    effects = with;
    out.added.push_back(best.name);
    out.space = space;
    out.parameters = p;
    jacobian = lm.jacobian;
    all = all_after;
    current = out.steps.back().after;
    remaining.erase(std::find(remaining.begin(), remaining.end(), best.name));
  }
  out.final_state = current;
  return out;
}

}  // namespace finverse::loop
