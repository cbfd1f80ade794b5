// Generalized-alpha time stepping with Newton iterations (see generalized_alpha.hpp).
#include "fem/generalized_alpha.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "fem/errors.hpp"
#include "fem/newton_iteration.hpp"
#include "fem/static_solver.hpp"

namespace finverse::fem {

namespace {
// Full-length increment from configuration a to b: translations, and spatial rotation vectors
// log(R_b R_a^T).
Eigen::VectorXd configuration_difference(const NodalState& a, const NodalState& b) {
  const int n = a.node_count();
  Eigen::VectorXd d(kDofsPerNode * n);
  for (int i = 0; i < n; ++i) {
    d.segment<3>(kDofsPerNode * i) = b.position[i] - a.position[i];
    d.segment<3>(kDofsPerNode * i + 3) = log_so3(b.rotation[i] * a.rotation[i].transpose());
  }
  return d;
}
}  // namespace

DynamicOptions with_model_damping(const Model& model, DynamicOptions options) {
  options.rayleigh_mass += model.rayleigh_mass();
  options.rayleigh_stiffness += model.rayleigh_stiffness();
  return options;
}

GeneralizedAlpha::GeneralizedAlpha(const Model& model, DynamicOptions options)
    : model_(model),
      opt_(with_model_damping(model, options)),
      dofs_((model.validate(), model)),
      assembler_(model_, dofs_),
      solver_(options.backend),
      predictor_solver_(options.backend),
      lchar_(model.characteristic_length()) {
  if (!(opt_.time_step > 0) || !std::isfinite(opt_.time_step))
    throw InvalidInput("generalized-alpha: time step must be > 0, got " + std::to_string(opt_.time_step));
  const double rho = opt_.spectral_radius;
  if (!(rho >= 0 && rho <= 1))
    throw InvalidInput("generalized-alpha: spectral radius " + std::to_string(rho) + ", expected 0..1");
  am_ = (2 * rho - 1) / (rho + 1);
  af_ = rho / (rho + 1);
  gamma_ = 0.5 - am_ + af_;
  beta_ = 0.25 * (1 - am_ + af_) * (1 - am_ + af_);
  solver_.set_equation_names([this](int eq) { return describe_equation(dofs_, eq); });
  predictor_solver_.set_equation_names([this](int eq) { return describe_equation(dofs_, eq); });
}

void GeneralizedAlpha::check_added_load(const Eigen::VectorXd& f) const {
  if (f.size() == 0) return;
  if (f.size() != dofs_.total())
    throw InvalidInput("generalized-alpha: added load has " + std::to_string(f.size()) +
                       " entries, expected " + std::to_string(dofs_.total()) + " (6 per node)");
  if (!f.allFinite()) throw InvalidInput("generalized-alpha: added load is not finite");
}

void GeneralizedAlpha::restore(const Snapshot& s) {
  if (s.initialized && s.old_terms.size() != dofs_.total())
    throw InvalidInput("generalized-alpha: snapshot of another model (old terms have " +
                       std::to_string(s.old_terms.size()) + " entries, expected " +
                       std::to_string(dofs_.total()) + ")");
  old_terms_ = s.old_terms;
  force_scale_ = s.force_scale;
  initialized_ = s.initialized;
}

DynamicState GeneralizedAlpha::reference_state(double t0) const {
  DynamicState s;
  s.configuration = model_.reference_state();
  s.velocity = Eigen::VectorXd::Zero(dofs_.total());
  s.acceleration = Eigen::VectorXd::Zero(dofs_.total());
  s.time = t0;
  return s;
}

void GeneralizedAlpha::store_old_terms(const DynamicState& s, const Eigen::VectorXd& added) {
  AssemblyRequest req;
  const bool stiff_damping = opt_.rayleigh_stiffness != 0;
  Eigen::VectorXd w = s.acceleration * am_ + s.velocity * (af_ * opt_.rayleigh_mass);
  req.mass_times = &w;
  if (stiff_damping) {
    req.viscous_velocity = &s.velocity;
    req.viscosity = opt_.rayleigh_stiffness;
  }
  req.time = s.time;
  assembler_.assemble(s.configuration, req);
  if (added.size() == 0)
    old_terms_ = assembler_.mass_product() + af_ * (assembler_.internal_force() -
                                                    model_.external_load(s.time));
  else
    old_terms_ = assembler_.mass_product() + af_ * (assembler_.internal_force() -
                                                    (model_.external_load(s.time) + added));
  if (stiff_damping) old_terms_ += af_ * assembler_.damping_force();
}

void GeneralizedAlpha::initialize(DynamicState& s) { initialize(s, Eigen::VectorXd()); }

void GeneralizedAlpha::initialize(DynamicState& s, const Eigen::VectorXd& added) {
  check_added_load(added);
  const int nt = dofs_.total();
  if (s.velocity.size() != nt) s.velocity = Eigen::VectorXd::Zero(nt);
  s.acceleration = Eigen::VectorXd::Zero(nt);
  // Prescribed accelerations: the forward second difference of the prescribed functions, the
  // acceleration the run meets after its start. A central one straddles the kink where a linear
  // ramp from rest begins (fin-loop's tracked root motion, load_history.hpp) and turns it into an
  // acceleration of slope / h, which the first predictor sends the free nodes flying with.
  const double h = 1e-3 * opt_.time_step;
  for (const auto& p : model_.prescribed())
    if (p.value)
      s.acceleration(kDofsPerNode * p.node + p.dof) =
          (p.at(s.time + 2 * h) - 2 * p.at(s.time + h) + p.at(s.time)) / (h * h);
  // Free accelerations from M_ff a_f = f_ext - f_int - C v - M_fp a_p.
  AssemblyRequest req;
  req.matrix = true;
  req.stiffness_coefficient = 0;
  req.mass_coefficient = 1;
  Eigen::VectorXd w = s.acceleration + opt_.rayleigh_mass * s.velocity;
  req.mass_times = &w;
  if (opt_.rayleigh_stiffness != 0) {
    req.viscous_velocity = &s.velocity;
    req.viscosity = opt_.rayleigh_stiffness;
  }
  req.time = s.time;
  assembler_.assemble(s.configuration, req);
  Eigen::VectorXd rhs = model_.external_load(s.time) - assembler_.internal_force() -
                        assembler_.mass_product();
  if (added.size() != 0) rhs += added;
  if (opt_.rayleigh_stiffness != 0) rhs -= assembler_.damping_force();
  SparseSolver mass_solver(opt_.backend);
  mass_solver.set_equation_names([this](int eq) { return describe_equation(dofs_, eq); });
  mass_solver.factorize(assembler_.matrix(), "mass matrix");
  const Eigen::VectorXd af = mass_solver.solve(dofs_.gather_free(rhs));
  for (int i = 0; i < dofs_.free(); ++i) s.acceleration(dofs_.free_to_global()[i]) = af(i);
  store_old_terms(s, added);
  initialized_ = true;
}

void GeneralizedAlpha::set_time_step(double h) {
  if (!(h > 0) || !std::isfinite(h))
    throw InvalidInput("generalized-alpha: time step must be > 0, got " + std::to_string(h));
  opt_.time_step = h;
}

DynamicStepInfo GeneralizedAlpha::step(DynamicState& s) { return step(s, Eigen::VectorXd()); }

DynamicStepInfo GeneralizedAlpha::step(DynamicState& s, const Eigen::VectorXd& added) {
  check_added_load(added);
  // Without a previous step the start load is the one at s.time; an added load given only now
  // counts as already acting at the start (a sudden load at t_n).
  if (!initialized_) initialize(s, added);
  const double h = opt_.time_step;
  const double t1 = s.time + h;
  const double aM = opt_.rayleigh_mass, aK = opt_.rayleigh_stiffness;
  const Eigen::VectorXd f_ext = added.size() == 0
                                    ? Eigen::VectorXd((1 - af_) * model_.external_load(t1))
                                    : Eigen::VectorXd((1 - af_) * (model_.external_load(t1) + added));

  // Predictor: prescribed DOFs to their new values, free DOFs with constant acceleration.
  NodalState x = s.configuration;
  apply_prescribed(model_, s.time, t1, x);
  {
    Eigen::VectorXd pred = opt_.predict_with_acceleration
                               ? Eigen::VectorXd(h * s.velocity + (0.5 * h * h) * s.acceleration)
                               : Eigen::VectorXd(Eigen::VectorXd::Zero(s.velocity.size()));
    for (int g = 0; g < dofs_.total(); ++g)
      if (dofs_.equation(g) < 0) pred(g) = 0;
    x.apply_increment(pred);
  }

  const double c_a = 1.0 / (beta_ * h * h);  // da/d(increment)
  const double c_v = gamma_ / (beta_ * h);   // dv/d(increment)
  AssemblyRequest req;
  req.matrix = true;
  // The damping force's tangent keeps C's dependence on the velocity only (c_v C); C's change with
  // the configuration is of relative size |v_def| h / l and is left to the iteration.
  req.stiffness_coefficient = 1 - af_;
  req.mass_coefficient = (1 - am_) * c_a + (1 - af_) * aM * c_v;
  req.viscosity = aK;
  req.damping_coefficient = (1 - af_) * c_v;
  req.time = t1;

  // Newton on the step's balance. Not the static iteration of newton_iteration.hpp: the residual
  // carries inertia and damping and is measured against the largest force level seen (a free
  // vibration passes through zero load), convergence is tested before the correction with the
  // previous increment relative to the step's, the factorisation is kept once the residual is
  // small (modified Newton), and a failure ends the run instead of cutting a load step.
  DynamicStepInfo info;
  Eigen::VectorXd a1, v1, w;
  double r0 = 0, floor = 0, last_inc = INFINITY, step_norm = 0, last_rn = INFINITY;
  const SparseSolver* current = &solver_;
  // Scaled norm (translations / lchar) of increments resolved only to position round-off.
  const double inc_floor =
      opt_.increment_roundoff_floor
          ? 10 * std::numeric_limits<double>::epsilon() * std::sqrt(double(dofs_.free())) *
                std::max(model_.position_scale() / lchar_, 1.0)
          : 0.0;
  for (int it = 0;; ++it) {
    const Eigen::VectorXd d = configuration_difference(s.configuration, x);
    a1 = c_a * (d - h * s.velocity - (h * h * (0.5 - beta_)) * s.acceleration);
    v1 = s.velocity + h * ((1 - gamma_) * s.acceleration + gamma_ * a1);
    w = (1 - am_) * a1 + ((1 - af_) * aM) * v1;
    req.mass_times = &w;
    req.viscous_velocity = aK != 0 ? &v1 : nullptr;
    assembler_.assemble(x, req);
    Eigen::VectorXd lhs = assembler_.mass_product() + (1 - af_) * assembler_.internal_force();
    if (aK != 0) lhs += (1 - af_) * assembler_.damping_force();
    const Eigen::VectorXd r_full = f_ext - lhs - old_terms_;
    const Eigen::VectorXd r = dofs_.gather_free(r_full);
    // The force level of a free vibration passes through zero twice a period; measure the
    // residual against the largest level seen so far instead.
    force_scale_ = std::max({force_scale_, dofs_.gather_free(f_ext).norm(),
                             dofs_.gather_free(assembler_.mass_product()).norm(),
                             dofs_.gather_free(assembler_.internal_force()).norm(), 1e-30});
    const double scale = force_scale_;
    const double rn = r.norm() / scale;
    info.residual = rn;
    if (!std::isfinite(rn)) {
      std::ostringstream os;
      os << "generalized-alpha: residual became NaN/Inf at t = " << t1;
      throw NotConverged(os.str());
    }
    if (it == 0) {
      r0 = rn;
      floor = roundoff_force_floor(assembler_.matrix(), dofs_, model_.position_scale());
    }
    if (rn <= opt_.residual_tolerance + floor / scale && last_inc <= opt_.increment_tolerance) break;
    if (it >= opt_.max_iterations) {
      std::ostringstream os;
      os.precision(4);
      os << "generalized-alpha Newton did not converge at t = " << t1 << " after " << it
         << " iterations (relative residual " << rn << " from " << r0 << ", tolerance "
         << opt_.residual_tolerance << "); reduce the time step";
      throw NotConverged(os.str());
    }
    // Modified Newton once close: the previous factorisation still contracts the small residual.
    if (it == 0 && opt_.reuse_predictor_factorization) {
      const auto& A = assembler_.matrix();
      const double* v = A.valuePtr();
      if (predictor_values_.size() != static_cast<std::size_t>(A.nonZeros()) ||
          !std::equal(predictor_values_.begin(), predictor_values_.end(), v)) {
        predictor_solver_.factorize(A, "effective stiffness");
        ++info.factorizations;
        predictor_values_.assign(v, v + A.nonZeros());
      }
      current = &predictor_solver_;
    } else if (it == 0 || rn > 1e-6 || !opt_.modified_newton || rn > 0.25 * last_rn) {
      // A kept factorisation that contracts the residual less than 4x per iteration (an impulsive
      // start, a root that jumps) is renewed rather than iterated on to the iteration cap.
      solver_.factorize(assembler_.matrix(), "effective stiffness");
      ++info.factorizations;
      current = &solver_;
    }
    last_rn = rn;
    const Eigen::VectorXd du = current->solve(r);
    const double inc = scaled_increment_norm(dofs_, du, lchar_);
    if (it == 0) {
      double dn = 0;
      for (int g = 0; g < dofs_.total(); ++g) {
        const double v = (g % kDofsPerNode) < 3 ? d(g) / lchar_ : d(g);
        dn += v * v;
      }
      step_norm = std::max(std::sqrt(dn), inc);
    }
    // Increments at the round-off of the positions count as zero (option): a step under a load
    // near zero (the start of an FSI ramp) moves so little that 1e-9 of its increment is noise.
    last_inc = (inc_floor > 0 ? std::max(inc - inc_floor, 0.0) : inc) / std::max(step_norm, 1e-300);
    x.apply_increment(dofs_.scatter_free(du));
    info.iterations = it + 1;
  }
  s.configuration = std::move(x);
  s.velocity = v1;
  s.acceleration = a1;
  s.time = t1;
  store_old_terms(s, added);
  return info;
}

double GeneralizedAlpha::kinetic_energy(const DynamicState& s) {
  return assembler_.kinetic_energy(s.configuration, s.velocity);
}

double GeneralizedAlpha::strain_energy(const DynamicState& s) const {
  return assembler_.strain_energy(s.configuration, s.time);
}

}  // namespace finverse::fem
