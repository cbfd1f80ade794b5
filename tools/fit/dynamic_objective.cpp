// Dynamic objective, eq. (1) (see dynamic_objective.hpp).
#include "fit/dynamic_objective.hpp"

#include <cmath>
#include <sstream>

#include "fit/errors.hpp"
#include "fit/node_weights.hpp"

namespace finverse::fit {

DynamicObjective::DynamicObjective(std::shared_ptr<const ModelFactory> factory, TargetMotion target,
                                   DynamicObjectiveOptions options)
    : factory_(std::move(factory)), target_(std::move(target)) {
  const std::unique_ptr<fem::Model> model = nominal_model_for(factory_.get(), target_, "dynamic objective");
  const std::string& src = target_.source;
  const auto& t = target_.times;
  // The integrator's output interval is fixed: unequal frames would be silently mis-timed.
  const double h = t.size() > 1 ? t[1] - t[0] : t[0] - options.start_time;
  for (size_t k = 1; k < t.size(); ++k)
    if (std::abs((t[k] - t[k - 1]) - h) > 1e-6 * h)
      throw InvalidInput(src + ": the dynamic objective needs equally spaced frames (interval " +
                         std::to_string(k) + " differs)");
  if (!(options.start_time < t.front()))
    throw InvalidInput(src + ": the dynamic run's start time " + std::to_string(options.start_time) +
                       " must precede the first frame " + std::to_string(t.front()));
  if (options.substeps < 1) throw InvalidInput("dynamic objective: substeps must be >= 1");
  if (!(options.spectral_radius >= 0 && options.spectral_radius <= 1))
    throw InvalidInput("dynamic objective: spectral radius must lie in [0, 1]");
  const fem::LoadHistory& loads = model->load_history();
  if (!loads.empty() && t.back() > loads.times().back() + 1e-9 * h) {
    std::ostringstream os;
    os << src << ": frames up to t = " << t.back() << " reach beyond the loads' last time "
       << loads.times().back();
    throw InvalidInput(os.str());
  }

  const RayleighDamping damping = options.damping ? *options.damping : factory_->damping();
  run_options_.analysis = fem::Analysis::dynamic;
  run_options_.start_time = options.start_time;
  run_options_.substeps = options.substeps;
  run_options_.dynamic_options.spectral_radius = options.spectral_radius;
  // Newton's relative-increment test has no round-off floor: a run that starts smoothly from
  // rest (the twins' start window) moves by ~1e-12 of the position scale in its first steps and
  // never reaches 1e-9 there. The residual test (1e-9 with its round-off floor) still decides.
  run_options_.dynamic_options.increment_tolerance = 1e-6;
  run_options_.dynamic_options.rayleigh_mass = damping.mass;
  run_options_.dynamic_options.rayleigh_stiffness = damping.stiffness;

  const std::vector<int> prescribed = factory_->prescribed_nodes();
  weights_ = options.node_weights.size() == 0
                 ? default_node_weights(*model, prescribed)
                 : checked_node_weights(options.node_weights, model->node_count(), prescribed, "dynamic objective");
  nodes_ = fit::compared_nodes(weights_);
  points_ = compared_points(*model, nodes_);
  sqrt_weights_.resize(static_cast<Eigen::Index>(nodes_.size() * t.size()));
  for (size_t k = 0, i = 0; k < t.size(); ++k)
    for (int n : nodes_) sqrt_weights_(static_cast<Eigen::Index>(i++)) = std::sqrt(weights_(n));
}

std::vector<fem::RunFrame> DynamicObjective::run(const Eigen::VectorXd& p) const {
  if (p.size() != factory_->parameter_count())
    throw InvalidInput("dynamic objective: " + std::to_string(p.size()) + " parameters, the model has " +
                       std::to_string(factory_->parameter_count()));
  const std::unique_ptr<fem::Model> model = factory_->build(p);
  return fem::run_structural_analysis(*model, run_options_, target_.times);
}

Eigen::VectorXd DynamicObjective::residuals(const Eigen::VectorXd& p) const {
  const std::vector<fem::RunFrame> frames = run(p);
  Eigen::VectorXd r(residual_count());
  Eigen::Index i = 0;
  for (size_t k = 0; k < frames.size(); ++k)
    for (size_t c = 0; c < nodes_.size(); ++c, ++i) {
      const int n = nodes_[c];
      r.segment<3>(3 * i) = sqrt_weights_(i) * (frames[k].state.position[n] - target_.positions[k][n]);
    }
  return r;
}

}  // namespace finverse::fit
