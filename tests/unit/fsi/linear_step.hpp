// Test participants for the coupling loop: the linear fixed point x = A x + b as a CoupledStep,
// with a matrix of chosen spectrum, and a log of the calls the loop makes (save, restore, evaluate).
#pragma once

#include <random>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "fsi/implicit_coupling.hpp"

namespace finverse::fsi::test {

// A = Q diag(lambda) Q^T, lambda evenly spaced in [lo, hi], Q a seeded random orthogonal matrix.
inline Eigen::MatrixXd symmetric_with_spectrum(int n, double lo, double hi, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd g(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) g(i, j) = normal(rng);
  const Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(g).householderQ();
  Eigen::VectorXd lambda = Eigen::VectorXd::LinSpaced(n, lo, hi);
  return q * lambda.asDiagonal() * q.transpose();
}

inline Eigen::VectorXd random_vector(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v(i) = normal(rng);
  return v;
}

// H(x) = A x + b; b may change between steps (set it in begin_step through the callback).
class LinearStep : public CoupledStep {
 public:
  LinearStep(Eigen::MatrixXd a, Eigen::VectorXd b) : a_(std::move(a)), b_(std::move(b)) {}

  void begin_step(const StepInfo& info) override {
    log.push_back("begin");
    info_ = info;
  }
  void save() override {
    log.push_back("save");
    ++saves;
    restored_since_evaluate = false;
  }
  void restore() override {
    log.push_back("restore");
    ++restores;
    restored_since_evaluate = true;
  }
  Eigen::VectorXd evaluate(const Eigen::VectorXd& x) override {
    log.push_back("evaluate");
    ++evaluations;
    if (!restored_since_evaluate) ++evaluations_without_restore;
    restored_since_evaluate = false;
    inputs.push_back(x);
    return a_ * x + b_;
  }
  void accept(const Eigen::VectorXd&, const Eigen::VectorXd&) override {
    log.push_back("accept");
    ++accepts;
  }

  void set_b(Eigen::VectorXd b) { b_ = std::move(b); }
  [[nodiscard]] Eigen::VectorXd solution() const {
    const Eigen::MatrixXd i_minus_a = Eigen::MatrixXd::Identity(a_.rows(), a_.cols()) - a_;
    return i_minus_a.partialPivLu().solve(b_);
  }
  [[nodiscard]] const StepInfo& info() const { return info_; }

  std::vector<std::string> log;
  std::vector<Eigen::VectorXd> inputs;
  int saves = 0, restores = 0, evaluations = 0, accepts = 0, evaluations_without_restore = 0;
  bool restored_since_evaluate = false;

 private:
  Eigen::MatrixXd a_;
  Eigen::VectorXd b_;
  StepInfo info_;
};

}  // namespace finverse::fsi::test
