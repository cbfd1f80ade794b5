// Crisfield's cylindrical arc-length method with adaptive step and cutback (see arc_length.hpp).
#include "fem/arc_length.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fem/errors.hpp"
#include "fem/newton_iteration.hpp"
#include "fem/static_solver.hpp"

namespace finverse::fem {

namespace {

[[noreturn]] void bad_option(const std::string& what) {
  throw InvalidInput("arc-length: " + what);
}

bool crosses(double before, double after, double target) {
  return after == target || (before - target) * (after - target) < 0;
}

}  // namespace

ArcLengthSolver::ArcLengthSolver(const Model& model, ArcLengthOptions options)
    : model_(model),
      opt_(std::move(options)),
      dofs_((model.validate(), model)),
      assembler_(model_, dofs_, opt_.unsymmetric_tangent),
      solver_(tangent_backend(opt_.backend, opt_.unsymmetric_tangent)) {
  const auto finite_positive = [](double v) { return std::isfinite(v) && v > 0; };
  if (!(std::isfinite(opt_.initial_arc_length) && opt_.initial_arc_length >= 0))
    bad_option("initial_arc_length must be >= 0");
  if (opt_.initial_arc_length == 0 &&
      !(std::isfinite(opt_.initial_load_increment) && opt_.initial_load_increment != 0))
    bad_option("initial_load_increment must be finite and nonzero");
  if (!(std::isfinite(opt_.min_arc_length) && opt_.min_arc_length >= 0) ||
      !(std::isfinite(opt_.max_arc_length) && opt_.max_arc_length >= 0))
    bad_option("min_arc_length and max_arc_length must be >= 0");
  if (opt_.max_arc_length > 0 && opt_.min_arc_length > opt_.max_arc_length)
    bad_option("min_arc_length exceeds max_arc_length");
  if (opt_.target_iterations < 1) bad_option("target_iterations must be >= 1");
  if (opt_.max_steps < 1) bad_option("max_steps must be >= 1");
  if (opt_.max_iterations < 1) bad_option("max_iterations must be >= 1");
  if (!finite_positive(opt_.residual_tolerance) || !finite_positive(opt_.increment_tolerance))
    bad_option("tolerances must be positive");
  if (opt_.stop_load_factor && !std::isfinite(*opt_.stop_load_factor))
    bad_option("stop_load_factor must be finite");
  for (int g : opt_.tracked_dofs)
    if (g < 0 || g >= dofs_.total())
      bad_option("tracked DOF " + std::to_string(g) + " out of range [0, " +
                 std::to_string(dofs_.total()) + ")");
  if (opt_.stop_dof >= 0) {
    if (opt_.stop_dof >= dofs_.total() || opt_.stop_dof % kDofsPerNode >= 3)
      bad_option("stop_dof " + std::to_string(opt_.stop_dof) +
                 " is not a translational DOF of the model");
    if (dofs_.is_prescribed(opt_.stop_dof))
      bad_option("stop_dof " + describe_dof(opt_.stop_dof) + " is prescribed");
    if (!std::isfinite(opt_.stop_displacement)) bad_option("stop_displacement must be finite");
    const auto& f2g = dofs_.free_to_global();
    stop_equation_ =
        static_cast<int>(std::find(f2g.begin(), f2g.end(), opt_.stop_dof) - f2g.begin());
  }
  solver_.set_equation_names([this](int eq) { return describe_equation(dofs_, eq); });

  const double lchar = model.characteristic_length();
  weight2_.resize(dofs_.free());
  for (int i = 0; i < dofs_.free(); ++i)
    weight2_(i) = dofs_.free_to_global()[i] % kDofsPerNode < 3 ? 1.0 / (lchar * lchar) : 1.0;

  q_full_ = model.reference_load();
  fixed_load_ = model.external_load(opt_.time) - model.load_factor(opt_.time) * q_full_;
  for (int g = 0; g < fixed_load_.size(); ++g)
    if (!std::isfinite(fixed_load_(g)) || !std::isfinite(q_full_(g))) {
      std::ostringstream os;
      os << "arc-length: external load on " << describe_dof(g) << " is not finite at time "
         << opt_.time;
      throw InvalidInput(os.str());
    }
  q_free_ = dofs_.gather_free(q_full_);
  if (q_free_.norm() == 0)
    throw InvalidInput("arc-length: the reference load (nodal loads) is zero on the free DOFs");
}

double ArcLengthSolver::dot_s(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
  return (a.array() * b.array() * weight2_.array()).sum();
}

double ArcLengthSolver::displacement(const NodalState& state, int g) const {
  const int node = g / kDofsPerNode, c = g % kDofsPerNode;
  if (c < 3) return state.position[node](c) - model_.reference_positions()[node](c);
  return log_so3(state.rotation[node])(c - 3);
}

ArcLengthPoint ArcLengthSolver::point(const NodalState& state, double lam) const {
  ArcLengthPoint p;
  p.load_factor = lam;
  for (int g : opt_.tracked_dofs) p.values.push_back(displacement(state, g));
  return p;
}

Eigen::VectorXd ArcLengthSolver::residual(const NodalState& state, double lam, double& scale) {
  // The reference load joins the scale: a traced path crosses lambda = 0 (arc_length.hpp).
  return out_of_balance(assembler_, state, opt_.time, fixed_load_ + lam * q_full_, q_free_.norm(), scale);
}

ArcLengthSolver::Corrector ArcLengthSolver::correct(NodalState& trial, Eigen::VectorXd& du_step,
                                                    double& lam, double arc,
                                                    Constraint constraint, double target) {
  Corrector out;
  const NewtonOutcome newton = newton_iterations(
      {opt_.max_iterations, opt_.residual_tolerance, opt_.increment_tolerance}, assembler_,
      [&](double& scale) { return residual(trial, lam, scale); },
      [&](const Eigen::VectorXd& r) {
        return correction(r, trial, du_step, lam, arc, constraint, target, out.singular);
      });
  out.iterations = newton.iterations;
  out.residual = newton.residual;
  return out;
}

std::optional<double> ArcLengthSolver::correction(const Eigen::VectorXd& r, NodalState& trial,
                                                  Eigen::VectorXd& du_step, double& lam, double arc,
                                                  Constraint constraint, double target, bool& singular) {
  try {
    solver_.factorize(assembler_.matrix(), "tangent stiffness");
  } catch (const SingularMatrix&) {
    singular = true;  // exactly at a limit point: the caller cuts the step
    return std::nullopt;
  }
  const Eigen::VectorXd du_r = solver_.solve(r);
  const Eigen::VectorXd du_t = solver_.solve(q_free_);
  double dlam = 0;
  switch (constraint) {
    case Constraint::arc: {
      // |du_step + du_r + dlam du_t|_s^2 = arc^2 (Crisfield 1981).
      const Eigen::VectorXd a = du_step + du_r;
      const double a1 = dot_s(du_t, du_t), a2 = 2 * dot_s(du_t, a), a3 = dot_s(a, a) - arc * arc;
      const double disc = a2 * a2 - 4 * a1 * a3;
      if (!(disc >= 0) || !(a1 > 0)) return std::nullopt;  // complex roots: the step is cut
      // Roots without cancellation.
      const double qq = -0.5 * (a2 + std::copysign(std::sqrt(disc), a2));
      const double s1 = qq / a1, s2 = qq != 0 ? a3 / qq : -s1;
      // Smallest angle between the old and the new step increment.
      const double c1 = dot_s(du_step, a + s1 * du_t), c2 = dot_s(du_step, a + s2 * du_t);
      dlam = c1 >= c2 ? s1 : s2;
      break;
    }
    case Constraint::fixed_load:
      dlam = target - lam;
      break;
    case Constraint::fixed_displacement: {
      const double now = displacement(trial, opt_.stop_dof);
      const double t = du_t(stop_equation_);
      if (!(std::abs(t) > 0)) return std::nullopt;
      dlam = (target - now - du_r(stop_equation_)) / t;
      break;
    }
  }
  const Eigen::VectorXd du = du_r + dlam * du_t;
  if (!du.allFinite() || !std::isfinite(dlam)) return std::nullopt;
  // The increment in the constraint's own norm |.|_s (weights 1/L_char^2) rather than
  // scaled_increment_norm (division by L_char): the same quantity, rounded differently.
  const double inc = std::sqrt(dot_s(du, du));
  trial.apply_increment(dofs_.scatter_free(du));
  du_step += du;
  lam += dlam;
  return inc;
}

ArcLengthResult ArcLengthSolver::solve(NodalState& state, double lam0) {
  if (!std::isfinite(lam0)) bad_option("starting load factor must be finite");
  ArcLengthResult result;
  double lam = lam0;
  result.path.push_back(point(state, lam));

  // Tangent at the starting state: a singular one here is a model error, not a limit point.
  double scale = 1;
  residual(state, lam, scale);
  solver_.factorize(assembler_.matrix(), "tangent stiffness");
  Eigen::VectorXd du_t = solver_.solve(q_free_);
  double arc = opt_.initial_arc_length > 0
                   ? opt_.initial_arc_length
                   : std::abs(opt_.initial_load_increment) * std::sqrt(dot_s(du_t, du_t));
  if (!(std::isfinite(arc) && arc > 0))
    bad_option("initial arc length is not positive (reference load gives no displacement)");
  const double min_arc = opt_.min_arc_length > 0 ? opt_.min_arc_length : 1e-4 * arc;
  const double max_arc = opt_.max_arc_length > 0 ? opt_.max_arc_length : 10 * arc;
  if (min_arc > max_arc) bad_option("min_arc_length exceeds the maximum arc length");
  arc = std::clamp(arc, min_arc, max_arc);
  const double first_sign = opt_.initial_load_increment < 0 ? -1.0 : 1.0;

  Eigen::VectorXd previous_step;  // Delta u of the last converged step
  bool tangent_current = true;    // du_t belongs to `state`
  for (int step = 0; step < opt_.max_steps; ++step) {
    NodalState trial;
    Eigen::VectorXd du_step;
    double lam_trial = lam;
    Corrector c;
    for (;;) {
      if (!tangent_current) {
        residual(state, lam, scale);
        try {
          solver_.factorize(assembler_.matrix(), "tangent stiffness");
          du_t = solver_.solve(q_free_);
        } catch (const SingularMatrix&) {
          // A converged point exactly on a limit point: predict with the last step instead.
          du_t = previous_step;
        }
        tangent_current = true;
      }
      const double nt = std::sqrt(dot_s(du_t, du_t));
      const double sign = previous_step.size() == 0 ? first_sign
                          : dot_s(du_t, previous_step) >= 0 ? 1.0 : -1.0;
      const double dlam = sign * arc / nt;
      trial = state;
      du_step = dlam * du_t;
      trial.apply_increment(dofs_.scatter_free(du_step));
      lam_trial = lam + dlam;
      c = std::isfinite(dlam) ? correct(trial, du_step, lam_trial, arc, Constraint::arc, 0)
                              : Corrector{};
      if (c.iterations > 0) break;
      result.total_iterations += opt_.max_iterations;
      ++result.cutbacks;
      arc *= 0.5;
      if (arc < min_arc) {
        std::ostringstream os;
        os.precision(4);
        os << "arc-length did not converge after " << step << " steps at load factor " << lam
           << ": arc length cut " << result.cutbacks << " times down to " << 2 * arc
           << " (minimum " << min_arc << "), ";
        if (c.singular)
          os << "singular tangent";
        else
          os << "last relative residual " << c.residual << " (tolerance "
             << opt_.residual_tolerance << ")";
        throw NotConverged(os.str());
      }
    }

    // A stop value crossed within this step: correct the point onto it exactly, starting from the
    // linear interpolation within the step.
    bool stop = false;
    double fraction = -1, stop_value = 0;
    Constraint stop_constraint = Constraint::fixed_load;
    if (opt_.stop_load_factor && crosses(lam, lam_trial, *opt_.stop_load_factor)) {
      stop = true;
      result.stop = ArcLengthStop::load_factor;
      stop_value = *opt_.stop_load_factor;
      fraction = (stop_value - lam) / (lam_trial - lam);
    } else if (opt_.stop_dof >= 0) {
      const double d0 = displacement(state, opt_.stop_dof), d1 = displacement(trial, opt_.stop_dof);
      if (crosses(d0, d1, opt_.stop_displacement)) {
        stop = true;
        result.stop = ArcLengthStop::displacement;
        stop_value = opt_.stop_displacement;
        stop_constraint = Constraint::fixed_displacement;
        fraction = (stop_value - d0) / (d1 - d0);
      }
    }
    if (stop && std::isfinite(fraction)) {
      NodalState fixed = state;
      Eigen::VectorXd du_fixed = fraction * du_step;
      fixed.apply_increment(dofs_.scatter_free(du_fixed));
      double lam_fixed = lam + fraction * (lam_trial - lam);
      const Corrector cf =
          correct(fixed, du_fixed, lam_fixed, 0, stop_constraint, stop_value);
      if (cf.iterations > 0) {
        trial = std::move(fixed);
        du_step = std::move(du_fixed);
        lam_trial = stop_constraint == Constraint::fixed_load ? stop_value : lam_fixed;
        c = cf;
        result.stop_corrected = true;
      }
    }

    state = std::move(trial);
    lam = lam_trial;
    previous_step = std::move(du_step);
    tangent_current = false;
    result.total_iterations += c.iterations;
    ArcLengthPoint p = point(state, lam);
    p.iterations = c.iterations;
    p.arc_length = arc;
    p.residual = c.residual;
    result.path.push_back(std::move(p));
    if (stop) break;
    // Crisfield 1981: Delta l_new = Delta l (I_d / I)^(1/2), I_d the desired iteration count.
    const double grow =
        std::clamp(std::sqrt(static_cast<double>(opt_.target_iterations) / c.iterations), 0.5, 2.0);
    arc = std::clamp(arc * grow, min_arc, max_arc);
  }
  return result;
}

}  // namespace finverse::fem
