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

}  // namespace

ResidualCorrelation estimate_residual_correlation(const Eigen::VectorXd& r, const ResidualLayout& layout,
                                                  double systematic_correlation) {
  check(r.size(), layout);
  ResidualCorrelation out;
  const Eigen::Index n = layout.points.cols();
  out.spacing = median_nearest_distance(layout.points);
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
  // Effective residuals: (tr R)^2 / tr(R^2) with R block-diagonal over samples and components.
  double trace_r2 = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j) {
      const double v = std::exp(-(layout.points.col(i) - layout.points.col(j)).norm() / out.length);
      trace_r2 += v * v;
    }
  const double blocks3 = 3.0 * layout.blocks;
  out.effective_residuals = blocks3 * static_cast<double>(n) * static_cast<double>(n) / trace_r2;
  return out;
}

Eigen::MatrixXd correlated_gram(const Eigen::MatrixXd& jacobian, const ResidualLayout& layout, double length) {
  check(jacobian.rows(), layout);
  const Eigen::Index n = layout.points.cols(), p = jacobian.cols();
  if (!(length > 0)) return jacobian.transpose() * jacobian;
  Eigen::MatrixXd R(n, n);
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < n; ++j)
      R(i, j) = std::exp(-(layout.points.col(i) - layout.points.col(j)).norm() / length);
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(p, p);
  Eigen::MatrixXd Jc(n, p);
  for (int b = 0; b < layout.blocks; ++b)
    for (int c = 0; c < 3; ++c) {
      for (Eigen::Index i = 0; i < n; ++i) Jc.row(i) = jacobian.row(row(layout, b, i, c));
      gram.noalias() += Jc.transpose() * (R * Jc);
    }
  return gram;
}

}  // namespace finverse::fit
