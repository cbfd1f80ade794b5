// Tests of the tracked motion through its first harmonics (fem/io/harmonic_motion.hpp): a node
// moving with the beat's first two harmonics plus a fifth-harmonic "tracking noise", sampled over
// two whole periods, comes back as the two harmonics exactly; too few frames and a zero
// frequency are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fem/errors.hpp"
#include "fem/io/harmonic_motion.hpp"

namespace finverse::fem::io {
namespace {

stage::Motion two_harmonics_and_noise(std::size_t frames, double f) {
  stage::Motion m;
  m.time = NdArray<double>({frames});
  m.points = NdArray<double>({frames, 2, 3});
  for (std::size_t k = 0; k < frames; ++k) {
    const double t = 2.0 / f * static_cast<double>(k) / static_cast<double>(frames), wt = 2 * std::numbers::pi * f * t;
    m.time.data[k] = t;
    for (std::size_t n = 0; n < 2; ++n) {
      m.points(k, n, 0) = 0.01 * static_cast<double>(n) + 1e-3 * std::sin(wt) + 4e-4 * std::cos(2 * wt);
      m.points(k, n, 1) = -2e-3 * std::cos(wt) + 3e-5 * std::sin(5 * wt);  // the noise
      m.points(k, n, 2) = 0.005;
    }
  }
  return m;
}

TEST(HarmonicMotion, KeepsTheBeatsHarmonicsAndDropsTheRest) {
  const double f = 4.4;
  const stage::Motion in = two_harmonics_and_noise(32, f);
  const stage::Motion out = harmonic_motion(in, f, 2, "test motion");
  ASSERT_EQ(out.points.data.size(), in.points.data.size());
  for (std::size_t k = 0; k < 32; ++k) {
    const double wt = 2 * std::numbers::pi * f * in.time.data[k];
    for (std::size_t n = 0; n < 2; ++n) {
      EXPECT_NEAR(out.points(k, n, 0), in.points(k, n, 0), 1e-15);
      EXPECT_NEAR(out.points(k, n, 1), -2e-3 * std::cos(wt), 1e-15);
      EXPECT_NEAR(out.points(k, n, 2), 0.005, 1e-15);
    }
  }
}

TEST(HarmonicMotion, RefusesTooFewFramesAndNoFrequency) {
  const stage::Motion in = two_harmonics_and_noise(4, 1.0);
  EXPECT_THROW(harmonic_motion(in, 1.0, 2, "test motion"), InvalidInput);
  EXPECT_THROW(harmonic_motion(in, 0.0, 1, "test motion"), InvalidInput);
  EXPECT_NO_THROW(harmonic_motion(in, 1.0, 1, "test motion"));
}

}  // namespace
}  // namespace finverse::fem::io
