// Residual analysis on analytic fields (loop/residual_field, harmonic_analysis, fin_regions,
// residual_modes, phase_character, trailing_edge_error): a flat fin pitching about its root line
// with a planted residual of known place, harmonic and phase.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "loop/errors.hpp"
#include "loop/fin_regions.hpp"
#include "loop/harmonic_analysis.hpp"
#include "loop/phase_character.hpp"
#include "loop/residual_field.hpp"
#include "loop/residual_modes.hpp"
#include "loop/trailing_edge_error.hpp"

namespace finverse::loop {
namespace {

constexpr double kPi = std::numbers::pi;

// 21 x 11 nodes on x in [0, 1] (chord), z in [-0.5, 0.5] (span); root nodes at x = 0.
struct Plate {
  Eigen::MatrixXd rest;
  std::vector<int> root;
  Plate() {
    rest.resize(21 * 11, 3);
    int n = 0;
    for (int i = 0; i < 21; ++i)
      for (int j = 0; j < 11; ++j, ++n) {
        rest.row(n) << i / 20.0, 0, -0.5 + j / 10.0;
        if (i == 0) root.push_back(n);
      }
  }
};

// The fin pitching: y = 0.2 x sin(w t), 24 frames over one period T = 1.
SampledMotion pitching(const Plate& plate, int frames, const std::string& source) {
  SampledMotion m;
  m.source = source;
  for (int k = 0; k < frames; ++k) {
    const double t = k / 24.0;
    Eigen::VectorXd p(3 * plate.rest.rows());
    for (Eigen::Index n = 0; n < plate.rest.rows(); ++n) {
      p.segment<3>(3 * n) = plate.rest.row(n).transpose();
      p(3 * n + 1) += 0.2 * plate.rest(n, 0) * std::sin(2 * kPi * t);
    }
    m.times.push_back(t);
    m.positions.push_back(p);
  }
  return m;
}

TEST(ResidualField, RefusesDifferentMeshesAndTimeBases) {
  const Plate plate;
  const auto a = pitching(plate, 24, "fsi.h5");
  auto b = pitching(plate, 24, "motion.h5");
  EXPECT_NO_THROW(residual_field(a, b, static_cast<int>(plate.rest.rows())));
  EXPECT_THROW(residual_field(a, b, 7), InvalidInput);
  auto fewer = pitching(plate, 20, "motion.h5");
  EXPECT_THROW(residual_field(a, fewer, static_cast<int>(plate.rest.rows())), InvalidInput);
  b.times[3] += 1e-3;
  try {
    residual_field(a, b, static_cast<int>(plate.rest.rows()));
    FAIL() << "shifted time base accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("fsi.h5 and motion.h5"), std::string::npos) << e.what();
  }
}

TEST(Harmonics, RecoverMeanAmplitudeAndPhase) {
  std::vector<double> t;
  Eigen::MatrixXd rows(3, 24);
  for (int k = 0; k < 24; ++k) {
    t.push_back(0.5 * k / 24.0);  // T = 0.5
    const double w = 2 * kPi / 0.5;
    rows(0, k) = 1 + 2 * std::cos(w * t[k] + 0.3) + 0.5 * std::cos(2 * w * t[k] - 1);
    rows(1, k) = 0;
    rows(2, k) = -0.1 * std::cos(3 * w * t[k] + 2);
  }
  const auto h = fit_harmonics(t, rows, 0.5, 3);
  EXPECT_TRUE(h.whole_period);
  EXPECT_NEAR(h.mean(0), 1, 1e-12);
  EXPECT_NEAR(node_amplitude(h, 1)(0), 2, 1e-12);
  EXPECT_NEAR(node_phase(h, 1)(0), 0.3, 1e-12);
  EXPECT_NEAR(node_amplitude(h, 2)(0), 0.5, 1e-12);
  EXPECT_NEAR(node_phase(h, 2)(0), -1, 1e-12);
  EXPECT_NEAR(node_amplitude(h, 3)(0), 0.1, 1e-12);
  EXPECT_NEAR(std::abs(node_phase(h, 3)(0)), kPi - 2, 1e-12);  // -0.1 cos(x + 2) = 0.1 cos(x + 2 - pi)
  EXPECT_THROW(fit_harmonics(t, rows, 0, 3), InvalidInput);
  const auto partial = fit_harmonics(std::vector<double>(t.begin(), t.begin() + 8), rows.leftCols(8), 0.5, 3);
  EXPECT_FALSE(partial.whole_period);
}

TEST(FinRegions, FiveRegionsOnAFlatFin) {
  const Plate plate;
  const auto r = classify_fin_regions(plate.rest, plate.root);
  EXPECT_EQ(r.region[plate.root[5]], Region::root);
  EXPECT_EQ(r.region[20 * 11 + 5], Region::distal);      // trailing edge, mid-span
  EXPECT_EQ(r.region[10 * 11 + 10], Region::dorsal_edge);  // mid-chord, z = +0.5
  EXPECT_EQ(r.region[10 * 11 + 0], Region::ventral_edge);
  EXPECT_EQ(r.region[10 * 11 + 5], Region::middle);
  EXPECT_THROW(classify_fin_regions(plate.rest, {}), InvalidInput);
}

// Residual: a distal mode in phase with the root velocity (cos while the root goes as sin) and a
// weaker dorsal-edge mode in phase with the displacement.
TEST(ResidualModes, PlaceEnergyAndPhaseOfPlantedModes) {
  const Plate plate;
  const int nv = static_cast<int>(plate.rest.rows());
  const auto data = pitching(plate, 24, "motion.h5");
  auto model = data;
  model.source = "fsi.h5";
  const auto regions = classify_fin_regions(plate.rest, plate.root);
  for (int k = 0; k < 24; ++k) {
    const double t = data.times[k];
    for (int n = 0; n < nv; ++n) {
      if (regions.region[n] == Region::distal) model.positions[k](3 * n + 1) += 0.02 * std::cos(2 * kPi * t);
      if (regions.region[n] == Region::dorsal_edge) model.positions[k](3 * n + 1) += 0.005 * std::sin(2 * kPi * t);
    }
  }
  const auto field = residual_field(model, data, nv);
  const auto modes = residual_modes(field, {}, 4);
  ASSERT_GE(modes.energy_fraction.size(), 2);
  EXPECT_NEAR(modes.energy_fraction.head(2).sum(), 1.0, 1e-9);
  int distal = 0, dorsal = 0;
  for (auto r : regions.region) distal += r == Region::distal, dorsal += r == Region::dorsal_edge;
  const double e_distal = distal * 0.02 * 0.02, e_dorsal = dorsal * 0.005 * 0.005;
  EXPECT_NEAR(modes.energy_fraction(0), e_distal / (e_distal + e_dorsal), 1e-9);
  const auto e0 = region_energy_fractions(regions, modes.shape.col(0));
  EXPECT_GT(e0[static_cast<int>(Region::distal)], 0.999);
  const auto e1 = region_energy_fractions(regions, modes.shape.col(1));
  EXPECT_GT(e1[static_cast<int>(Region::dorsal_edge)], 0.999);

  const auto root = root_signal(data, regions);
  EXPECT_GT(root.amplitude, 0);
  const auto p0 = phase_character(modes.coefficient.col(0), root);
  EXPECT_EQ(p0.character, "damping-like");
  EXPECT_GT(std::abs(p0.rho_velocity), 0.99);
  // One harmonic: displacement and acceleration are collinear, so stiffness and inertia are
  // not told apart; the label says so.
  const auto p1 = phase_character(modes.coefficient.col(1), root);
  EXPECT_EQ(p1.character, "stiffness- or inertia-like");
  // A third harmonic is orthogonal to the root's first over a period: it follows no root signal.
  Eigen::VectorXd third(24);
  for (int k = 0; k < 24; ++k) third(k) = std::cos(3 * 2 * kPi * k / 24.0);
  EXPECT_EQ(phase_character(third, root).character, "none");

  // Harmonic 1 of the residual: amplitude 0.02 at the distal nodes, phase 0 (cos).
  const auto h = fit_harmonics(field.times, field.values, 1.0, 3);
  EXPECT_NEAR(node_amplitude(h, 1)(20 * 11 + 5), 0.02, 1e-9);
  EXPECT_NEAR(node_phase(h, 1)(20 * 11 + 5), 0, 1e-9);
  EXPECT_NEAR(node_amplitude(h, 2)(20 * 11 + 5), 0, 1e-9);

  // Trailing edge (x = 1): residual RMS 0.02 / sqrt 2 against an excursion of 0.4 (edge rows
  // of the trailing edge are dorsal/ventral edge nodes: only the mid-span ones).
  std::vector<int> te;
  for (int j = 3; j <= 7; ++j) te.push_back(20 * 11 + j);
  const auto err = trailing_edge_error(field, data, te);
  EXPECT_NEAR(err.excursion, 0.4 * std::sin(2 * kPi * 6 / 24.0), 1e-9);
  EXPECT_NEAR(err.rms, 0.02 / std::sqrt(2.0), 1e-9);
}

}  // namespace
}  // namespace finverse::loop
