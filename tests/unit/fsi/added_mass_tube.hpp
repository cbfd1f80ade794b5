// The added-mass model problem of Causin, Gerbeau & Nobile (2005) as a CoupledStep: a 2-D channel
// (0, L) x (0, R) of inviscid incompressible fluid, rigid bottom, an elastic top wall (generalized
// string: mass m = rho_s h_s per length, tension T, spring k), driven by an inlet pressure pulse
// p_in(t) at x = 0, p = 0 at x = L.
//   structure: m eta_tt = T eta_xx - k eta + p_wall, implicit Euler:
//              (m/dt + dt K) v = (m/dt) v^n - K eta^n + p_wall,  eta = eta^n + dt v,  K = -T D2 + k;
//   flow:      Laplace p = 0, dp/dy = -rho_f eta_tt on the wall, 0 on the bottom; in sine modes
//              lambda_k = k pi / L: p_wall = p_in (1 - x/L) - M_A eta_tt, M_A = S diag(m_k) S 2/(n+1),
//              m_k = rho_f / (lambda_k tanh(lambda_k R)) (the added mass), eta_tt = (v - v^n) / dt.
// The flow takes the wall velocity of the interface vector [eta; v]; the plain partitioned
// iteration has the error operator -(m + dt^2 K)^{-1} M_A, whose spectral radius exceeds one when
// rho_f L / m is large, whatever dt: the added-mass instability. The monolithic step
// (m/dt + dt K + M_A/dt) v = ((m + M_A)/dt) v^n - K eta^n + p_in (1 - x/L) is the reference.
// With moving_height the flow sees the channel height R + mean(X) of the interface vector, so
// H depends on X too (as a real flow depends on the surface position) and is nonlinear.
#pragma once

#include <cmath>

#include <Eigen/Dense>

#include "fsi/implicit_coupling.hpp"

namespace finverse::fsi::test {

struct TubeParameters {
  int n = 40;              // wall nodes (interior)
  double length = 1.0;     // L
  double height = 0.5;     // R
  double rho_f = 1.0;
  double mass = 0.1;       // rho_s h_s
  double tension = 1.0;    // T
  double spring = 1.0;     // k
  double pulse = 1.0;      // p_in amplitude
  double pulse_time = 0.2; // p_in = pulse sin^2(pi t / pulse_time) for t < pulse_time
  bool moving_height = false;
};

class AddedMassTube : public CoupledStep {
 public:
  explicit AddedMassTube(const TubeParameters& p) : p_(p) {
    const int n = p.n;
    const double h = p.length / (n + 1);
    stiffness_ = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n; ++i) {
      stiffness_(i, i) = 2.0 * p.tension / (h * h) + p.spring;
      if (i > 0) stiffness_(i, i - 1) = -p.tension / (h * h);
      if (i + 1 < n) stiffness_(i, i + 1) = -p.tension / (h * h);
    }
    sine_.resize(n, n);
    for (int k = 1; k <= n; ++k)
      for (int j = 1; j <= n; ++j) sine_(j - 1, k - 1) = std::sin(k * M_PI * j / (n + 1.0));
    added_mass_ = added_mass(p.height);
    inlet_shape_.resize(n);
    for (int j = 1; j <= n; ++j) inlet_shape_(j - 1) = 1.0 - j * h / p.length;
    eta_ = v_ = Eigen::VectorXd::Zero(n);
  }

  // M_A for a channel of height r.
  [[nodiscard]] Eigen::MatrixXd added_mass(double r) const {
    Eigen::VectorXd modal_mass(p_.n);
    for (int k = 1; k <= p_.n; ++k) {
      const double lambda = k * M_PI / p_.length;
      modal_mass(k - 1) = p_.rho_f / (lambda * std::tanh(lambda * r));
    }
    return sine_ * modal_mass.asDiagonal() * sine_ * (2.0 / (p_.n + 1.0));
  }
  [[nodiscard]] InterfaceLayout layout() const { return {p_.n, p_.n}; }
  [[nodiscard]] Eigen::VectorXd state() const { return layout().stack(eta_, v_); }
  [[nodiscard]] double inlet(double t) const {
    return t < p_.pulse_time ? p_.pulse * std::pow(std::sin(M_PI * t / p_.pulse_time), 2) : 0.0;
  }
  // Spectral radius of the plain iteration's error operator for this dt.
  [[nodiscard]] double plain_iteration_radius(double dt) const {
    const Eigen::MatrixXd s = p_.mass * Eigen::MatrixXd::Identity(p_.n, p_.n) + dt * dt * stiffness_;
    const Eigen::MatrixXd e = s.ldlt().solve(added_mass_);
    return e.eigenvalues().cwiseAbs().maxCoeff();
  }

  void begin_step(const StepInfo& info) override {
    dt_ = info.dt;
    t_end_ = info.time + info.dt;
    const Eigen::MatrixXd lhs =
        (p_.mass / dt_) * Eigen::MatrixXd::Identity(p_.n, p_.n) + dt_ * stiffness_;
    structure_ = lhs.ldlt();
  }
  void save() override {
    saved_eta_ = eta_;
    saved_v_ = v_;
  }
  void restore() override {
    eta_ = saved_eta_;
    v_ = saved_v_;
  }
  Eigen::VectorXd evaluate(const Eigen::VectorXd& x) override {
    // Flow with the wall velocity of x -> wall pressure.
    const Eigen::VectorXd v_in = x.tail(p_.n);
    const Eigen::MatrixXd m_a = p_.moving_height ? added_mass(p_.height + x.head(p_.n).mean())
                                                 : added_mass_;
    const Eigen::VectorXd p_wall = inlet(t_end_) * inlet_shape_ - m_a * ((v_in - v_) / dt_);
    // Structure over the step under that pressure.
    const Eigen::VectorXd rhs = (p_.mass / dt_) * v_ - stiffness_ * eta_ + p_wall;
    const Eigen::VectorXd v_new = structure_.solve(rhs);
    eta_ = eta_ + dt_ * v_new;
    v_ = v_new;
    return layout().stack(eta_, v_);
  }

  // The monolithic step from (eta, v) to t_end: the reference the coupling must reproduce.
  void monolithic_step(Eigen::VectorXd& eta, Eigen::VectorXd& v, double t_end, double dt) const {
    const Eigen::MatrixXd id = Eigen::MatrixXd::Identity(p_.n, p_.n);
    const Eigen::MatrixXd lhs = (p_.mass / dt) * id + dt * stiffness_ + added_mass_ / dt;
    const Eigen::VectorXd rhs = ((p_.mass / dt) * id + added_mass_ / dt) * v - stiffness_ * eta +
                                inlet(t_end) * inlet_shape_;
    v = lhs.ldlt().solve(rhs);
    eta = eta + dt * v;
  }

 private:
  TubeParameters p_;
  Eigen::MatrixXd stiffness_, added_mass_, sine_;
  Eigen::VectorXd inlet_shape_;
  Eigen::LDLT<Eigen::MatrixXd> structure_;
  Eigen::VectorXd eta_, v_, saved_eta_, saved_v_;
  double dt_ = 0.0, t_end_ = 0.0;
};

}  // namespace finverse::fsi::test
