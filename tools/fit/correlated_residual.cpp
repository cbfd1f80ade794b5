// The residual's spatial correlation and the sandwich gram (see correlated_residual.hpp).
#include "fit/correlated_residual.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "fit/errors.hpp"

namespace finverse::fit {

namespace {

void check(Eigen::Index rows, const ResidualLayout& layout) {
  if (layout.blocks < 1 || rows != 3 * static_cast<Eigen::Index>(layout.blocks) * layout.points.cols())
    throw InvalidInput("residual layout: " + std::to_string(rows) + " residuals, expected 3 x " +
                       std::to_string(layout.blocks) + " samples x " + std::to_string(layout.points.cols()) + " nodes");
}

// Row of component c of node i in sample b.
inline Eigen::Index row(const ResidualLayout& l, int b, Eigen::Index i, int c) {
  return 3 * (static_cast<Eigen::Index>(b) * l.points.cols() + i) + c;
}

double median_nearest_distance(const Eigen::Matrix3Xd& p) {
  const Eigen::Index n = p.cols();
  std::vector<double> nearest(static_cast<size_t>(n), std::numeric_limits<double>::infinity());
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j)
      if (i != j) nearest[i] = std::min(nearest[i], (p.col(i) - p.col(j)).norm());
  if (n < 2) return 0;
  std::nth_element(nearest.begin(), nearest.begin() + n / 2, nearest.end());
  return nearest[n / 2];
}

// K: the residual's channels (sample x component) against each other at the same node.
Eigen::MatrixXd channel_covariance(const Eigen::VectorXd& r, const ResidualLayout& layout) {
  const Eigen::Index n = layout.points.cols(), k = 3 * static_cast<Eigen::Index>(layout.blocks);
  Eigen::MatrixXd x(k, n);
  for (int b = 0; b < layout.blocks; ++b)
    for (Eigen::Index i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) x(3 * b + c, i) = r(row(layout, b, i, c));
  return x * x.transpose() / static_cast<double>(n);
}

}  // namespace

ResidualCorrelation estimate_residual_correlation(const Eigen::VectorXd& r, const ResidualLayout& layout,
                                                  double systematic_correlation) {
  check(r.size(), layout);
  ResidualCorrelation out;
  const Eigen::Index n = layout.points.cols();
  out.spacing = median_nearest_distance(layout.points);
  out.channels = channel_covariance(r, layout);
  const double trace_k = out.channels.trace(), trace_k2 = out.channels.squaredNorm();
  out.effective_channels = trace_k2 > 0 ? trace_k * trace_k / trace_k2 : 3.0 * layout.blocks;
  const double s2 = r.squaredNorm() / static_cast<double>(r.size());
  out.effective_residuals = static_cast<double>(r.size());
  if (!(out.spacing > 0) || !(s2 > 0)) return out;
  // Empirical correlation in distance bins one spacing wide, centred on k spacings (k >= 1).
  constexpr int kBins = 24;
  std::vector<double> sum(kBins + 1, 0.0), count(kBins + 1, 0.0);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = i + 1; j < n; ++j) {
      const int k = static_cast<int>(std::lround((layout.points.col(i) - layout.points.col(j)).norm() / out.spacing));
      if (k < 1 || k > kBins) continue;
      for (int b = 0; b < layout.blocks; ++b)
        for (int c = 0; c < 3; ++c) sum[k] += r(row(layout, b, i, c)) * r(row(layout, b, j, c));
      count[k] += 3.0 * layout.blocks;
    }
  const auto rho = [&](int k) { return count[k] > 0 ? sum[k] / (count[k] * s2) : 0.0; };
  out.neighbour = rho(1);
  out.systematic = out.neighbour >= systematic_correlation;
  // l: where the correlation falls to 1/e (interpolated between bins); from the first bin alone
  // when it is already below; white below 0.05 at the nearest neighbours.
  const double e1 = std::exp(-1.0);
  if (out.neighbour < 0.05) return out;
  if (out.neighbour <= e1) {
    out.length = -out.spacing / std::log(out.neighbour);
  } else {
    out.length = kBins * out.spacing;  // correlated beyond the binned range
    for (int k = 2; k <= kBins; ++k)
      if (count[k] > 0 && rho(k) <= e1) {
        const double a = rho(k - 1), b = rho(k);
        out.length = out.spacing * ((k - 1) + (a - e1) / std::max(a - b, 1e-300));
        break;
      }
  }
  // Effective residuals of K (x) R: (tr K)^2 (tr R)^2 / (tr K^2 tr R^2).
  double trace_r2 = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) {
      const double v = std::exp(-(layout.points.col(i) - layout.points.col(j)).norm() / out.length);
      trace_r2 += v * v;
    }
  out.effective_residuals = out.effective_channels * static_cast<double>(n) * static_cast<double>(n) / trace_r2;
  return out;
}

Eigen::MatrixXd correlated_gram(const Eigen::MatrixXd& jacobian, const ResidualLayout& layout,
                                const ResidualCorrelation& correlation) {
  check(jacobian.rows(), layout);
  const Eigen::Index n = layout.points.cols(), p = jacobian.cols(), k = 3 * static_cast<Eigen::Index>(layout.blocks);
  if (correlation.channels.rows() != k || correlation.channels.cols() != k)
    throw InvalidInput("residual correlation: channel covariance is " + std::to_string(correlation.channels.rows()) +
                       " x " + std::to_string(correlation.channels.cols()) + ", expected " + std::to_string(k) + " x " +
                       std::to_string(k));
  // J_a: the rows of channel a (n x p); gram = sum_ab K_ab J_a^T R J_b.
  std::vector<Eigen::MatrixXd> ja(static_cast<size_t>(k), Eigen::MatrixXd(n, p));
  for (int b = 0; b < layout.blocks; ++b)
    for (Eigen::Index i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) ja[3 * b + c].row(i) = jacobian.row(row(layout, b, i, c));
  Eigen::MatrixXd R = Eigen::MatrixXd::Identity(n, n);
  if (correlation.length > 0)
    for (Eigen::Index i = 0; i < n; ++i)
      for (Eigen::Index j = 0; j < n; ++j)
        R(i, j) = std::exp(-(layout.points.col(i) - layout.points.col(j)).norm() / correlation.length);
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(p, p), mixed(n, p);
  for (Eigen::Index b = 0; b < k; ++b) {
    mixed.setZero();
    for (Eigen::Index a = 0; a < k; ++a)
      if (correlation.channels(a, b) != 0) mixed.noalias() += correlation.channels(a, b) * ja[a];
    gram.noalias() += mixed.transpose() * (R * ja[b]);
  }
  return gram;
}

double span_share_correction(const Eigen::MatrixXd& q, const ResidualLayout& layout,
                             const ResidualCorrelation& correlation) {
  const double total = correlation.channels.trace() * static_cast<double>(layout.points.cols());
  const double in_span = correlated_gram(q, layout, correlation).trace();
  return total > in_span ? total / (total - in_span) : 1.0;
}

}  // namespace finverse::fit
