// Aitken dynamic under-relaxation, the seed paper's rule and Irons-Tuck (aitken.hpp).
#include "fsi/aitken.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace finverse::fsi {

AitkenRelaxation::AitkenRelaxation(InterfaceLayout layout, AitkenOptions options)
    : layout_(layout), options_(options), omega_(options.initial_omega) {
  layout_.validate();
  if (!(options_.omega_min > 0.0 && options_.omega_min <= options_.omega_max)) {
    throw Error("fsi Aitken: expected 0 < omega_min <= omega_max, got " +
                std::to_string(options_.omega_min) + " and " + std::to_string(options_.omega_max));
  }
  if (!(std::abs(options_.initial_omega) >= options_.omega_min &&
        std::abs(options_.initial_omega) <= options_.omega_max)) {
    throw Error("fsi Aitken: expected omega_min <= |initial omega| <= omega_max, got " +
                std::to_string(options_.initial_omega));
  }
  // The literal rule needs two increments of the relaxed inputs (three inputs); Mok's form one.
  const int least = options_.rule == AitkenRule::SeedPaperLiteral ? 2 : 1;
  if (options_.fixed_iterations < least) {
    throw Error("fsi Aitken: expected at least " + std::to_string(least) +
                " fixed iterations with omega0, got " + std::to_string(options_.fixed_iterations));
  }
}

std::string AitkenRelaxation::name() const {
  switch (options_.rule) {
    case AitkenRule::SeedPaper: return "aitken-seed";
    case AitkenRule::SeedPaperLiteral: return "aitken-seed-literal";
    case AitkenRule::IronsTuck: break;
  }
  return "aitken-irons-tuck";
}

void AitkenRelaxation::reset_time_step() {
  iteration_ = 0;
  previous_in_.resize(0);
  previous_dd_.resize(0);
  previous_residual_.resize(0);
}

double AitkenRelaxation::bounded(double omega) const {
  const double sign = omega < 0.0 ? -1.0 : 1.0;
  return sign * std::clamp(std::abs(omega), options_.omega_min, options_.omega_max);
}

double AitkenRelaxation::mok_omega(const Eigen::VectorXd& dd_now) {
  // The paper's gamma recursion, gamma_{m-1} = 1 - omega_{m-1}; omega0 while m <= fixed.
  double omega = options_.initial_omega;
  if (iteration_ > options_.fixed_iterations) {
    const Eigen::VectorXd diff = previous_dd_ - dd_now;
    const double denom = diff.squaredNorm();
    omega = omega_;
    if (denom > 0.0 && std::isfinite(denom)) {
      const double gamma_prev = 1.0 - omega_;
      const double gamma = gamma_prev + (gamma_prev - 1.0) * diff.dot(dd_now) / denom;
      omega = bounded(1.0 - gamma);
    }
  }
  previous_dd_ = dd_now;
  return omega;
}

double AitkenRelaxation::irons_tuck_omega(const Eigen::VectorXd& residual) {
  double omega = options_.reuse_last_omega ? omega_ : options_.initial_omega;
  if (iteration_ > 1) {
    const Eigen::Index n = options_.displacement_only ? layout_.n_position : layout_.size();
    const Eigen::VectorXd dr = residual.head(n) - previous_residual_.head(n);
    const double denom = dr.squaredNorm();
    omega = omega_;
    if (denom > 0.0 && std::isfinite(denom)) {
      omega = bounded(-omega_ * previous_residual_.head(n).dot(dr) / denom);
    }
  } else if (options_.reuse_last_omega) {
    omega = bounded(omega);
  }
  previous_residual_ = residual;
  return omega;
}

Eigen::VectorXd AitkenRelaxation::accelerate(const Eigen::VectorXd& x_in,
                                             const Eigen::VectorXd& x_out) {
  layout_.check(x_in, "Aitken input");
  layout_.check(x_out, "Aitken output");
  ++iteration_;
  const Eigen::VectorXd residual = x_out - x_in;
  const Eigen::Index n = options_.displacement_only ? layout_.n_position : layout_.size();
  switch (options_.rule) {
    case AitkenRule::SeedPaper:  // DdX^m = X^{N,m} - X~^{N,m} = -r_m
      omega_ = mok_omega(-residual.head(n));
      break;
    case AitkenRule::SeedPaperLiteral: {  // DdX^m = X^{N,m-1} - X^{N,m}; none at m = 1
      const bool first = previous_in_.size() == 0;
      const Eigen::VectorXd dd = first ? Eigen::VectorXd(Eigen::VectorXd::Zero(n))
                                       : Eigen::VectorXd(previous_in_.head(n) - x_in.head(n));
      omega_ = mok_omega(dd);
      previous_in_ = x_in;
      break;
    }
    case AitkenRule::IronsTuck:
      omega_ = irons_tuck_omega(residual);
      break;
  }
  return x_in + omega_ * residual;
}

void AitkenRelaxation::restore_carried_state(const CarriedState& state) {
  const auto it = state.find("aitken_omega");
  if (it == state.end() || it->second.size() != 1)
    throw Error("fsi Aitken: carried state does not fit: expected one value aitken_omega");
  omega_ = it->second[0];
}

}  // namespace finverse::fsi
