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
  EXPECT_FALSE(j.contains("scope"));  // said only when the case gives one
  in.scope = "the grading, not the method";
  EXPECT_EQ(summary_json(in, r)["scope"], "the grading, not the method");
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

// Fig. 12's data carries the truth's root drive when truth.h5 records it (issue 33), in degrees.
namespace finverse::report {
namespace {
TEST(FinReport, RootPitchFigureCarriesTheTruthsRootDrive) {
  // flapping_fin's 9 x 13 grid as a tracked template: 13 rays along x.
  const auto fin = flapping_fin(1.0);
  const std::size_t nx = 9, nz = 13;
  stage::Kinematics k;
  k.time = fin.motion.time;
  k.points = fin.motion.points;
  k.template_points = fin.mesh.points;
  std::vector<std::int32_t> tri, offsets{0}, vertices;
  for (std::size_t i = 0; i + 1 < nx; ++i)
    for (std::size_t j = 0; j + 1 < nz; ++j) {
      const auto a = std::int32_t(i * nz + j), b = std::int32_t((i + 1) * nz + j);
      for (std::int32_t v : {a, b, b + 1, a, b + 1, a + 1}) tri.push_back(v);
    }
  for (std::size_t j = 0; j < nz; ++j) {
    for (std::size_t i = 0; i < nx; ++i) vertices.push_back(std::int32_t(i * nz + j));
    offsets.push_back(std::int32_t(vertices.size()));
  }
  k.template_triangles = NdArray<std::int32_t>({tri.size() / 3, 3}, tri);
  k.ray_offsets = NdArray<std::int32_t>({offsets.size()}, offsets);
  k.ray_vertices = NdArray<std::int32_t>({vertices.size()}, vertices);
  stage::Truth t;
  t.time = k.time;
  t.points = k.points;
  t.template_points = k.template_points;
  t.template_triangles = k.template_triangles;
  t.root_ray_ids = NdArray<std::int32_t>({2}, {1, 2});
  t.root_eta = NdArray<double>({2}, {1.0, -1.0});
  t.root_pitch_amplitude = NdArray<double>({2}, {std::numbers::pi / 180 * 22, std::numbers::pi / 180 * 12});
  t.root_pitch_phase = NdArray<double>({2}, {-std::numbers::pi / 2, -std::numbers::pi / 3});
  ReportInputs in;
  in.case_name = "synthetic";
  in.mesh = fin.mesh;
  in.kinematics = k;
  in.truth = t;
  const auto r = build_report(in);
  ASSERT_TRUE(r.figures.contains("root_pitch"));
  const auto& d = r.figures["root_pitch"]["truth_drive"];
  EXPECT_NEAR(d["pitch_amplitude_deg"][0].get<double>(), 22, 1e-12);
  EXPECT_NEAR(d["pitch_phase_deg"][1].get<double>(), -60, 1e-12);
  EXPECT_EQ(d["ray_ids"][1].get<int>(), 2);
}
}  // namespace
}  // namespace finverse::report
