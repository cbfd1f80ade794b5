// The periodic low-pass of a sampled motion (cfd/immersed/periodic_low_pass.hpp): a motion made of
// its first K harmonics passes unchanged, also when the frames do not tile the period (a camera's
// rate); a harmonic above K and frame-to-frame noise are removed; too few frames are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "cfd/immersed/periodic_low_pass.hpp"
#include "core/error.hpp"

namespace finverse::cfd {
namespace {

constexpr double kT = 0.22727;  // the default fin's period, 114 frames at 500 fps do not tile it

double smooth(double t, int channel) {
  const double w = 2 * std::numbers::pi / kT;
  return 0.3 * channel + std::sin(w * t + channel) + 0.2 * std::cos(3 * w * t) + 0.05 * std::sin(7 * w * t);
}

TEST(PeriodicLowPass, KeepsTheFirstHarmonicsAndRemovesTheRest) {
  std::vector<double> time, clean, noisy;
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.01);
  for (int k = 0; k < 114; ++k) {
    time.push_back(0.002 * k);
    for (int c = 0; c < 2; ++c) {
      clean.push_back(smooth(time.back(), c));
      noisy.push_back(clean.back() + noise(rng) + 0.1 * std::sin(2 * std::numbers::pi / kT * 15 * time.back()));
    }
  }
  const std::vector<double> same = periodic_low_pass(time, clean, 2, kT, 10, "test motion");
  double err = 0;
  for (std::size_t i = 0; i < clean.size(); ++i) err = std::max(err, std::abs(same[i] - clean[i]));
  EXPECT_LT(err, 1e-10);
  const std::vector<double> filtered = periodic_low_pass(time, noisy, 2, kT, 10, "test motion");
  double before = 0, after = 0;
  for (std::size_t i = 0; i < clean.size(); ++i) {
    before += std::pow(noisy[i] - clean[i], 2);
    after += std::pow(filtered[i] - clean[i], 2);
  }
  // The 15th harmonic (rms 0.07) goes; of the white noise (rms 0.01) about sqrt(21 / 114) stays.
  EXPECT_GT(std::sqrt(before / clean.size()), 0.07);
  EXPECT_LT(std::sqrt(after / clean.size()), 0.006);
}

TEST(PeriodicLowPass, TooFewFramesOrNoPeriodAreRefused) {
  const std::vector<double> time{0, 0.1, 0.2, 0.3, 0.4, 0.5}, values(6, 1.0);
  EXPECT_THROW(periodic_low_pass(time, values, 1, 0.6, 2, "m"), Error);  // 5 unknowns, 6 frames
  EXPECT_NO_THROW(periodic_low_pass(time, values, 1, 0.6, 1, "m"));
  EXPECT_THROW(periodic_low_pass(time, values, 1, 0.0, 1, "m"), Error);
  EXPECT_THROW(periodic_low_pass(time, values, 2, 0.6, 1, "m"), Error);  // values do not fit
}

}  // namespace
}  // namespace finverse::cfd
