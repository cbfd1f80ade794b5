// The fin run's centred output-interval mean of the loads (cfd/io/loads_window.hpp) and the
// smoothness measures of a periodic loads history (cfd/validation/load_smoothness.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "cfd/io/loads_window.hpp"
#include "cfd/validation/load_smoothness.hpp"

namespace finverse::cfd {
namespace {

using io::LoadsWindow;

// Feeds steps 1..last with the scalar load f(n) (one node, x component; one shell triangle) and
// returns the outputs' values by output step.
std::vector<std::pair<long, double>> run(LoadsWindow& w, long last, double (*f)(long)) {
  std::vector<std::pair<long, double>> out;
  for (long n = 1; n <= last; ++n) {
    if (!w.needs(n)) continue;
    for (const auto& o : w.add(n, {Vec3{f(n), 0, 0}}, Vec3{f(n), 0, 0}, {f(n)})) {
      EXPECT_DOUBLE_EQ(o.total[0], o.nodal[0][0]);
      EXPECT_DOUBLE_EQ(o.jump[0], o.nodal[0][0]);
      out.push_back({o.step, o.nodal[0][0]});
    }
  }
  return out;
}

TEST(LoadsWindow, EvenStepsPerOutputAverageOneIntervalCentredOnTheOutput) {
  // m = 4: outputs at steps 8, 12, 16; the run goes 2 steps past the last.
  LoadsWindow w(4, 1, 1, 8, 16, 18);
  EXPECT_FALSE(w.needs(5));
  EXPECT_TRUE(w.needs(6));
  EXPECT_DOUBLE_EQ(w.weight(8, 6), 0.5);
  EXPECT_DOUBLE_EQ(w.weight(8, 7), 1.0);
  EXPECT_DOUBLE_EQ(w.weight(8, 10), 0.5);
  EXPECT_DOUBLE_EQ(w.weight(12, 10), 0.5);  // shared with the next output's window
  const auto linear = run(w, 18, [](long n) { return 3.0 * static_cast<double>(n) - 1.0; });
  ASSERT_EQ(linear.size(), 3u);
  for (const auto& [s, v] : linear) EXPECT_NEAR(v, 3.0 * static_cast<double>(s) - 1.0, 1e-12);  // no lag
  // A one-step spike keeps its impulse: it adds spike / m to its output.
  LoadsWindow w2(4, 1, 1, 8, 16, 18);
  const auto spike = run(w2, 18, [](long n) { return n == 11 ? 8.0 : 0.0; });
  EXPECT_NEAR(spike[1].second, 2.0, 1e-15);
  EXPECT_NEAR(spike[0].second + spike[2].second, 0.0, 1e-15);
}

TEST(LoadsWindow, OddStepsPerOutputAndTheShortenedLastWindow) {
  // m = 3, outputs at 3, 6, 9, and the run ends on the last output: its window shrinks to itself.
  LoadsWindow w(3, 1, 1, 3, 9, 9);
  EXPECT_EQ(w.half_width(3), 1);
  EXPECT_EQ(w.half_width(9), 0);
  const auto out = run(w, 9, [](long n) { return static_cast<double>(n * n); });
  ASSERT_EQ(out.size(), 3u);
  EXPECT_NEAR(out[0].second, (4.0 + 9.0 + 16.0) / 3.0, 1e-12);
  EXPECT_NEAR(out[2].second, 81.0, 1e-12);
}

TEST(LoadsWindow, SamplingTakesTheOutputStepAlone) {
  LoadsWindow w(4, 1, 1, 4, 8, 10, true);
  EXPECT_FALSE(w.needs(5));
  const auto out = run(w, 10, [](long n) { return static_cast<double>(n * n); });
  ASSERT_EQ(out.size(), 2u);
  EXPECT_DOUBLE_EQ(out[0].second, 16.0);
  EXPECT_DOUBLE_EQ(out[1].second, 64.0);
}

TEST(LoadsWindow, ARestoredStateContinuesTheSameSums) {
  const auto f = [](long n) { return std::sin(0.7 * static_cast<double>(n)); };
  LoadsWindow a(6, 1, 1, 6, 30, 33), b(6, 1, 1, 6, 30, 33);
  std::vector<double> whole, resumed;
  for (long n = 1; n <= 33; ++n)
    if (a.needs(n))
      for (const auto& o : a.add(n, {Vec3{f(n), 1, 2}}, Vec3{f(n), 1, 2}, {f(n)})) whole.push_back(o.total[0]);
  for (long n = 1; n <= 14; ++n)
    if (b.needs(n))
      for (const auto& o : b.add(n, {Vec3{f(n), 1, 2}}, Vec3{f(n), 1, 2}, {f(n)})) resumed.push_back(o.total[0]);
  LoadsWindow c(6, 1, 1, 6, 30, 33);
  c.restore(b.state());
  for (long n = 15; n <= 33; ++n)
    if (c.needs(n))
      for (const auto& o : c.add(n, {Vec3{f(n), 1, 2}}, Vec3{f(n), 1, 2}, {f(n)})) resumed.push_back(o.total[0]);
  ASSERT_EQ(whole.size(), 5u);
  EXPECT_EQ(whole, resumed);
  EXPECT_THROW(c.restore({1.0, 2.0}), Error);
}

TEST(LoadSmoothness, SplitsAPeriodIntoHarmonicsUpToTenAndTheRest) {
  const int N = 100;
  std::vector<double> smooth(N), noisy(N);
  for (int t = 0; t < N; ++t) {
    const double p = 2 * std::numbers::pi * t / N;
    smooth[static_cast<std::size_t>(t)] = 0.3 + std::sin(p) + 0.2 * std::cos(10 * p);
    noisy[static_cast<std::size_t>(t)] = smooth[static_cast<std::size_t>(t)] + 0.1 * std::sin(23 * p);
  }
  EXPECT_LT(validation::high_frequency_energy_fraction(smooth, 10), 1e-20);
  // Energy 0.01 / 2 against 1 / 2 + 0.04 / 2 + 0.01 / 2.
  EXPECT_NEAR(validation::high_frequency_energy_fraction(noisy, 10), 0.01 / 1.05, 1e-12);
  const auto s = validation::smooth_part(noisy, 10);
  for (int t = 0; t < N; ++t) EXPECT_NEAR(s[static_cast<std::size_t>(t)], smooth[static_cast<std::size_t>(t)], 1e-12);
}

TEST(LoadSmoothness, MeasuresALoadsRecordOverItsLastPeriod) {
  const std::size_t N = 40, nt = 2 * N;  // two periods of 40 outputs; only the last counts
  stage::Loads l;
  l.period = 0.4;
  l.time = NdArray<double>({nt});
  l.thrust = NdArray<double>({nt});
  l.lateral = NdArray<double>({nt});
  l.nodal_force = NdArray<double>({nt, 2, 3}, 0.0);
  l.pressure_jump = NdArray<double>({nt, 1}, 0.0);
  for (std::size_t k = 0; k < nt; ++k) {
    const double t = 0.01 * static_cast<double>(k + 1), p = 2 * std::numbers::pi * t / 0.4;
    l.time(k) = t;
    l.thrust(k) = 0.1 + 0.5 * std::sin(2 * p) + (k < N ? 5.0 * std::sin(17 * p) : 0.0);  // noise in period 1 only
    l.lateral(k) = std::sin(p) + 0.1 * std::sin(15 * p);
    l.nodal_force(k, 0, 1) = std::sin(p);
    l.nodal_force(k, 1, 1) = std::cos(p) + (k % 2 ? 0.05 : -0.05);  // Nyquist noise
    l.pressure_jump(k, 0) = 2 + std::sin(p);
  }
  const auto q = validation::load_smoothness(l);
  ASSERT_TRUE(q.has_value());
  EXPECT_EQ(q->outputs, 40);
  EXPECT_LT(q->thrust_energy_fraction, 1e-20);
  EXPECT_NEAR(q->lateral_energy_fraction, 0.01 / 1.01, 1e-12);
  EXPECT_NEAR(q->nodal_rms_ratio, 0.05, 1e-12);  // rms 0.05 against the two unit sines' rms 1/sqrt(2) each
  EXPECT_NEAR(q->jump_rms_ratio, 0.0, 1e-12);
  EXPECT_GT(q->nodal_increment_ratio, 1.05);
  EXPECT_NEAR(q->thrust_increment_ratio, 1.0, 1e-12);
  l.period = 0.15;  // fewer than 22 outputs per period: not measured
  EXPECT_FALSE(validation::load_smoothness(l).has_value());
}

}  // namespace
}  // namespace finverse::cfd
