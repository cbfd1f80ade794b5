// The FSI motion source (issue 33, Deliver 1): the map from the mesh's nodes to the render surface
// is exact for a rigid motion (affine coordinates, also just outside the outline) and second order
// for a bending (flat facets on a curved surface); the time interpolation is periodic in T, C1,
// uses only the last period, and mismatched fsi.h5 / mesh.h5 pairs are refused in one line;
// fin-synth --motion-source fsi renders that motion and records materials and root drive.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <numbers>

#include <nlohmann/json.hpp>

#include "../scratch_dir.hpp"
#include "core/error.hpp"
#include "core/stage_files.hpp"
#include "mesh/ibm_surface.hpp"
#include "mesh/planform_mesher.hpp"
#include "mesh/structural_mesh.hpp"
#include "vision/fsi_motion_source.hpp"

using namespace finverse;
using namespace finverse::vision;

namespace {

constexpr double kPi = std::numbers::pi;

struct Fixture {
  mesh::FinTemplate fin = mesh::make_caudal_fin({});
  FinSurface surface = make_fin_surface(fin, 4);
  stage::Mesh m;
  Fixture() {
    const auto pm = mesh::mesh_planform(fin, {0.1, 25.0});  // coarse: c/10 edges
    m = mesh::assemble_mesh(fin, pm, mesh::build_ibm_surface(pm, 0.05 * fin.chord), 0.0);
  }
  std::size_t nv() const { return m.points.dim(0); }
};

// Samples of a node motion x(X, t) at `nt` times per period over `periods` periods ending at t_end.
template <class F> FsiSamples sample(const Fixture& f, double T, std::size_t nt, double periods, F&& motion) {
  FsiSamples s;
  s.rest = f.m.points;
  s.triangles = f.m.triangles;
  s.period = T;
  const auto n = static_cast<std::size_t>(std::llround(periods * nt)) + 1;
  s.points = NdArray<double>({n, f.nv(), 3});
  for (std::size_t k = 0; k < n; ++k) {
    const double t = k * T / nt;
    s.time.push_back(t);
    for (std::size_t i = 0; i < f.nv(); ++i) {
      const auto x = motion(f.m.points(i, 0), f.m.points(i, 1), f.m.points(i, 2), t);
      for (int d = 0; d < 3; ++d) s.points(k, i, d) = x[d];
    }
  }
  return s;
}

// Rigid motion: rotation by theta(t) about the dorsal axis z through (0.3 c, 0), then heave in y.
std::array<double, 3> rigid(double x, double y, double z, double t, double T, double c) {
  const double th = 0.4 * std::sin(2 * kPi * t / T), h = 0.44 * c * std::sin(2 * kPi * t / T + 0.3);
  const double dx = x - 0.3 * c;
  return {0.3 * c + dx * std::cos(th) - y * std::sin(th), h + dx * std::sin(th) + y * std::cos(th), z};
}

}  // namespace

TEST(FsiMotion, RigidMotionIsCarriedExactlyAtTheSamples) {
  const Fixture f;
  const double T = 0.2, c = f.fin.chord;
  // The surface stretched by 3% about (0.5 c, 0) and lifted 0.01 c off the fin plane: vertices
  // outside the outline (affine extrapolation) and off the plane (the normal offset).
  auto surface = f.surface;
  for (std::size_t v = 0; v < surface.size(); ++v) {
    surface.rest(v, 0) = 0.5 * c + 1.03 * (surface.rest(v, 0) - 0.5 * c);
    surface.rest(v, 1) = 0.01 * c;
    surface.rest(v, 2) *= 1.03;
  }
  FsiMotion motion(sample(f, T, 16, 1, [&](double x, double y, double z, double t) { return rigid(x, y, z, t, T, c); }),
                   surface);
  EXPECT_GT(motion.max_outside_distance(), 0.015 * c);
  double worst = 0;
  for (int k : {0, 3, 7, 12}) {
    const double t = k * T / 16;
    const auto p = motion.positions(surface, t);
    for (std::size_t v = 0; v < surface.size(); ++v) {
      const auto e = rigid(surface.rest(v, 0), surface.rest(v, 1), surface.rest(v, 2), t, T, c);
      for (int d = 0; d < 3; ++d) worst = std::max(worst, std::abs(p(v, d) - e[d]));
    }
  }
  EXPECT_LT(worst, 1e-12 * c);
}

TEST(FsiMotion, BendingIsCarriedToSecondOrderInTheMeshSize) {
  const Fixture f;
  const double T = 0.2, c = f.fin.chord, a = 0.2;
  // Lateral deflection a c (x / c)^2 at full amplitude at t = T / 4: curvature 2 a / c.
  auto bend = [&](double x, double y, double z, double t) {
    return std::array<double, 3>{x, y + a * c * std::pow(x / c, 2) * std::sin(2 * kPi * t / T), z};
  };
  FsiMotion motion(sample(f, T, 16, 1, bend), f.surface);
  const auto p = motion.positions(f.surface, T / 4);
  double worst = 0;
  for (std::size_t v = 0; v < f.surface.size(); ++v)
    worst = std::max(worst, std::abs(p(v, 1) - a * c * std::pow(f.surface.rest(v, 0) / c, 2)));
  // Flat facets of edge h under curvature k: chord sag h^2 k / 8 = 0.1^2 * 0.4 / 8 c = 5e-4 c.
  EXPECT_LT(worst, 1e-3 * c);
  EXPECT_GT(worst, 1e-6 * c);  // not trivially exact: the facets are flat
}

TEST(FsiMotion, TimeInterpolationIsPeriodicSmoothAndUsesTheLastPeriod) {
  const Fixture f;
  const double T = 0.2, c = f.fin.chord, A = 0.5 * c;
  auto wave = [&](double x, double, double z, double t) {
    const double y = A * std::sin(2 * kPi * t / T - 3 * x / c);
    // Earlier periods (t < 2 T) carry a transient that the last period no longer has.
    return std::array<double, 3>{x, y + (t < 2 * T - 1e-12 ? 0.1 * c : 0.0), z};
  };
  auto s = sample(f, T, 32, 3, wave);  // t = 0 .. 3 T
  FsiMotion motion(std::move(s), f.surface);
  EXPECT_LT(motion.periodicity_gap(), 1e-12);  // samples at 2 T and 3 T agree
  double worst = 0, jump = 0;
  for (int j = 0; j < 97; ++j) {
    const double t = (j + 0.37) * T / 97;
    const auto x = motion.node_positions(t);
    for (std::size_t i = 0; i < f.nv(); ++i) {
      const double e = A * std::sin(2 * kPi * t / T - 3 * f.m.points(i, 0) / c);
      worst = std::max(worst, std::abs(x(i, 1) - e));
    }
  }
  // Periodic: t and t + 5 T give the same state; C1 across the wrap: one-sided slopes agree.
  const auto a = motion.node_positions(0.123 * T), b = motion.node_positions(5.123 * T);
  for (std::size_t i = 0; i < a.data.size(); ++i) jump = std::max(jump, std::abs(a.data[i] - b.data[i]));
  const double eps = 1e-7 * T;
  const auto l0 = motion.node_positions(T - eps), l1 = motion.node_positions(T - 2 * eps);
  const auto r0 = motion.node_positions(T + eps), r1 = motion.node_positions(T + 2 * eps);
  double kink = 0;
  for (std::size_t i = 0; i < l0.data.size(); ++i)
    kink = std::max(kink, std::abs((l0.data[i] - l1.data[i]) - (r1.data[i] - r0.data[i])) / eps);
  EXPECT_LT(worst, 1e-3 * A);  // cubic Hermite, 32 samples per period
  EXPECT_LT(jump, 1e-14);
  EXPECT_LT(kink, 1e-3 * 2 * kPi * A / T);
}

TEST(FsiMotion, RefusesSamplesThatDoNotCoverAPeriod) {
  const Fixture f;
  const double T = 0.2, c = f.fin.chord;
  auto s = sample(f, T, 16, 0.5, [&](double x, double y, double z, double t) { return rigid(x, y, z, t, T, c); });
  s.label = "half.h5";
  try {
    FsiMotion motion(std::move(s), f.surface);
    FAIL() << "half a period was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("half.h5: time:"), std::string::npos) << e.what();
  }
}

TEST(FsiMotion, FilesThatDoNotBelongTogetherAreRefusedInOneLine) {
  const Fixture f;
  const finverse::test::ScratchDir dir;
  const double T = 0.2, c = f.fin.chord;
  auto m = f.m;
  stage::write(dir / "mesh.h5", m, Provenance{"test", {}, {}});
  auto s = sample(f, T, 8, 1, [&](double x, double y, double z, double t) { return rigid(x, y, z, t, T, c); });
  auto write_fsi = [&](const std::string& name, const NdArray<double>& points, std::optional<double> period) {
    stage::Fsi r;
    const std::size_t nt = s.time.size(), nv = points.dim(1);
    r.time = NdArray<double>({nt}, s.time);
    r.points = points;
    r.nodal_force = NdArray<double>({nt, nv, 3}, 0.0);
    r.force_total = NdArray<double>({nt, 3}, 0.0);
    r.thrust = r.lateral = r.vertical = NdArray<double>({nt}, 0.0);
    r.coupling_iterations = NdArray<std::int32_t>({nt}, 1);
    r.coupling_residual = NdArray<double>({nt}, 0.0);
    r.rho = 1000, r.U = 0.1, r.reference_area = 1e-4, r.period = period;
    stage::write(dir / name, r, Provenance{"test", {}, {}});
  };
  write_fsi("ok.h5", s.points, T);
  const auto good = read_fsi_motion(dir / "ok.h5", dir / "mesh.h5", f.surface);
  EXPECT_DOUBLE_EQ(good.period(), T);
  NdArray<double> fewer({s.time.size(), f.nv() - 1, 3});
  for (std::size_t k = 0; k < s.time.size(); ++k)
    std::copy_n(s.points.data.begin() + k * f.nv() * 3, (f.nv() - 1) * 3, fewer.data.begin() + k * (f.nv() - 1) * 3);
  write_fsi("fewer.h5", fewer, T);
  write_fsi("no_period.h5", s.points, std::nullopt);
  for (const auto& [name, what] : {std::pair{"fewer.h5", "nodes per frame"}, std::pair{"no_period.h5", "attribute T"}}) {
    try {
      read_fsi_motion(dir / name, dir / "mesh.h5", f.surface);
      ADD_FAILURE() << name << " was accepted";
    } catch (const Error& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find(name), std::string::npos) << msg;
      EXPECT_NE(msg.find(what), std::string::npos) << msg;
      EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
  }
}

// fin-synth --motion-source fsi: the frames follow fsi.h5, and truth.h5 records the materials and
// the root drive; a drive whose frequency is not the FSI's is refused in one line (exit 2).
TEST(FinSynth, FsiSourceRecordsMaterialsAndTheRootDrive) {
  const Fixture f;
  const finverse::test::ScratchDir dir;
  const double T = 1 / 4.4, c = f.fin.chord;  // Re 1000, St 0.44 on A = 1.0 c: f = 4.4 Hz
  auto m = f.m;
  stage::write(dir / "mesh.h5", m, Provenance{"test", {}, {}});
  const auto s = sample(f, T, 20, 1, [&](double x, double y, double z, double t) { return rigid(x, y, z, t, T, c); });
  stage::Fsi r;
  const std::size_t nt = s.time.size();
  r.time = NdArray<double>({nt}, s.time);
  r.points = s.points;
  r.nodal_force = NdArray<double>({nt, f.nv(), 3}, 0.0);
  r.force_total = NdArray<double>({nt, 3}, 0.0);
  r.thrust = r.lateral = r.vertical = NdArray<double>({nt}, 0.0);
  r.coupling_iterations = NdArray<std::int32_t>({nt}, 1);
  r.coupling_residual = NdArray<double>({nt}, 0.0);
  r.rho = 1000, r.U = 0.1, r.reference_area = 1e-4, r.period = T;
  stage::write(dir / "fsi.h5", r, Provenance{"test", {}, {}});
  std::ofstream(dir / "materials.json") << R"({"membrane": {"E": 1.2e7, "nu": 0.4, "density": 1050},
      "rays": {"E": 3e8, "nu": 0.4, "density": 1100}, "ray": {"1": {"E": 1.3e9}, "20": {"E": 1.1e9}}})";
  std::ofstream(dir / "drive.json") << R"({"heave_over_chord": 0.44, "pitch_center_deg": 12, "pitch_edge_deg": 22,
      "pitch_phase_deg": -90, "pitch_phase_w_deg": -20, "strouhal": 0.44, "excursion_over_chord": 1.0})";
  std::ofstream(dir / "drive5.json") << R"({"frequency_hz": 5})";
  auto synth = [&](const std::string& drive, const std::string& extra = "") {
    const std::string cmd = std::string(FIN_SYNTH_EXE) + " --out-dir " + (dir / "out").string() +
                            " --motion-source fsi --fsi " + (dir / "fsi.h5").string() + " --fsi-mesh " +
                            (dir / "mesh.h5").string() + " --materials " + (dir / "materials.json").string() +
                            " --root-drive " + (dir / drive).string() + " --periods 0.05 --width 48 --height 48" +
                            " --supersample 1 --vtk false --log-level error --threads 1 " + extra + " 2> " +
                            (dir / "err.txt").string();
    const int rc = std::system(cmd.c_str());
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  };
  ASSERT_EQ(synth("drive.json"), 0);
  const auto truth = stage::read<stage::Truth>(dir / "out" / "truth.h5");
  EXPECT_EQ(truth.motion_source.value_or(""), "fsi");
  ASSERT_TRUE(truth.period.has_value());
  EXPECT_NEAR(*truth.period, T, 1e-12);
  std::map<std::string, double> mat;
  for (std::size_t i = 0; i < truth.material_names.size(); ++i) mat[truth.material_names[i]] = truth.material_values(i);
  EXPECT_DOUBLE_EQ(mat["E_membrane"], 1.2e7);
  EXPECT_DOUBLE_EQ(mat["E_ray1"], 1.3e9);
  EXPECT_DOUBLE_EQ(mat["E_ray10"], 3e8);
  EXPECT_DOUBLE_EQ(mat["E_ray20"], 1.1e9);
  EXPECT_DOUBLE_EQ(mat["nu"], 0.4);
  ASSERT_EQ(truth.root_pitch_amplitude.size(), 20u);
  EXPECT_EQ(truth.root_ray_ids(0), 1);
  EXPECT_NEAR(truth.root_pitch_amplitude(0), 22 * kPi / 180, 1e-12);  // U: the edge rays pitch most
  EXPECT_LT(truth.root_pitch_amplitude(10), 13 * kPi / 180);
  EXPECT_NEAR(truth.root_heave_amplitude(5), 0.44 * c, 1e-15);
  // The frames are the FSI motion: frame 3's vertices are the rigid motion at t = 3 / 500 s.
  const auto surface = make_fin_surface(f.fin, 4);
  ASSERT_EQ(truth.points.dim(1), surface.size());
  const double t3 = truth.time(3);
  double worst = 0;
  for (std::size_t v = 0; v < surface.size(); ++v) {
    const auto e = rigid(surface.rest(v, 0), surface.rest(v, 1), surface.rest(v, 2), t3, T, c);
    for (int d = 0; d < 3; ++d) worst = std::max(worst, std::abs(truth.points(3, v, d) - e[d]));
  }
  EXPECT_LT(worst, 2e-3 * c);  // the time interpolation between 20 samples per period
  EXPECT_EQ(synth("drive5.json"), 2);
  EXPECT_EQ(synth("drive.json", "--pitch-edge-deg 30"), 2);
}

// fin-synth --motion-source fem (issue 34's structural truth): fin-fem run's motion.h5 stands
// where fsi.h5 would; truth.h5 names the source "fem" and records the run's planted effects.
TEST(FinSynth, FemSourceRecordsTheRunsEffects) {
  const Fixture f;
  const finverse::test::ScratchDir dir;
  const double T = 1 / 4.4, c = f.fin.chord;
  auto m = f.m;
  stage::write(dir / "mesh.h5", m, Provenance{"test", {}, {}});
  const auto s = sample(f, T, 20, 1, [&](double x, double y, double z, double t) { return rigid(x, y, z, t, T, c); });
  stage::Motion r;
  r.time = NdArray<double>({s.time.size()}, s.time);
  r.points = s.points;
  r.period = T;
  r.effects = R"([{"name":"active_stiffening","amplitude":0.3,"phase":0.0,"group":"all"}])";
  stage::write(dir / "motion.h5", r, Provenance{"test", {}, {dir / "mesh.h5"}});
  std::ofstream(dir / "materials.json") << R"({"membrane": {"E": 1.2e7, "nu": 0.4, "density": 1050},
      "rays": {"E": 3e8, "nu": 0.4, "density": 1100}})";
  std::ofstream(dir / "drive.json") << R"({"frequency_hz": 4.4})";
  auto synth = [&](const std::string& source) {
    const std::string cmd = std::string(FIN_SYNTH_EXE) + " --out-dir " + (dir / "out").string() +
                            " --motion-source fem " + source + " --fsi-mesh " + (dir / "mesh.h5").string() +
                            " --materials " + (dir / "materials.json").string() + " --root-drive " +
                            (dir / "drive.json").string() + " --periods 0.02 --width 32 --height 32 --supersample 1" +
                            " --vtk false --log-level error --threads 1 2> " + (dir / "err.txt").string();
    const int rc = std::system(cmd.c_str());
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  };
  ASSERT_EQ(synth("--fem " + (dir / "motion.h5").string()), 0);
  const auto truth = stage::read<stage::Truth>(dir / "out" / "truth.h5");
  EXPECT_EQ(truth.motion_source.value_or(""), "fem");
  const auto effects = nlohmann::json::parse(truth.effects.value_or("{}"));
  ASSERT_TRUE(effects.contains("structural"));
  EXPECT_EQ(effects["structural"][0]["name"], "active_stiffening");
  EXPECT_EQ(synth("--fsi " + (dir / "motion.h5").string()), 2);  // fsi.h5's flag with the fem source
}
