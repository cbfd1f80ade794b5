// Quasi-static objective, eq. (2) (see quasi_static_objective.hpp).
#include "fit/quasi_static_objective.hpp"

#include <cmath>
#include <sstream>

#include "fit/errors.hpp"
#include "fit/node_weights.hpp"
#include "fit/rotation_relaxation.hpp"
#include "fit/state_from_positions.hpp"

namespace finverse::fit {

struct QuasiStaticObjective::Workspace {
  Eigen::VectorXd key;
  std::unique_ptr<fem::Model> model;
  std::unique_ptr<fem::QuasiStaticIncrement> increment;  // refers to *model: declared after it
  // relax_rotations: a second model with the bases' translations held, and its solver.
  std::unique_ptr<fem::Model> held;
  std::unique_ptr<RotationRelaxation> relaxation;  // refers to *held
  // stress_free_base: one model per instant, built on that instant's shape, and its increment.
  std::vector<std::unique_ptr<fem::Model>> instant_models;
  std::vector<std::unique_ptr<fem::QuasiStaticIncrement>> instant_increments;
  void set_moduli(const ModelFactory& f, const std::vector<std::shared_ptr<const ModelFactory>>& rebased,
                  const Eigen::VectorXd& p) {
    f.set_moduli(*model, p);
    if (held) f.set_moduli(*held, p);
    for (size_t j = 0; j < instant_models.size(); ++j) rebased[j]->set_moduli(*instant_models[j], p);
  }
};

QuasiStaticObjective::~QuasiStaticObjective() = default;

QuasiStaticObjective::QuasiStaticObjective(std::shared_ptr<const ModelFactory> factory, TargetMotion target,
                                           QuasiStaticOptions options)
    : factory_(std::move(factory)), options_(std::move(options)) {
  if (!factory_) throw InvalidInput("quasi-static objective: no model factory");
  check_target(target);
  const std::string& src = target.source;
  // Topology, drive, weights and bases do not depend on the parameters: one nominal model.
  const std::unique_ptr<fem::Model> model = factory_->build(factory_->default_parameters());
  if (target.node_count() != model->node_count())
    throw InvalidInput(src + ": the target has " + std::to_string(target.node_count()) + " nodes, the model " +
                       std::to_string(model->node_count()));

  instants_ = options_.instants;
  if (instants_.empty()) instants_.push_back(target.times[target.times.size() / 2]);
  dt_ = options_.dt > 0 ? options_.dt : target.frame_spacing();
  if (!(dt_ > 0) || !std::isfinite(dt_))
    throw InvalidInput(src + ": quasi-static increment dt must be > 0 (a single-frame target has no frame spacing)");
  const fem::LoadHistory& loads = model->load_history();
  for (double t : instants_) {
    target.positions_at(t), target.positions_at(t + dt_);  // throw outside the target's span
    if (!loads.empty()) {
      const double tol = 1e-9 * dt_;
      if (t < loads.times().front() - tol || t + dt_ > loads.times().back() + tol) {
        std::ostringstream os;
        os << src << ": the increment [" << t << ", " << t + dt_ << "] leaves the loads' span ["
           << loads.times().front() << ", " << loads.times().back() << "]";
        throw InvalidInput(os.str());
      }
    }
  }

  const std::vector<int> prescribed = factory_->prescribed_nodes();
  weights_ = options_.node_weights.size() == 0
                 ? default_node_weights(*model, prescribed)
                 : checked_node_weights(options_.node_weights, model->node_count(), prescribed,
                                        "quasi-static objective");
  nodes_ = fit::compared_nodes(weights_);
  sqrt_weights_.resize(static_cast<Eigen::Index>(nodes_.size() * instants_.size()));
  for (size_t j = 0, k = 0; j < instants_.size(); ++j)
    for (int n : nodes_) sqrt_weights_(static_cast<Eigen::Index>(k++)) = std::sqrt(weights_(n));

  const StateFromPositions from_positions(*model);
  for (double t : instants_) {
    const std::vector<fem::Vec3> x0 = target.positions_at(t), x1 = target.positions_at(t + dt_);
    if (options_.stress_free_base) {
      // The instant's shape is the model's reference: the base is its reference state with the
      // drive's values at t (the root's displacement from that shape, zero up to the drive's fit).
      auto rebased = factory_->rebased(x0);
      if (!rebased) throw InvalidInput(src + ": this model cannot take a stress-free base (no rebased factory)");
      const std::unique_ptr<fem::Model> at_t = rebased->build(rebased->default_parameters());
      fem::NodalState base = at_t->reference_state();
      fem::apply_prescribed(*at_t, t, t, base);
      base_.push_back(std::move(base));
      rebased_.push_back(std::move(rebased));
    } else {
      fem::NodalState base = from_positions(x0);
      // The drive's own values at t (t1 = t2: no spin), so that the FE root increment is the drive's.
      fem::apply_prescribed(*model, t, t, base);
      base_.push_back(std::move(base));
    }
    std::vector<fem::Vec3> dx(x0.size());
    for (size_t i = 0; i < dx.size(); ++i) dx[i] = x1[i] - x0[i];
    target_dx_.push_back(std::move(dx));
  }
}

std::unique_ptr<QuasiStaticObjective::Workspace> QuasiStaticObjective::acquire(const Eigen::VectorXd& p) const {
  if (p.size() != factory_->parameter_count())
    throw InvalidInput("quasi-static objective: " + std::to_string(p.size()) + " parameters, the model has " +
                       std::to_string(factory_->parameter_count()));
  const Eigen::VectorXd key = factory_->rebuild_key(p);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = idle_.begin(); it != idle_.end(); ++it)
      if ((*it)->key.size() == key.size() && (*it)->key == key) {
        std::unique_ptr<Workspace> w = std::move(*it);
        idle_.erase(it);
        w->set_moduli(*factory_, rebased_, p);
        return w;
      }
  }
  auto w = std::make_unique<Workspace>();
  w->key = key;
  w->model = factory_->build(key);
  w->increment = std::make_unique<fem::QuasiStaticIncrement>(*w->model, options_.static_options);
  for (const auto& f : rebased_) {
    w->instant_models.push_back(f->build(key));
    w->instant_increments.push_back(
        std::make_unique<fem::QuasiStaticIncrement>(*w->instant_models.back(), options_.static_options));
  }
  if (options_.relax_rotations && rebased_.empty()) {
    w->held = factory_->build(key);
    w->relaxation = std::make_unique<RotationRelaxation>(*w->held, instants_, base_, options_.static_options);
  }
  ++builds_;
  // Always through set_moduli, also right after a build: the result then depends on p alone.
  w->set_moduli(*factory_, rebased_, p);
  return w;
}

void QuasiStaticObjective::release(std::unique_ptr<Workspace> w) const {
  if (options_.cached_models <= 0) return;
  std::lock_guard<std::mutex> lock(mutex_);
  idle_.push_front(std::move(w));
  while (static_cast<int>(idle_.size()) > options_.cached_models) idle_.pop_back();
}

std::vector<std::vector<fem::Vec3>> QuasiStaticObjective::increments(const Eigen::VectorXd& p) const {
  std::unique_ptr<Workspace> w = acquire(p);
  std::vector<std::vector<fem::Vec3>> dx;
  // On an exception the workspace is dropped (its solver may hold a failed factorisation).
  for (size_t j = 0; j < instants_.size(); ++j) {
    const double t = instants_[j];
    if (!w->instant_increments.empty())
      dx.push_back(w->instant_increments[j]->displacement_increment(base_[j], t, t + dt_));
    else if (w->relaxation)
      dx.push_back(w->increment->displacement_increment(w->relaxation->relax(base_[j], t), t, t + dt_));
    else
      dx.push_back(w->increment->displacement_increment(base_[j], t, t + dt_));
  }
  release(std::move(w));
  return dx;
}

Eigen::VectorXd QuasiStaticObjective::residuals(const Eigen::VectorXd& p) const {
  const auto dx = increments(p);
  Eigen::VectorXd r(residual_count());
  Eigen::Index k = 0;
  for (size_t j = 0; j < instants_.size(); ++j)
    for (size_t c = 0; c < nodes_.size(); ++c, ++k) {
      const int n = nodes_[c];
      r.segment<3>(3 * k) = sqrt_weights_(k) * (dx[j][n] - target_dx_[j][n]);
    }
  return r;
}

}  // namespace finverse::fit
