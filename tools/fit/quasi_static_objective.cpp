// Quasi-static objective, eq. (2) (see quasi_static_objective.hpp).
#include "fit/quasi_static_objective.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <sstream>

#include "fem/errors.hpp"
#include "fit/errors.hpp"
#include "fit/measured_inertia.hpp"
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
  // Solve::linear: a model that only carries the moduli of p, and the solver's state.
  std::unique_ptr<fem::Model> moduli_model;
  std::unique_ptr<fem::LinearIncrement::Workspace> linear;
  // Solve::stored: the factorisation of the stored tangent (one pattern for every instant).
  std::unique_ptr<fem::StoredTangentIncrement::Workspace> stored;
  void set_moduli(const ModelFactory& f, const std::vector<std::shared_ptr<const ModelFactory>>& rebased,
                  const Eigen::VectorXd& p) {
    if (model) f.set_moduli(*model, p);
    if (moduli_model) f.set_moduli(*moduli_model, p);
    if (held) f.set_moduli(*held, p);
    for (size_t j = 0; j < instant_models.size(); ++j) rebased[j]->set_moduli(*instant_models[j], p);
  }
};

QuasiStaticObjective::~QuasiStaticObjective() = default;

QuasiStaticOptions::Solve parse_increment_solve(const std::string& name) {
  if (name == "newton") return QuasiStaticOptions::Solve::newton;
  if (name == "stored") return QuasiStaticOptions::Solve::stored;
  if (name == "linear") return QuasiStaticOptions::Solve::linear;
  throw InvalidInput("--increment '" + name + "': expected newton, stored or linear");
}

namespace {
// Poisson ratios of the linearised increment's basis (fem/tangent_basis.hpp): spread over the
// physical range so that the 4 x 4 solve per entry is well conditioned.
constexpr double kBasisPoisson[fem::TangentBasis::kPoissonModels] = {0.1, 0.3, 0.4, 0.49};

// Every element's Young's modulus at time t: what the stored and linear routes weigh their
// element matrices with.
std::vector<double> element_moduli_at(const fem::Model& model, double t) {
  std::vector<double> moduli(model.elements().size());
  for (size_t e = 0; e < moduli.size(); ++e) moduli[e] = model.element_youngs_modulus(static_cast<int>(e), t);
  return moduli;
}
}  // namespace

QuasiStaticObjective::QuasiStaticObjective(std::shared_ptr<const ModelFactory> factory, TargetMotion target,
                                           QuasiStaticOptions options)
    : factory_(std::move(factory)), options_(std::move(options)) {
  // Topology, drive, weights and bases do not depend on the parameters: one nominal model.
  const std::unique_ptr<fem::Model> model = nominal_model_for(factory_.get(), target, "quasi-static objective");
  const std::string& src = target.source;

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
  points_ = compared_points(*model, nodes_);
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
      if (options_.inertia) load_change_.push_back(inertial_load_change(*at_t, base, target, t, dt_));
      base_.push_back(std::move(base));
      rebased_.push_back(std::move(rebased));
    } else {
      fem::NodalState base = from_positions(x0);
      // The drive's own values at t (t1 = t2: no spin), so that the FE root increment is the drive's.
      fem::apply_prescribed(*model, t, t, base);
      if (options_.inertia) load_change_.push_back(inertial_load_change(*model, base, target, t, dt_));
      base_.push_back(std::move(base));
    }
    std::vector<fem::Vec3> dx(x0.size());
    for (size_t i = 0; i < dx.size(); ++i) dx[i] = x1[i] - x0[i];
    target_dx_.push_back(std::move(dx));
  }
  if (options_.solve != QuasiStaticOptions::Solve::newton) set_up_stored_tangents(target);
}

// The stored tangents, in the modulus-Poisson basis from the model at four Poisson ratios,
// checked against a model at the default parameters. Solve::linear: each instant's tangent at its
// base (fem/linear_increment.hpp). Solve::stored: at the increment's converged state at the
// default parameters, the reference each evaluation starts from (fem/stored_tangent_increment.hpp).
void QuasiStaticObjective::set_up_stored_tangents(const TargetMotion& target) {
  const std::string& src = target.source;
  const bool linear = options_.solve == QuasiStaticOptions::Solve::linear;
  const std::string route = linear ? "the linear increment" : "the stored increment";
  if (!factory_->moduli_and_poisson_only())
    throw InvalidInput(src + ": " + route +
                       " needs parameters that are element moduli and one Poisson ratio; "
                       "this model has others (use the newton increment)");
  if (!options_.stress_free_base && options_.relax_rotations)
    throw InvalidInput(src + ": " + route +
                       " needs bases that do not depend on the parameters: stress-free "
                       "bases, or rotations not relaxed");
  const int nu_index = factory_->poisson_index();
  const Eigen::VectorXd p0 = factory_->default_parameters();
  const std::vector<double> nus =
      nu_index < 0 ? std::vector<double>{0.0} : std::vector<double>(std::begin(kBasisPoisson), std::end(kBasisPoisson));
  const auto build_at = [&](const ModelFactory& f) {
    std::vector<std::unique_ptr<fem::Model>> models;
    for (double nu : nus) {
      Eigen::VectorXd p = p0;
      if (nu_index >= 0) p(nu_index) = nu;
      models.push_back(f.build(p));
    }
    return models;
  };
  basis_poisson_ = nus;
  if (rebased_.empty()) linear_models_.push_back(build_at(*factory_));
  for (size_t j = 0; j < instants_.size(); ++j) {
    const ModelFactory& f = rebased_.empty() ? *factory_ : *rebased_[j];
    if (!rebased_.empty()) linear_models_.push_back(build_at(f));
    const auto& models = linear_models_.back();
    const double t = instants_[j];
    for (int e = 0; e < static_cast<int>(models[0]->elements().size()); ++e)
      if (models[0]->element_youngs_modulus(e, t) != models[0]->element_youngs_modulus(e, t + dt_))
        throw InvalidInput(src + ": " + route + " needs moduli constant over the increment (element " +
                           std::to_string(e) + "'s changes); use the newton increment");
    std::vector<const fem::Model*> pointers;
    for (const auto& m : models) pointers.push_back(m.get());
    const std::unique_ptr<fem::Model> check = f.build(p0);
    const fem::TangentBasis* basis = nullptr;
    if (linear) {
      linear_.push_back(std::make_unique<fem::LinearIncrement>(pointers, nus, base_[j], t, t + dt_, load_change(j)));
      basis = &linear_.back()->basis();
    } else {
      stored_.push_back(stored_at(j, *check, poisson_of(p0)));
      basis = &stored_.back()->basis();
    }
    if (nu_index >= 0) linear_form_error_ = std::max(linear_form_error_, basis->form_error(*check, p0(nu_index)));
  }
  if (!(linear_form_error_ <= 1e-8))
    throw InvalidInput(src + ": the model's tangent is not of the modulus-Poisson form " + route +
                       " needs (relative error " + std::to_string(linear_form_error_) + "); use the newton increment");
}

// Solve::stored: instant j's reference, the converged increment of `model` (the factory's model
// at the reference parameters), and the stored tangent there. With `from` (the current reference)
// the increment is solved from it, at a tenth of Newton's cost from the base, and to Newton's
// tolerances; Newton from the base where that does not converge.
std::unique_ptr<fem::StoredTangentIncrement> QuasiStaticObjective::stored_at(
    size_t j, const fem::Model& model, double nu, const fem::StoredTangentIncrement* from) const {
  const double t = instants_[j];
  std::vector<double> moduli = element_moduli_at(model, t + dt_);
  fem::QuasiStaticIncrement newton(model, options_.static_options);
  fem::NodalState reference;
  bool solved = false;
  if (from) {
    const Eigen::VectorXd f_target = model.external_load(t + dt_) - newton.base_offset(base_[j], t, load_change(j));
    fem::StoredTangentIncrement::Workspace w(options_.static_options.backend);
    solved = from->solve(newton.solver().assembler(), t + dt_, moduli, nu, f_target, reference, w);
  }
  if (!solved) reference = newton.solve(base_[j], t, t + dt_, nullptr, load_change(j));
  std::vector<const fem::Model*> pointers;
  for (const auto& m : linear_models_[rebased_.empty() ? 0 : j]) pointers.push_back(m.get());
  const fem::StoredTangentOptions so{.residual_tolerance = options_.static_options.residual_tolerance,
                                     .increment_tolerance = options_.static_options.increment_tolerance,
                                     .reuse_within = options_.reuse_reference_tangent ? 0.05 : 0.0};
  auto stored = std::make_unique<fem::StoredTangentIncrement>(pointers, basis_poisson_, reference, t + dt_, so);
  stored->set_reference_moduli(std::move(moduli), nu);
  return stored;
}

// The references move only when p is outside their reuse window: within it a Jacobian's columns
// already run on the references' own tangents, and a move costs a converged increment and a new
// tangent basis per instant.
void QuasiStaticObjective::expect_near(const Eigen::VectorXd& p) const {
  if (stored_.empty()) return;
  std::vector<std::unique_ptr<fem::Model>> models;
  bool near = true;
  for (size_t j = 0; j < instants_.size(); ++j) {
    models.push_back((rebased_.empty() ? *factory_ : *rebased_[j]).build(p));
    near = near && stored_[j]->near_reference(element_moduli_at(*models.back(), instants_[j] + dt_), poisson_of(p));
  }
  if (near) return;
  std::vector<std::unique_ptr<fem::StoredTangentIncrement>> moved;
  try {
    for (size_t j = 0; j < instants_.size(); ++j)
      moved.push_back(stored_at(j, *models[j], poisson_of(p), stored_[j].get()));
  } catch (const fem::NotConverged&) {
    return;  // keep the references there are: p is a hint, and Newton fails at p anyway
  } catch (const fem::SingularMatrix&) {
    return;
  }
  stored_ = std::move(moved);
}

std::unique_ptr<QuasiStaticObjective::Workspace> QuasiStaticObjective::acquire(const Eigen::VectorXd& p) const {
  if (p.size() != factory_->parameter_count())
    throw InvalidInput("quasi-static objective: " + std::to_string(p.size()) + " parameters, the model has " +
                       std::to_string(factory_->parameter_count()));
  // The linear route's workspaces only carry moduli: any of them serves any p.
  const bool linear = !linear_.empty();
  const Eigen::VectorXd key = linear ? Eigen::VectorXd() : factory_->rebuild_key(p);
  std::unique_ptr<Workspace> spare;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = idle_.begin(); it != idle_.end(); ++it)
      if ((*it)->key.size() == key.size() && (*it)->key == key) {
        std::unique_ptr<Workspace> w = std::move(*it);
        idle_.erase(it);
        w->set_moduli(*factory_, rebased_, p);
        return w;
      }
    // The least recently used workspace, to be rebuilt for this key (rekey).
    if (!linear && !idle_.empty() && !idle_.back()->relaxation) {
      spare = std::move(idle_.back());
      idle_.pop_back();
    }
  }
  if (spare && rekey(*spare, key)) {
    spare->set_moduli(*factory_, rebased_, p);
    return spare;
  }
  auto w = std::make_unique<Workspace>();
  w->key = key;
  if (linear) {
    w->moduli_model = factory_->build(factory_->default_parameters());
    w->linear = std::make_unique<fem::LinearIncrement::Workspace>(options_.static_options.backend);
    ++builds_;
    w->set_moduli(*factory_, rebased_, p);
    return w;
  }
  // With stress-free bases every increment is solved on its instant's model: no shared one.
  if (rebased_.empty()) {
    w->model = factory_->build(key);
    w->increment = std::make_unique<fem::QuasiStaticIncrement>(*w->model, options_.static_options);
  }
  if (!stored_.empty())
    w->stored = std::make_unique<fem::StoredTangentIncrement::Workspace>(options_.static_options.backend);
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

// A workspace built for another rebuild key (another nu) takes the models of `key` in place: with
// the same topology its DofMaps, assemblers and symbolic factorisations still serve, and building
// those is most of a workspace's cost (a fit gives every individual its own nu). The models are
// moved into the existing objects, which the solvers refer to. Workspaces with a rotation
// relaxation are not rekeyed (its model carries extra prescriptions).
bool QuasiStaticObjective::rekey(Workspace& w, const Eigen::VectorXd& key) const {
  std::unique_ptr<fem::Model> model;
  if (w.model) {
    model = factory_->build(key);
    if (!fem::same_topology(*w.model, *model)) return false;
  }
  std::vector<std::unique_ptr<fem::Model>> instant;
  for (size_t j = 0; j < rebased_.size(); ++j) {
    instant.push_back(rebased_[j]->build(key));
    if (!fem::same_topology(*w.instant_models[j], *instant.back())) return false;
  }
  if (model) *w.model = std::move(*model);
  for (size_t j = 0; j < instant.size(); ++j) *w.instant_models[j] = std::move(*instant[j]);
  w.key = key;
  ++rekeys_;
  return true;
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
    if (w->linear) {
      dx.push_back(
          linear_[j]->displacement_increment(element_moduli_at(*w->moduli_model, t + dt_), poisson_of(p), *w->linear));
    } else if (!stored_.empty()) {
      dx.push_back(
          stored_increment(j, w->instant_increments.empty() ? *w->increment : *w->instant_increments[j], p, *w));
    } else if (!w->instant_increments.empty()) {
      dx.push_back(w->instant_increments[j]->displacement_increment(base_[j], t, t + dt_, nullptr, load_change(j)));
    } else if (w->relaxation) {
      dx.push_back(
          w->increment->displacement_increment(w->relaxation->relax(base_[j], t), t, t + dt_, nullptr, load_change(j)));
    } else {
      dx.push_back(w->increment->displacement_increment(base_[j], t, t + dt_, nullptr, load_change(j)));
    }
  }
  release(std::move(w));
  return dx;
}

// Solve::stored: the increment from the reference solution on its stored tangent; Newton from the
// base where that iteration does not converge (moduli far from the reference's).
std::vector<fem::Vec3> QuasiStaticObjective::stored_increment(size_t j, fem::QuasiStaticIncrement& increment,
                                                              const Eigen::VectorXd& p, Workspace& w) const {
  const double t = instants_[j], t_next = t + dt_;
  const fem::Model& m = increment.solver().model();
  const std::vector<double> moduli = element_moduli_at(m, t_next);
  const Eigen::VectorXd f_target = m.external_load(t_next) - increment.base_offset(base_[j], t, load_change(j));
  fem::NodalState x;
  fem::StoredTangentInfo info;
  const bool ok =
      stored_[j]->solve(increment.solver().assembler(), t_next, moduli, poisson_of(p), f_target, x, *w.stored, &info);
  ++stored_solves_;
  stored_reuses_ += info.reused_reference ? 1 : 0;
  stored_iterations_ += info.iterations;
  if (!ok) {
    ++stored_fallbacks_;
    return increment.displacement_increment(base_[j], t, t_next, nullptr, load_change(j));
  }
  std::vector<fem::Vec3> dx(x.position.size());
  for (size_t i = 0; i < dx.size(); ++i) dx[i] = x.position[i] - base_[j].position[i];
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
