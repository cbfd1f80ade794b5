// Least-squares harmonics of the beat frequency (harmonic_analysis.hpp).
#include "loop/harmonic_analysis.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include <Eigen/QR>
#include <Eigen/SVD>

#include "loop/errors.hpp"

namespace finverse::loop {

Harmonics fit_harmonics(const std::vector<double>& times, const Eigen::MatrixXd& rows, double period, int order) {
  const int nf = static_cast<int>(times.size());
  if (!(period > 0) || !std::isfinite(period))
    throw InvalidInput("harmonics: expected a positive period (motion.h5 T or --period), got " +
                       std::to_string(period));
  if (order < 0) throw InvalidInput("harmonics: expected order >= 0");
  if (nf < 2 * order + 1 || rows.cols() != nf)
    throw InvalidInput("harmonics: " + std::to_string(nf) + " frames cannot determine " + std::to_string(order) +
                       " harmonics (need at least " + std::to_string(2 * order + 1) + ")");
  const double w = 2 * std::numbers::pi / period;
  Eigen::MatrixXd a(nf, 2 * order + 1);
  for (int j = 0; j < nf; ++j) {
    a(j, 0) = 1;
    for (int k = 1; k <= order; ++k) {
      a(j, 2 * k - 1) = std::cos(k * w * times[j]);
      a(j, 2 * k) = std::sin(k * w * times[j]);
    }
  }
  Harmonics h;
  h.period = period;
  h.order = order;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a);
  const auto& s = svd.singularValues();
  h.condition = s(s.size() - 1) > 0 ? s(0) / s(s.size() - 1) : INFINITY;
  h.whole_period = nf > 1 && (times.back() - times.front()) * (1 + 1e-9) >= period * (nf - 1.0) / nf;
  const Eigen::MatrixXd x = a.colPivHouseholderQr().solve(rows.transpose());  // [2K+1, rows]
  h.mean = x.row(0).transpose();
  for (int k = 1; k <= order; ++k) {
    Eigen::VectorXcd c(rows.rows());
    for (Eigen::Index r = 0; r < rows.rows(); ++r) c(r) = {x(2 * k - 1, r), -x(2 * k, r)};
    h.coefficient.push_back(c);
  }
  return h;
}

Eigen::VectorXd node_amplitude(const Harmonics& h, int k) {
  const auto& c = h.coefficient.at(k - 1);
  Eigen::VectorXd amp(c.size() / 3);
  for (Eigen::Index i = 0; i < amp.size(); ++i) amp(i) = c.segment<3>(3 * i).norm();
  return amp;
}

Eigen::VectorXd node_phase(const Harmonics& h, int k) {
  const auto& c = h.coefficient.at(k - 1);
  Eigen::VectorXd phase(c.size() / 3);
  for (Eigen::Index i = 0; i < phase.size(); ++i) {
    Eigen::Index axis = 0;
    c.segment<3>(3 * i).cwiseAbs().maxCoeff(&axis);
    phase(i) = std::arg(c(3 * i + axis));
  }
  return phase;
}

}  // namespace finverse::loop
