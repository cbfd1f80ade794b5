// Spectral peak picking (see spectral_peaks.hpp).
#include "fem/spectral_peaks.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include <unsupported/Eigen/FFT>

#include "fem/errors.hpp"

namespace finverse::fem {

std::vector<SpectralPeak> spectral_peaks(const std::vector<double>& signal, double dt, int count,
                                         double min_frequency, double relative_threshold,
                                         int padding) {
  const size_t n = signal.size();
  if (n < 16) throw InvalidInput("spectral_peaks: signal has fewer than 16 samples");
  if (!(dt > 0)) throw InvalidInput("spectral_peaks: sampling interval must be > 0");
  size_t nfft = 1;
  while (nfft < static_cast<size_t>(std::max(padding, 1)) * n) nfft <<= 1;
  double mean = 0;
  for (double v : signal) mean += v;
  mean /= static_cast<double>(n);
  std::vector<double> x(nfft, 0.0);
  for (size_t i = 0; i < n; ++i) {
    const double w = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n - 1));
    x[i] = w * (signal[i] - mean);
  }
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> X;
  fft.fwd(X, x);
  const size_t half = nfft / 2;
  std::vector<double> mag(half + 1);
  for (size_t k = 0; k <= half; ++k) mag[k] = std::abs(X[k]);
  const double df = 1.0 / (static_cast<double>(nfft) * dt);
  std::vector<SpectralPeak> peaks;
  for (size_t k = 1; k < half; ++k) {
    if (!(mag[k] > mag[k - 1] && mag[k] >= mag[k + 1])) continue;
    if (static_cast<double>(k) * df < min_frequency) continue;
    const double a = std::log(mag[k - 1]), b = std::log(mag[k]), c = std::log(mag[k + 1]);
    const double denom = a - 2 * b + c;
    const double delta = denom != 0 ? 0.5 * (a - c) / denom : 0.0;
    peaks.push_back({(static_cast<double>(k) + delta) * df, std::exp(b - 0.25 * (a - c) * delta)});
  }
  double largest = 0;
  for (const auto& p : peaks) largest = std::max(largest, p.amplitude);
  std::vector<SpectralPeak> strong;  // already in ascending frequency
  for (const auto& p : peaks)
    if (p.amplitude >= relative_threshold * largest && static_cast<int>(strong.size()) < count)
      strong.push_back(p);
  return strong;
}

}  // namespace finverse::fem
