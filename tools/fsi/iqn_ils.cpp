// IQN-ILS with reuse of past time steps and the QR1 filter (iqn_ils.hpp).
#include "fsi/iqn_ils.hpp"

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "core/error.hpp"

namespace finverse::fsi {

IqnIls::IqnIls(InterfaceLayout layout, IqnIlsOptions options) : layout_(layout), options_(options) {
  layout_.validate();
  if (!(options_.initial_omega > 0.0 && options_.initial_omega <= 1.0)) {
    throw Error("fsi IQN-ILS: expected 0 < initial omega <= 1, got " +
                std::to_string(options_.initial_omega));
  }
  if (options_.reused_time_steps < 0 || options_.max_columns < 1) {
    throw Error("fsi IQN-ILS: expected reused time steps >= 0 and max columns >= 1, got " +
                std::to_string(options_.reused_time_steps) + " and " +
                std::to_string(options_.max_columns));
  }
  if (!(options_.filter_epsilon >= 0.0 && options_.filter_epsilon < 1.0)) {
    throw Error("fsi IQN-ILS: expected 0 <= filter epsilon < 1, got " +
                std::to_string(options_.filter_epsilon));
  }
}

void IqnIls::reset_time_step() {
  // Columns of a step that never converged (no end_time_step) are not trusted for reuse.
  while (!columns_.empty() && columns_.front().step == step_ && has_previous_) columns_.pop_front();
  ++step_;
  has_previous_ = false;
  row_scale_.resize(0);
}

void IqnIls::set_scaling(const Eigen::VectorXd& x_out) {
  row_scale_ = Eigen::VectorXd::Ones(layout_.size());
  if (!options_.block_scaling) return;
  const double nx = layout_.position(x_out).norm();
  const double nv = layout_.n_velocity > 0 ? layout_.velocity(x_out).norm() : 0.0;
  // A block at rest borrows the other's scale; both at rest: no scaling.
  const double sx = nx > 0.0 ? 1.0 / nx : (nv > 0.0 ? 1.0 / nv : 1.0);
  const double sv = nv > 0.0 ? 1.0 / nv : sx;
  row_scale_.head(layout_.n_position).setConstant(sx);
  if (layout_.n_velocity > 0) row_scale_.tail(layout_.n_velocity).setConstant(sv);
}

void IqnIls::add_column(const Eigen::VectorXd& residual, const Eigen::VectorXd& x_out) {
  if (has_previous_) {
    columns_.push_front({residual - previous_residual_, x_out - previous_out_, step_});
    while (static_cast<int>(columns_.size()) > options_.max_columns) columns_.pop_back();
  }
  previous_residual_ = residual;
  previous_out_ = x_out;
  has_previous_ = true;
}

Eigen::VectorXd IqnIls::quasi_newton_update(const Eigen::VectorXd& residual,
                                            const Eigen::VectorXd& x_out) {
  // QR of D V by Gram-Schmidt, newest column first, twice per column ("twice is enough"); the
  // QR1 filter drops a column whose orthogonal part is small against its own norm.
  const Eigen::Index n = layout_.size();
  const auto c_max = static_cast<Eigen::Index>(columns_.size());
  Eigen::MatrixXd q(n, c_max);
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(c_max, c_max);
  std::vector<std::size_t> kept;
  Eigen::Index c = 0;
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    Eigen::VectorXd v = row_scale_.cwiseProduct(columns_[i].v);
    const double v_norm = v.norm();
    Eigen::VectorXd coeff = Eigen::VectorXd::Zero(c);
    for (int pass = 0; pass < 2; ++pass) {
      for (Eigen::Index j = 0; j < c; ++j) {
        const double h = q.col(j).dot(v);
        v -= h * q.col(j);
        coeff(j) += h;
      }
    }
    const double rho = v.norm();
    if (!(rho > options_.filter_epsilon * v_norm) || rho == 0.0) continue;  // filtered out
    q.col(c) = v / rho;
    r.col(c).head(c) = coeff;
    r(c, c) = rho;
    kept.push_back(i);
    ++c;
  }
  if (kept.size() != columns_.size()) {
    filtered_ += static_cast<int>(columns_.size() - kept.size());
    std::deque<Column> remaining;
    for (std::size_t i : kept) remaining.push_back(std::move(columns_[i]));
    columns_ = std::move(remaining);
  }
  if (c == 0) {  // every column filtered out: relax
    last_omega_ = options_.initial_omega;
    return x_out - (1.0 - options_.initial_omega) * residual;
  }
  const Eigen::VectorXd rhs = -(q.leftCols(c).transpose() * row_scale_.cwiseProduct(residual));
  const Eigen::VectorXd alpha =
      r.topLeftCorner(c, c).triangularView<Eigen::Upper>().solve(rhs);
  Eigen::VectorXd x_next = x_out;
  for (Eigen::Index j = 0; j < c; ++j) x_next += alpha(j) * columns_[static_cast<std::size_t>(j)].w;
  last_omega_ = 1.0;
  return x_next;
}

Eigen::VectorXd IqnIls::accelerate(const Eigen::VectorXd& x_in, const Eigen::VectorXd& x_out) {
  layout_.check(x_in, "IQN-ILS input");
  layout_.check(x_out, "IQN-ILS output");
  if (step_ == 0) reset_time_step();  // used without the loop's reset: this is step 1
  if (row_scale_.size() == 0) set_scaling(x_out);
  const Eigen::VectorXd residual = x_out - x_in;
  add_column(residual, x_out);
  if (columns_.empty()) {
    last_omega_ = options_.initial_omega;
    return x_in + options_.initial_omega * residual;
  }
  return quasi_newton_update(residual, x_out);
}

void IqnIls::end_time_step(const Eigen::VectorXd& x_in, const Eigen::VectorXd& x_out) {
  layout_.check(x_in, "IQN-ILS converged input");
  layout_.check(x_out, "IQN-ILS converged output");
  // The converged iteration's difference is information too (preCICE keeps it).
  add_column(x_out - x_in, x_out);
  has_previous_ = false;
  // Reuse: the columns of the last q steps (this one included) survive into the next step.
  while (!columns_.empty() && columns_.back().step <= step_ - options_.reused_time_steps) {
    columns_.pop_back();
  }
}

Acceleration::CarriedState IqnIls::carried_state() const {
  CarriedState s;
  std::vector<double>&v = s["iqn_ils_v"], &w = s["iqn_ils_w"], &step = s["iqn_ils_column_step"];
  for (const Column& c : columns_) {
    v.insert(v.end(), c.v.data(), c.v.data() + c.v.size());
    w.insert(w.end(), c.w.data(), c.w.data() + c.w.size());
    step.push_back(static_cast<double>(c.step));
  }
  s["iqn_ils_counters"] = {static_cast<double>(step_), static_cast<double>(filtered_), last_omega_};
  return s;
}

void IqnIls::restore_carried_state(const CarriedState& s) {
  const auto get = [&](const char* key) -> const std::vector<double>& {
    static const std::vector<double> empty;
    const auto it = s.find(key);
    return it == s.end() ? empty : it->second;
  };
  const std::vector<double>&v = get("iqn_ils_v"), &w = get("iqn_ils_w"), &step = get("iqn_ils_column_step");
  const std::vector<double>& counters = get("iqn_ils_counters");
  const auto n = static_cast<std::size_t>(layout_.size());
  if (counters.size() != 3 || v.size() != step.size() * n || w.size() != v.size())
    throw Error("fsi IQN-ILS: carried state does not fit: expected 3 counters and " + std::to_string(n) +
                " values per column, got " + std::to_string(counters.size()) + " counters, " +
                std::to_string(v.size()) + " and " + std::to_string(w.size()) + " values for " +
                std::to_string(step.size()) + " columns");
  columns_.clear();
  for (std::size_t c = 0; c < step.size(); ++c) {
    const auto off = static_cast<std::ptrdiff_t>(c * n);
    columns_.push_back({Eigen::Map<const Eigen::VectorXd>(v.data() + off, layout_.size()),
                        Eigen::Map<const Eigen::VectorXd>(w.data() + off, layout_.size()),
                        static_cast<long>(step[c])});
  }
  step_ = static_cast<long>(counters[0]);
  filtered_ = static_cast<int>(counters[1]);
  last_omega_ = counters[2];
  has_previous_ = false;
  row_scale_.resize(0);
}

}  // namespace finverse::fsi
