// Frequencies of the strongest spectral peaks of a uniformly sampled signal, for measuring
// natural frequencies from a simulated free vibration.
//
// Hann window, zero padding to >= `padding` times the signal length (power of two), FFT (Eigen's
// kissfft backend), local maxima of |X|, each refined by
// a parabola through the log-magnitudes of the three bins around it (for a Hann window the
// remaining bias is < 1e-3 bin; Grandke 1983, IEEE Trans. Instrum. Meas. 32:350).
#pragma once

#include <vector>

namespace finverse::fem {

struct SpectralPeak {
  double frequency = 0;  // Hz
  double amplitude = 0;  // |X| at the refined peak (relative)
};

// The `count` lowest-frequency peaks above min_frequency whose amplitude is at least
// relative_threshold times the largest peak's (0.1 = -20 dB, above the Hann side lobes at
// -31 dB), sorted by ascending frequency.
std::vector<SpectralPeak> spectral_peaks(const std::vector<double>& signal, double dt, int count,
                                         double min_frequency = 0, double relative_threshold = 0.1,
                                         int padding = 8);

}  // namespace finverse::fem
