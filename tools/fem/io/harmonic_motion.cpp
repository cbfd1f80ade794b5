// A tracked motion through its first harmonics of the beat (see harmonic_motion.hpp).
#include "fem/io/harmonic_motion.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include <Eigen/QR>

#include "fem/errors.hpp"

namespace finverse::fem::io {

stage::Motion harmonic_motion(const stage::Motion& motion, double frequency, int harmonics, const std::string& source) {
  const std::size_t nt = motion.time.data.size();
  if (!(std::isfinite(frequency) && frequency > 0) || harmonics < 1)
    throw InvalidInput(source + ": a harmonic drive needs a beat frequency > 0 and at least one harmonic");
  if (nt < static_cast<std::size_t>(2 * harmonics + 1) || motion.points.dim(0) != nt)
    throw InvalidInput(source + ": " + std::to_string(nt) + " frames cannot carry " + std::to_string(harmonics) +
                       " harmonics (2 H + 1 frames at least)");
  const Eigen::Index cols = 2 * harmonics + 1;
  Eigen::MatrixXd basis(static_cast<Eigen::Index>(nt), cols);
  for (std::size_t k = 0; k < nt; ++k) {
    const double wt = 2 * std::numbers::pi * frequency * motion.time.data[k];
    basis(static_cast<Eigen::Index>(k), 0) = 1;
    for (int h = 1; h <= harmonics; ++h) {
      basis(static_cast<Eigen::Index>(k), 2 * h - 1) = std::sin(h * wt);
      basis(static_cast<Eigen::Index>(k), 2 * h) = std::cos(h * wt);
    }
  }
  const std::size_t values = motion.points.data.size() / nt;  // nodes x 3, frame-major
  Eigen::MatrixXd x(static_cast<Eigen::Index>(nt), static_cast<Eigen::Index>(values));
  for (std::size_t k = 0; k < nt; ++k)
    for (std::size_t j = 0; j < values; ++j)
      x(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(j)) = motion.points.data[k * values + j];
  const Eigen::MatrixXd fit = basis * basis.colPivHouseholderQr().solve(x);
  stage::Motion out = motion;
  out.velocity = {};
  for (std::size_t k = 0; k < nt; ++k)
    for (std::size_t j = 0; j < values; ++j)
      out.points.data[k * values + j] = fit(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(j));
  return out;
}

}  // namespace finverse::fem::io
