// The structure's side of an implicit FSI coupling step (see coupled_structure.hpp).
#include "fem/coupled_structure.hpp"

#include <cmath>
#include <optional>
#include <sstream>
#include <utility>

#include "fem/errors.hpp"

namespace finverse::fem {

namespace {
DynamicOptions integrator_options(const CoupledStructureOptions& o) {
  if (o.substeps < 1)
    throw InvalidInput("coupled structure: substeps must be >= 1, got " + std::to_string(o.substeps));
  if (o.dim < 1 || o.dim > 3)
    throw InvalidInput("coupled structure: dim must be 1, 2 or 3, got " + std::to_string(o.dim));
  DynamicOptions d = o.dynamics;
  d.time_step = o.dynamics.time_step / o.substeps;
  d.reuse_predictor_factorization = true;
  d.increment_roundoff_floor = true;
  return d;
}
}  // namespace

CoupledStructure::CoupledStructure(const Model& model, const CoupledStructureOptions& options,
                                   std::vector<int> wet_nodes)
    : model_(model), opt_(options), wet_(std::move(wet_nodes)),
      integrator_(model, integrator_options(options)) {
  if (wet_.empty()) throw InvalidInput("coupled structure: the wet-node list is empty");
  std::vector<bool> seen(model.node_count(), false);
  for (int n : wet_) {
    if (n < 0 || n >= model.node_count())
      throw InvalidInput("coupled structure: wet node " + std::to_string(n) + " out of range 0.." +
                         std::to_string(model.node_count() - 1));
    if (seen[n]) throw InvalidInput("coupled structure: wet node " + std::to_string(n) + " repeated");
    seen[n] = true;
  }
  opt_.dynamics = with_model_damping(model, opt_.dynamics);  // as the integrator does
  if (opt_.dynamics.rayleigh_mass != 0 || opt_.dynamics.rayleigh_stiffness != 0)
    damping_assembler_ = std::make_unique<Assembler>(model_, integrator_.dofs());
  initialize(options.start_time, Eigen::VectorXd::Zero(opt_.dim * static_cast<int>(wet_.size())));
}

Eigen::VectorXd CoupledStructure::damping_force(const DynamicState& s) {
  AssemblyRequest req;
  const bool viscous = opt_.dynamics.rayleigh_stiffness != 0;
  req.mass_times = &s.velocity;
  req.viscous_velocity = viscous ? &s.velocity : nullptr;
  req.viscosity = opt_.dynamics.rayleigh_stiffness;
  req.time = s.time;
  damping_assembler_->assemble(s.configuration, req);
  Eigen::VectorXd f = opt_.dynamics.rayleigh_mass * damping_assembler_->mass_product();
  if (viscous) f += damping_assembler_->damping_force();
  return f;
}

void CoupledStructure::check_load(const Eigen::VectorXd& f, const char* what) const {
  const long n = static_cast<long>(opt_.dim) * static_cast<long>(wet_.size());
  if (f.size() != n) {
    std::ostringstream os;
    os << "coupled structure: " << what << " has " << f.size() << " entries, expected " << n
       << " (" << opt_.dim << " per wet node)";
    throw InvalidInput(os.str());
  }
  for (int i = 0; i < f.size(); ++i)
    if (!std::isfinite(f(i))) {
      std::ostringstream os;
      os << "coupled structure: " << what << " entry " << i << " (wet node " << wet_[i / opt_.dim]
         << ") is not finite";
      throw InvalidInput(os.str());
    }
}

Eigen::VectorXd CoupledStructure::scatter(const Eigen::VectorXd& f) const {
  check_load(f, "interface load");
  Eigen::VectorXd full = Eigen::VectorXd::Zero(kDofsPerNode * model_.node_count());
  for (std::size_t k = 0; k < wet_.size(); ++k)
    for (int c = 0; c < opt_.dim; ++c) full(kDofsPerNode * wet_[k] + c) = f(opt_.dim * k + c);
  return full;
}

Eigen::VectorXd CoupledStructure::gather(const Eigen::VectorXd& full) const {
  Eigen::VectorXd out(opt_.dim * wet_.size());
  for (std::size_t k = 0; k < wet_.size(); ++k)
    for (int c = 0; c < opt_.dim; ++c) out(opt_.dim * k + c) = full(kDofsPerNode * wet_[k] + c);
  return out;
}

void CoupledStructure::initialize(const DynamicState& state, const Eigen::VectorXd& f) {
  const Eigen::VectorXd full = scatter(f);
  const int nt = kDofsPerNode * model_.node_count();
  if (state.configuration.node_count() != model_.node_count() || state.velocity.size() != nt)
    throw InvalidInput("coupled structure: initial state must have " +
                       std::to_string(model_.node_count()) + " nodes and full-length velocities");
  state_ = state;
  load_ = f;
  integrator_.initialize(state_, full);
  has_saved_ = false;
  advanced_ = false;
}

void CoupledStructure::initialize(double t0, const Eigen::VectorXd& f) {
  initialize(integrator_.reference_state(t0), f);
}

void CoupledStructure::save() {
  saved_.state = state_;
  saved_.integrator = integrator_.snapshot();
  saved_.load = load_;
  has_saved_ = true;
  advanced_ = false;
}

void CoupledStructure::restore() {
  if (!has_saved_) throw InvalidInput("coupled structure: restore() before save()");
  state_ = saved_.state;
  integrator_.restore(saved_.integrator);
  load_ = saved_.load;
}

void CoupledStructure::restart(const DynamicState& state, const GeneralizedAlpha::Snapshot& integrator,
                               const Eigen::VectorXd& f) {
  check_load(f, "restart interface load");
  const int nt = kDofsPerNode * model_.node_count();
  if (state.configuration.node_count() != model_.node_count() ||
      static_cast<int>(state.configuration.rotation.size()) != model_.node_count() || state.velocity.size() != nt ||
      state.acceleration.size() != nt)
    throw InvalidInput("coupled structure: restart state must have " + std::to_string(model_.node_count()) +
                       " nodes and full-length velocities and accelerations");
  integrator_.restore(integrator);
  state_ = state;
  load_ = f;
  save();
}

CoupledStepReport CoupledStructure::advance(double t_new, const Eigen::VectorXd& f_new) {
  if (!has_saved_)
    throw InvalidInput("coupled structure: advance() before save(): no start state for the step");
  check_load(f_new, "interface load");
  const double dt = opt_.dynamics.time_step;
  const double t_expected = saved_.state.time + dt;
  if (!(std::abs(t_new - t_expected) <= 1e-9 * dt)) {
    std::ostringstream os;
    os.precision(12);
    os << "coupled structure: advance to t = " << t_new << ", expected the step's end "
       << t_expected << " (start " << saved_.state.time << " + time step " << dt << ")";
    throw InvalidInput(os.str());
  }
  restore();
  CoupledStepReport rep;
  const int k = opt_.substeps;
  const double h = dt / k;
  const Eigen::VectorXd f0 = saved_.load;
  SubstepStart start{model_.external_load(state_.time), damping_assembler_ ? damping_force(state_) : Eigen::VectorXd()};
  Eigen::VectorXd f_prev = f0;
  for (int j = 1; j <= k; ++j) {
    // Linear in time over the sub-steps; the last one is f_new exactly.
    const Eigen::VectorXd f_j = j == k ? f_new : Eigen::VectorXd(f0 + (double(j) / k) * (f_new - f0));
    substep(h, f_prev, f_j, opt_.max_halvings, start, rep);
    f_prev = f_j;
  }
  state_.time = t_new;  // no drift of the sub-steps' summed times against the coupling's clock
  load_ = f_new;
  advanced_ = true;
  return rep;
}

void CoupledStructure::substep(double h, const Eigen::VectorXd& f_from, const Eigen::VectorXd& f_to, int halvings,
                               SubstepStart& start, CoupledStepReport& rep) {
  const NodalState x0 = state_.configuration;
  // What a retry restarts from; copied only when a retry may come.
  std::optional<std::pair<DynamicState, GeneralizedAlpha::Snapshot>> retry;
  if (halvings > 0) retry.emplace(state_, integrator_.snapshot());
  DynamicStepInfo info;
  integrator_.set_time_step(h);
  try {
    info = integrator_.step(state_, scatter(f_to));
  } catch (const NotConverged&) {
    if (!retry) throw;
    // The same sub-step as two of half the length, the load at its middle halfway.
    state_ = retry->first;
    integrator_.restore(retry->second);
    ++rep.halvings;
    const Eigen::VectorXd f_mid = 0.5 * (f_from + f_to);
    substep(0.5 * h, f_from, f_mid, halvings - 1, start, rep);
    substep(0.5 * h, f_mid, f_to, halvings - 1, start, rep);
    return;
  }
  rep.newton_iterations += info.iterations;
  rep.factorizations += info.factorizations;
  rep.residual = info.residual;
  // Work of the alpha_f-weighted loads the balance used, on the translation increments.
  const double af = integrator_.alpha_f();
  const Eigen::VectorXd fa = (1 - af) * f_to + af * f_from;
  for (std::size_t n = 0; n < wet_.size(); ++n) {
    const Vec3 du = state_.configuration.position[wet_[n]] - x0.position[wet_[n]];
    for (int c = 0; c < opt_.dim; ++c) {
      const int i = opt_.dim * static_cast<int>(n) + c;
      rep.interface_work += fa(i) * du(c);
      rep.interface_work_trapezoidal += 0.5 * (f_to(i) + f_from(i)) * du(c);
    }
  }
  if (damping_assembler_) {
    const Eigen::VectorXd damping_new = damping_force(state_);
    const Eigen::VectorXd ca = (1 - af) * damping_new + af * start.damping;
    for (int node = 0; node < model_.node_count(); ++node) {
      const Vec3 du = state_.configuration.position[node] - x0.position[node];
      const Vec3 dw = log_so3(state_.configuration.rotation[node] * x0.rotation[node].transpose());
      rep.damping_work += ca.segment<3>(kDofsPerNode * node).dot(du) + ca.segment<3>(kDofsPerNode * node + 3).dot(dw);
    }
    start.damping = damping_new;
  }
  const Eigen::VectorXd model_new = model_.external_load(state_.time);
  const Eigen::VectorXd ma = (1 - af) * model_new + af * start.model_load;
  const DofMap& dofs = integrator_.dofs();
  for (int g = 0; g < dofs.total(); ++g) {
    if (ma(g) == 0 || g % kDofsPerNode >= 3) continue;  // moments: no rotation work tracked
    const int node = g / kDofsPerNode, c = g % kDofsPerNode;
    rep.model_load_work += ma(g) * (state_.configuration.position[node](c) - x0.position[node](c));
  }
  start.model_load = model_new;
}

void CoupledStructure::accept() {
  if (!advanced_) throw InvalidInput("coupled structure: accept() without an advance() since save()");
  save();
}

Eigen::VectorXd CoupledStructure::wet_positions() const {
  Eigen::VectorXd out(opt_.dim * wet_.size());
  for (std::size_t k = 0; k < wet_.size(); ++k)
    for (int c = 0; c < opt_.dim; ++c) out(opt_.dim * k + c) = state_.configuration.position[wet_[k]](c);
  return out;
}
Eigen::VectorXd CoupledStructure::wet_velocities() const { return gather(state_.velocity); }
Eigen::VectorXd CoupledStructure::wet_accelerations() const { return gather(state_.acceleration); }

double CoupledStructure::kinetic_energy() { return integrator_.kinetic_energy(state_); }
double CoupledStructure::strain_energy() const { return integrator_.strain_energy(state_); }

}  // namespace finverse::fem
