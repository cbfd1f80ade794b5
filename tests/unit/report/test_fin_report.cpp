// The report of a case on synthetic stage files (tools/report/fin_report): without fsi.h5 every
// FSI-against-reconstruction score is "not available" and says it needs fsi.h5; with an fsi.h5
// whose motion is the reconstruction's at 90 % amplitude the trailing-edge scores are graded and
// missed by 10 %, and with the same motion they are met.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "report/fin_report.hpp"

namespace finverse::report {
namespace {

// A 9 x 13 node rectangular fin (chord 0.01 m, span 0.015 m) flapping y = a(z) sin(2 pi t / T)
// with edges leading the middle (a W at mid-stroke).
struct Fin {
  stage::Mesh mesh;
  stage::Motion motion;
};

Fin flapping_fin(double amplitude_scale) {
  Fin fin;
  const std::size_t nx = 9, nz = 13, nf = 24;
  fin.mesh.points = NdArray<double>({nx * nz, 3});
  for (std::size_t i = 0; i < nx; ++i)
    for (std::size_t j = 0; j < nz; ++j)
      fin.mesh.points(i * nz + j, 0) = 0.01 * double(i) / (nx - 1), fin.mesh.points(i * nz + j, 2) = 0.015 * double(j) / (nz - 1);
  fin.mesh.chord = 0.01;
  fin.motion.time = NdArray<double>({nf});
  fin.motion.points = NdArray<double>({nf, nx * nz, 3});
  for (std::size_t f = 0; f < nf; ++f) {
    fin.motion.time(f) = 0.01 * double(f);
    const double phase = std::sin(2 * std::numbers::pi * double(f) / nf);
    for (std::size_t v = 0; v < nx * nz; ++v) {
      const double x = fin.mesh.points(v, 0), z = fin.mesh.points(v, 2), zeta = (z - 0.0075) / 0.0075;
      const double a = amplitude_scale * 0.5 * x * (1 + 0.5 * zeta * zeta);
      fin.motion.points(f, v, 0) = x, fin.motion.points(f, v, 2) = z;
      fin.motion.points(f, v, 1) = a * phase + 0.2 * x * zeta * zeta * std::cos(2 * std::numbers::pi * double(f) / nf);
    }
  }
  return fin;
}

const Score& find(const Report& r, const std::string& name) {
  for (const auto& s : r.scores)
    if (s.name == name) return s;
  throw std::runtime_error("no score " + name);
}

TEST(FinReport, WithoutFsiTheFsiScoresAreNotAvailableAndSaySo) {
  const auto fin = flapping_fin(1.0);
  ReportInputs in;
  in.case_name = "synthetic";
  in.mesh = fin.mesh;
  in.motion = fin.motion;
  const auto r = build_report(in);
  const auto& te = find(r, "trailing-edge point 1 peak-to-peak, FSI vs reconstruction");
  EXPECT_EQ(te.status, Status::not_available);
  EXPECT_NE(te.note.find("fsi.h5"), std::string::npos);
  EXPECT_EQ(find(r, "W-shape d2, FSI vs reconstruction").status, Status::not_available);
  EXPECT_EQ(find(r, "fitted ray E vs truth, median relative error").status, Status::not_available);
  // The reconstruction's own trailing-edge excursion: point 1 at the dorsal tip (x = c, zeta = 1),
  // 2 sqrt(0.75^2 + 0.2^2) c, sampled at 24 frames (within 1 %).
  EXPECT_NEAR(*find(r, "trailing-edge point 1 peak-to-peak, reconstruction (motion.h5)").value,
              2 * std::hypot(0.75, 0.2), 0.02);
  const auto j = summary_json(in, r);
  EXPECT_EQ(j["schema"], "finverse/report");
  EXPECT_EQ(j["counts"]["met"], 0);
  EXPECT_FALSE(j["inputs"]["fsi"].get<bool>());
}

TEST(FinReport, AnFsiAtNinetyPercentAmplitudeMissesTheTrailingEdgeGoal) {
  const auto fin = flapping_fin(1.0), weaker = flapping_fin(0.9);
  ReportInputs in;
  in.case_name = "synthetic";
  in.mesh = fin.mesh;
  in.motion = fin.motion;
  in.fsi = stage::Fsi{};
  in.fsi->time = weaker.motion.time;
  in.fsi->points = weaker.motion.points;
  auto r = build_report(in);
  const auto& te = find(r, "trailing-edge point 2 peak-to-peak, FSI vs reconstruction");
  EXPECT_EQ(te.status, Status::missed);
  EXPECT_GT(*te.value, 0.05);
  in.fsi->points = fin.motion.points;
  r = build_report(in);
  for (int p = 1; p <= 3; ++p)
    EXPECT_EQ(find(r, "trailing-edge point " + std::to_string(p) + " peak-to-peak, FSI vs reconstruction").status,
              Status::met);
  EXPECT_EQ(find(r, "W-shape alpha1, FSI vs reconstruction").status, Status::met);
  EXPECT_NEAR(*find(r, "FSI vs reconstructed motion, mean node distance").value, 0.0, 1e-15);
}

}  // namespace
}  // namespace finverse::report
