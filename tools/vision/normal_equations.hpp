// Gauss-Newton normal equations J^T W J and J^T W r accumulated one sparse residual row at a
// time (seed paper section 2.1 step 1: the skeleton is fitted by least squares). Rows come from
// the silhouettes of every view and from the priors; each view fills its own instance in
// parallel and the instances are summed, so the result does not depend on the thread count.
#pragma once

#include <vector>

#include <Eigen/Dense>

namespace finverse::vision {

class NormalEquations {
 public:
  explicit NormalEquations(std::size_t n) : A_(Eigen::MatrixXd::Zero(n, n)), g_(Eigen::VectorXd::Zero(n)), row_(n, 0.0), mark_(n, 0) {}

  // Row under construction: add d(residual)/d(p[col]) contributions, then commit with the value.
  void add(int col, double value) {
    if (!mark_[col]) mark_[col] = 1, touched_.push_back(col);
    row_[col] += value;
  }
  void commit(double residual, double weight) {
    cost_ += weight * residual * residual;
    ++rows_;
    // Column by column (A is column-major): each column's updates stay within one column.
    for (std::size_t b = 0; b < touched_.size(); ++b) {
      const int j = touched_[b];
      const double wj = weight * row_[j];
      g_[j] += wj * residual;
      double* col = A_.data() + static_cast<std::ptrdiff_t>(j) * A_.rows();
      for (std::size_t a = 0; a < touched_.size(); ++a) col[touched_[a]] += wj * row_[touched_[a]];
    }
    for (int i : touched_) row_[i] = 0.0, mark_[i] = 0;
    touched_.clear();
  }
  // A residual without a Jacobian (cost evaluation only).
  void cost_only(double residual, double weight) {
    cost_ += weight * residual * residual;
    ++rows_;
  }
  NormalEquations& operator+=(const NormalEquations& o) {
    A_ += o.A_;
    g_ += o.g_;
    cost_ += o.cost_;
    rows_ += o.rows_;
    return *this;
  }
  const Eigen::MatrixXd& A() const { return A_; }
  const Eigen::VectorXd& g() const { return g_; }
  double cost() const { return cost_; }
  std::size_t rows() const { return rows_; }

 private:
  Eigen::MatrixXd A_;
  Eigen::VectorXd g_;
  std::vector<double> row_;
  std::vector<char> mark_;
  std::vector<int> touched_;
  double cost_ = 0;
  std::size_t rows_ = 0;
};

}  // namespace finverse::vision
