// How smooth a periodic loads history is (issue 30: "fin loads you can fit against"): over the
// last period of loads.h5 (N outputs, the period a whole number of output intervals), each series
// x_t is split by its discrete Fourier transform into the harmonics 0..K of the beat frequency
// (the smooth part, the mean included) and the rest (harmonics K+1 .. N/2, the high-frequency
// part). Measures, with K = 10 as in the issue:
//   - energy fraction: sum_{k>K} |X_k|^2 / sum_{k>=1} |X_k|^2 (mean removed), for C_T and C_L;
//   - rms ratio: rms of the high-frequency part / rms of the smooth part, over every series of a
//     field (the three components of every nodal force; every shell triangle's pressure jump);
//   - increment ratio: rms of the load increments x_{t+1} - x_t between consecutive outputs (what
//     the quasi-static objective, seed paper eq. (2), is driven by) / the same for the smooth part.
// A spike of one output in a smooth history shows in all three; a smooth history gives
// 0, 0 and 1.
#pragma once

#include <optional>
#include <vector>

#include "core/stage_files.hpp"

namespace finverse::cfd::validation {

// The smooth part (harmonics 0..K) of one period of samples x_0..x_{N-1}.
std::vector<double> smooth_part(const std::vector<double>& x, int harmonics);

// Spectral energy above harmonic K over the total (mean removed); 0 for a constant series.
double high_frequency_energy_fraction(const std::vector<double>& x, int harmonics);

struct LoadSmoothness {
  int outputs = 0;                        // N, outputs in the last period
  int harmonics = 10;                     // K
  double thrust_energy_fraction = 0;      // C_T
  double lateral_energy_fraction = 0;     // C_L (lateral)
  double nodal_rms_ratio = 0;             // nodal forces
  double jump_rms_ratio = 0;              // pressure jumps
  double nodal_increment_ratio = 0;       // nodal forces: raw / smooth increments
  double thrust_increment_ratio = 0;      // C_T: raw / smooth increments
};

// Over the last period of a periodic record; nothing when the record is not periodic, its output
// times are not evenly spaced, or the last period holds fewer than 2 K + 2 outputs (the smooth and
// high-frequency parts would not be told apart).
std::optional<LoadSmoothness> load_smoothness(const stage::Loads& loads, int harmonics = 10);

}  // namespace finverse::cfd::validation
