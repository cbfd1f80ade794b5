// Static load levels against measured positions (see static_objective.hpp).
#include "fit/static_objective.hpp"

#include <cmath>
#include <sstream>

#include "fit/errors.hpp"
#include "fit/node_weights.hpp"

namespace finverse::fit {

struct StaticObjective::Workspace {
  Eigen::VectorXd key;
  std::unique_ptr<fem::Model> model;
  std::unique_ptr<fem::StaticSolver> solver;  // refers to *model
};

StaticObjective::~StaticObjective() = default;

StaticObjective::StaticObjective(std::shared_ptr<const ModelFactory> factory, TargetMotion target,
                                 StaticObjectiveOptions options)
    : factory_(std::move(factory)), target_(std::move(target)), options_(std::move(options)) {
  const std::unique_ptr<fem::Model> model = nominal_model_for(factory_.get(), target_, "static objective");
  const std::string& src = target_.source;
  if (!(options_.start_level < target_.times.front())) {
    std::ostringstream os;
    os << src << ": the first load level " << target_.times.front() << " must follow the unloaded reference at "
       << options_.start_level;
    throw InvalidInput(os.str());
  }
  const fem::LoadHistory& loads = model->load_history();
  if (!loads.empty() && target_.times.back() > loads.times().back() * (1 + 1e-12) + 1e-300) {
    std::ostringstream os;
    os << src << ": load level " << target_.times.back() << " lies beyond the loads' last level "
       << loads.times().back();
    throw InvalidInput(os.str());
  }
  const std::vector<int> prescribed = factory_->prescribed_nodes();
  weights_ = options_.node_weights.size() == 0
                 ? default_node_weights(*model, prescribed)
                 : checked_node_weights(options_.node_weights, model->node_count(), prescribed, "static objective");
  nodes_ = fit::compared_nodes(weights_);
  points_ = compared_points(*model, nodes_);
  sqrt_weights_.resize(static_cast<Eigen::Index>(nodes_.size() * target_.times.size()));
  for (size_t k = 0, i = 0; k < target_.times.size(); ++k)
    for (int n : nodes_) sqrt_weights_(static_cast<Eigen::Index>(i++)) = std::sqrt(weights_(n));
}

std::unique_ptr<StaticObjective::Workspace> StaticObjective::acquire(const Eigen::VectorXd& p) const {
  if (p.size() != factory_->parameter_count())
    throw InvalidInput("static objective: " + std::to_string(p.size()) + " parameters, the model has " +
                       std::to_string(factory_->parameter_count()));
  const Eigen::VectorXd key = factory_->rebuild_key(p);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = idle_.begin(); it != idle_.end(); ++it)
      if ((*it)->key.size() == key.size() && (*it)->key == key) {
        std::unique_ptr<Workspace> w = std::move(*it);
        idle_.erase(it);
        factory_->set_moduli(*w->model, p);
        return w;
      }
  }
  auto w = std::make_unique<Workspace>();
  w->key = key;
  w->model = factory_->build(key);
  w->solver = std::make_unique<fem::StaticSolver>(*w->model, options_.static_options);
  factory_->set_moduli(*w->model, p);  // the result depends on p alone
  return w;
}

void StaticObjective::release(std::unique_ptr<Workspace> w) const {
  if (options_.cached_models <= 0) return;
  std::lock_guard<std::mutex> lock(mutex_);
  idle_.push_front(std::move(w));
  while (static_cast<int>(idle_.size()) > options_.cached_models) idle_.pop_back();
}

std::vector<std::vector<fem::Vec3>> StaticObjective::positions(const Eigen::VectorXd& p) const {
  std::unique_ptr<Workspace> w = acquire(p);
  // On an exception the workspace is dropped (its solver may hold a failed factorisation).
  fem::NodalState x = w->model->reference_state();
  fem::apply_prescribed(*w->model, options_.start_level, options_.start_level, x);
  std::vector<std::vector<fem::Vec3>> out;
  double level = options_.start_level;
  for (double next : target_.times) {
    w->solver->solve(x, level, next);
    out.push_back(x.position);
    level = next;
  }
  release(std::move(w));
  return out;
}

Eigen::VectorXd StaticObjective::residuals(const Eigen::VectorXd& p) const {
  const auto x = positions(p);
  Eigen::VectorXd r(residual_count());
  Eigen::Index i = 0;
  for (size_t k = 0; k < x.size(); ++k)
    for (int n : nodes_) {
      r.segment<3>(3 * i) = sqrt_weights_(i) * (x[k][n] - target_.positions[k][n]);
      ++i;
    }
  return r;
}

}  // namespace finverse::fit
