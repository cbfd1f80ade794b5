// A periodic motion's first harmonics; see periodic_low_pass.hpp.
#include "cfd/immersed/periodic_low_pass.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace finverse::cfd {

std::vector<double> periodic_low_pass(const std::vector<double>& time, const std::vector<double>& values,
                                      std::size_t channels, double period, int harmonics, const std::string& what) {
  const auto n = static_cast<Eigen::Index>(time.size());
  if (n < 3 || values.size() != time.size() * channels)
    throw Error(what + ": a low-pass needs at least 3 frames of " + std::to_string(channels) + " values");
  if (!(period > 0)) throw Error(what + ": a low-pass needs the motion's period T");
  const Eigen::Index basis = 2 * harmonics + 1;
  // Twice the unknowns keeps the fit from interpolating the noise.
  if (harmonics < 1 || 2 * basis > n)
    throw Error(what + ": " + std::to_string(harmonics) + " harmonics need at least " + std::to_string(2 * basis) +
                " frames (there are " + std::to_string(n) + ")");
  const double w = 2 * std::numbers::pi / period;
  Eigen::MatrixXd B(n, basis);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double t = time[static_cast<std::size_t>(k)] - time[0];
    B(k, 0) = 1;
    for (int j = 1; j <= harmonics; ++j) {
      B(k, 2 * j - 1) = std::cos(j * w * t);
      B(k, 2 * j) = std::sin(j * w * t);
    }
  }
  const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> Y(
      values.data(), n, static_cast<Eigen::Index>(channels));
  // Least squares by a QR of the basis: the frames need not tile the period exactly (a camera's
  // frame rate rarely divides the beat).
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(B);
  if (qr.rank() < basis)
    throw Error(what + ": the frames do not determine " + std::to_string(harmonics) + " harmonics");
  const Eigen::MatrixXd fit = B * qr.solve(Eigen::MatrixXd(Y));
  std::vector<double> out(values.size());
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      out.data(), n, static_cast<Eigen::Index>(channels)) = fit;
  return out;
}

std::vector<double> periodic_low_pass(const stage::Motion& motion, const PeriodicLayout& layout, int harmonics,
                                      const std::string& what) {
  if (!layout.wrap || !motion.period)
    throw Error(what + ": --motion-harmonics needs a periodic motion (" +
                (layout.note.empty() ? std::string("no attribute T") : layout.note) + ")");
  const std::size_t channels = 3 * motion.points.dim(1);
  const auto frames = static_cast<std::ptrdiff_t>(layout.frames);
  const std::vector<double> time(motion.time.data.begin(), motion.time.data.begin() + frames);
  const std::vector<double> values(motion.points.data.begin(),
                                   motion.points.data.begin() + frames * static_cast<std::ptrdiff_t>(channels));
  return periodic_low_pass(time, values, channels, *motion.period, harmonics, what);
}

}  // namespace finverse::cfd
