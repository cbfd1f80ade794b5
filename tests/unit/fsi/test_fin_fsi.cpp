// Tests of the fin's coupled run (fsi/fin_fsi_run.hpp) on a small synthetic fin (4 x 4 shell cells,
// three rays, c = 1 cm) in a coarse short flow, driven by a fast, small root drive (a few steps):
//   - the run completes; fsi.h5's points are [frames, mesh nodes, 3] in the mesh's node order and
//     the root nodes sit exactly where the drive puts them (heave, pitch about z through the root);
//   - the coefficients are the total force over 0.5 rho U^2 A with A the mid-surface area;
//   - driven instead by a tracked motion.h5 of that drive (per-ray root rotation, smooth start,
//     periodic tiling), the root nodes sit at the tracked positions at every output frame;
//   - candidate effects reach the structure and are recorded in fsi.h5;
//   - bad input (no drive, or both a drive and a motion) is refused with finverse::Error.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <filesystem>
#include <string>

#include "../scratch_dir.hpp"
#include "core/error.hpp"
#include "fem/io/root_drive_file.hpp"
#include "fem/io/fin_model.hpp"
#include "fsi/fin_frequency_check.hpp"
#include "fsi/fin_fsi_run.hpp"

namespace finverse::fsi {
namespace {

constexpr int kN = 4;  // cells per side
constexpr double kC = 0.01;

int node(int i, int k) { return k * (kN + 1) + i; }

stage::Mesh small_fin() {
  stage::Mesh m;
  const std::size_t nv = (kN + 1) * (kN + 1);
  m.points = NdArray<double>({nv, 3});
  for (int k = 0; k <= kN; ++k)
    for (int i = 0; i <= kN; ++i) {
      m.points(node(i, k), 0) = kC * i / kN;
      m.points(node(i, k), 2) = kC * (0.5 - static_cast<double>(k) / kN);  // k = 0 dorsal (+z)
    }
  std::vector<std::int32_t> tri;
  for (int k = 0; k < kN; ++k)
    for (int i = 0; i < kN; ++i) {
      const int a = node(i, k), b = node(i + 1, k), c = node(i + 1, k + 1), d = node(i, k + 1);
      tri.insert(tri.end(), {a, c, b, a, d, c});
    }
  const std::size_t nt = tri.size() / 3;
  m.triangles = NdArray<std::int32_t>({nt, 3}, tri);
  m.shell_thickness = NdArray<double>({nt}, std::vector<double>(nt, 2e-4));
  m.shell_region = NdArray<std::int32_t>({nt}, std::vector<std::int32_t>(nt, 0));
  std::vector<std::int32_t> be, br;
  std::vector<double> bs, bt, bw;
  for (int r = 0; r < 3; ++r)
    for (int i = 0; i < kN; ++i) {
      be.insert(be.end(), {node(i, 2 * r), node(i + 1, 2 * r)});
      br.push_back(r + 1);
      bs.insert(bs.end(), {static_cast<double>(i) / kN, static_cast<double>(i + 1) / kN});
      bt.insert(bt.end(), {4e-4, 4e-4});
      bw.insert(bw.end(), {4e-4, 4e-4});
    }
  const std::size_t nb = br.size();
  m.beam_elements = NdArray<std::int32_t>({nb, 2}, be);
  m.beam_ray = NdArray<std::int32_t>({nb}, br);
  m.beam_s = NdArray<double>({nb, 2}, bs);
  m.beam_thickness = NdArray<double>({nb, 2}, bt);
  m.beam_width = NdArray<double>({nb, 2}, bw);
  std::vector<std::int32_t> root;
  for (int k = 0; k <= kN; ++k) root.push_back(node(0, k));
  m.root_nodes = NdArray<std::int32_t>({root.size()}, root);
  m.chord = kC;
  return m;
}

FinFsiInputs inputs() {
  FinFsiInputs in;
  in.mesh = small_fin();
  in.materials = fem::io::parse_material_spec(
      {{"membrane", {{"E", 1e7}, {"nu", 0.4}, {"density", 1050}}}, {"rays", {{"E", 1e9}, {"nu", 0.4}, {"density", 1100}}}},
      "test materials");
  in.drive = fem::io::parse_root_drive({{"heave_over_chord", 0.05},
                                        {"pitch_center_deg", 2},
                                        {"pitch_edge_deg", 4},
                                        {"frequency_hz", 20},
                                        {"ramp_periods", 0.5}},
                                       "test drive");
  return in;
}

FinFsiOptions options() {
  FinFsiOptions o;
  o.flow.cells_per_chord = 8;
  o.flow.upstream = 1;
  o.flow.downstream = 1.5;
  o.flow.lateral = 1;
  o.flow.spanwise = 1;
  o.flow.wake = 0.25;
  o.flow.stretch_ratio = 1.3;
  o.flow.cfl = 1.0;
  o.flow.periods = 1;
  o.flow.output_periods = 1;
  o.flow.output_interval = 1.0 / 20 / 4;  // T / 4
  o.spectral_radius = 0;  // the pipeline's settings (config fsi.flags)
  o.substeps = 2;
  return o;
}

TEST(FinFsi, SmallFinRunsAndTheRootFollowsTheDrive) {
  const FinFsiInputs in = inputs();
  const FinFsiResult r = run_fin_fsi(in, options());
  const stage::Fsi& f = r.fsi;
  const std::size_t nv = (kN + 1) * (kN + 1);
  ASSERT_EQ(f.points.rank(), 3u);
  EXPECT_EQ(f.points.dim(0), 4u);
  EXPECT_EQ(f.points.dim(1), nv);
  EXPECT_EQ(f.time.size(), 4u);
  EXPECT_NEAR(f.time.data.back(), 1.0 / 20, 1e-12);
  EXPECT_GE(r.iterations_mean, 1.0);
  // The drive, rebuilt: every root node at its heave, turned about z through itself (it stays).
  const fem::RootDrive drive = fem::io::make_root_drive(in.mesh, *in.drive, 20, kC, "mesh");
  for (std::size_t k = 0; k < f.time.size(); ++k)
    for (int kk = 0; kk <= kN; ++kk) {
      const auto n = static_cast<std::size_t>(node(0, kk));
      EXPECT_NEAR(f.points(k, n, 1), drive.heave(f.time(k)), 1e-12) << "frame " << k << " node " << n;
      EXPECT_NEAR(f.points(k, n, 0), 0.0, 1e-12);
    }
  // Coefficients: total force over 0.5 rho U^2 A, A = c^2 (the square mid-surface).
  const double q = 0.5 * 1000 * r.U * r.U * kC * kC;
  EXPECT_NEAR(*f.reference_area, kC * kC, 1e-15);
  for (std::size_t k = 0; k < f.time.size(); ++k) {
    EXPECT_NEAR(f.thrust(k), -f.force_total(k, 0) / q, 1e-12);
    EXPECT_TRUE(std::isfinite(f.thrust(k)));
  }
}

// motion.h5 of the rigid fin carried by the inputs' drive without its ramp (21 frames over one
// period, the last repeating the first: periodic).
stage::Motion tracked_motion(const FinFsiInputs& in) {
  const fem::RootDrive drive = fem::io::make_root_drive(in.mesh, fem::io::parse_root_drive({{"heave_over_chord", 0.05},
                                                                                              {"pitch_center_deg", 2},
                                                                                              {"pitch_edge_deg", 4},
                                                                                              {"frequency_hz", 20},
                                                                                              {"ramp_periods", 0}},
                                                                                             "drive"),
                                                        20, kC, "mesh");
  const double T = 1.0 / 20;
  const std::size_t nf = 21, nv = (kN + 1) * (kN + 1);
  stage::Motion m;
  m.period = T;
  m.time = NdArray<double>({nf});
  m.points = NdArray<double>({nf, nv, 3});
  for (std::size_t k = 0; k < nf; ++k) {
    m.time(k) = T * static_cast<double>(k) / 20;
    for (std::size_t i = 0; i < nv; ++i) {
      const Eigen::Vector3d p = drive.rigid_position(
          Eigen::Vector3d(in.mesh.points(i, 0), in.mesh.points(i, 1), in.mesh.points(i, 2)), m.time(k));
      for (int d = 0; d < 3; ++d) m.points(k, i, static_cast<std::size_t>(d)) = p(d);
    }
  }
  return m;
}

// The fin driven by its tracked root over the last half period, after half a period of smooth start.
FinFsiOptions tracked_options() {
  FinFsiOptions o = options();
  o.flow.output_interval = 0;  // the frames
  o.flow.periods = 1;
  o.flow.output_periods = 0.5;
  o.ramp_periods = 0.5;
  return o;
}

TEST(FinFsi, TrackedRootMotionDrivesTheFin) {
  // Per-ray root rotation, smooth start, periodic tiling: the root nodes sit at the tracked
  // positions at every output (the frames of the last half period).
  FinFsiInputs in = inputs();
  const stage::Motion m = tracked_motion(in);
  const double T = *m.period;
  in.drive.reset();
  in.motion = m;
  const FinFsiResult r = run_fin_fsi(in, tracked_options());
  const stage::Fsi& f = r.fsi;
  ASSERT_EQ(f.time.size(), 10u);
  for (std::size_t k = 0; k < f.time.size(); ++k) {
    EXPECT_NEAR(f.time(k), T * static_cast<double>(k + 1) / 20, 1e-12);
    for (int kk = 0; kk <= kN; ++kk) {
      const auto n = static_cast<std::size_t>(node(0, kk));
      EXPECT_NEAR(f.points(k, n, 1), m.points(k + 1, n, 1), 1e-12) << "frame " << k << " node " << n;
    }
  }
}

TEST(FinFsi, MotionHarmonicsTakeATrackingGlitchOutOfTheRootDrive) {
  // A one-frame glitch of the tracked root (0.005 c across the stream at frame 6; the default
  // case's reconstruction has 2 % c ones) moves the driven root by all of it; with the motion kept to its
  // first 3 harmonics the root passes within (2K + 1) / 20 of it (the least-squares fit's share of
  // one sample) and follows the clean drive elsewhere. A motion without a period is refused.
  FinFsiInputs in = inputs();
  const stage::Motion clean = tracked_motion(in);
  stage::Motion glitched = clean;
  const std::size_t nv = (kN + 1) * (kN + 1), kg = 6;  // an output frame (the outputs are frames 1..10)
  const double g = 0.005 * kC;
  for (std::size_t i = 0; i < nv; ++i) glitched.points(kg, i, 1) += g;
  in.drive.reset();
  in.motion = glitched;
  const auto root_error = [&](const FinFsiResult& r, std::size_t frame) {
    double worst = 0;
    for (int kk = 0; kk <= kN; ++kk) {
      const auto n = static_cast<std::size_t>(node(0, kk));
      worst = std::max(worst, std::abs(r.fsi.points(frame - 1, n, 1) - clean.points(frame, n, 1)));
    }
    return worst;
  };
  const FinFsiResult raw = run_fin_fsi(in, tracked_options());
  EXPECT_NEAR(root_error(raw, kg), g, 1e-12);
  FinFsiOptions o = tracked_options();
  o.motion_harmonics = 3;
  const FinFsiResult smooth = run_fin_fsi(in, o);
  EXPECT_LT(root_error(smooth, kg), 0.4 * g);
  EXPECT_LT(root_error(smooth, kg - 4), 0.1 * g);
  EXPECT_EQ(smooth.config["drive"]["motion_harmonics"], 3);
  in.motion->period.reset();
  EXPECT_THROW(run_fin_fsi(in, o), Error);
}

TEST(FinFsi, EffectsAreAppliedToTheStructureAndRecorded) {
  // One run (the physics of each effect is tested in tests/unit/fem/test_effects.cpp): structural
  // damping on the fin's structure, recorded in fsi.h5; an unknown effect is refused before any step.
  FinFsiInputs in = inputs();
  in.effects = nlohmann::json::parse(R"([{"name": "rayleigh_damping", "mass": 50}])");
  const FinFsiResult r = run_fin_fsi(in, options());
  ASSERT_TRUE(r.fsi.effects.has_value());
  const auto recorded = nlohmann::json::parse(*r.fsi.effects);
  EXPECT_EQ(recorded[0]["name"], "rayleigh_damping");
  EXPECT_EQ(recorded[0]["mass"], 50.0);
  for (std::size_t k = 0; k < r.fsi.time.size(); ++k) EXPECT_TRUE(std::isfinite(r.fsi.points(k, node(kN, 2), 1)));
  in.effects = nlohmann::json::parse(R"([{"name": "ray_stiffening"}])");
  EXPECT_THROW(run_fin_fsi(in, options()), Error);
}

TEST(FinFsi, RefusesNoDriveOrTwoDrives) {
  FinFsiInputs none = inputs();
  none.drive.reset();
  EXPECT_THROW(run_fin_fsi(none, options()), Error);
  FinFsiInputs both = inputs();
  both.motion = stage::Motion{};
  EXPECT_THROW(run_fin_fsi(both, options()), Error);
}

// The first natural frequency (fin_frequency_check.hpp): at rest and linear, so it grows as the
// square root of the moduli; in water it is the in-vacuo one over sqrt(1 + rho pi c / (4 m_s)).
TEST(FinFsi, FirstFrequencyScalesWithTheModuliAndTheAddedMass) {
  const FinFsiInputs in = inputs();
  fem::Model soft = fem::io::build_fin_model(in.mesh, in.materials, "small fin").model;
  fem::io::MaterialSpec stiffer = in.materials;
  stiffer.membrane.youngs_modulus *= 4;
  stiffer.rays.youngs_modulus *= 4;
  fem::Model stiff = fem::io::build_fin_model(in.mesh, stiffer, "small fin").model;
  const double area = kC * kC, flap = 20;
  const FinFrequencies a = fin_frequencies(soft, area, kC, 1000, flap);
  const FinFrequencies b = fin_frequencies(stiff, area, kC, 1000, flap);
  EXPECT_NEAR(b.vacuum_hz / a.vacuum_hz, 2.0, 1e-6);
  EXPECT_NEAR(a.mass_per_area, soft.total_mass() / area, 1e-12);
  EXPECT_NEAR(a.wet_hz, a.vacuum_hz / std::sqrt(1 + 1000 * std::numbers::pi * kC / 4 / a.mass_per_area), 1e-9);
  EXPECT_NEAR(a.ratio, a.wet_hz / flap, 1e-12);
  EXPECT_THROW(fin_frequencies(soft, 0, kC, 1000, flap), Error);
}

// Materials whose fin's first wet frequency is below --min-frequency-ratio times the flapping
// frequency are refused before any step, in one line naming the materials and the ratio.
TEST(FinFsi, RefusesAFinTooSoftForTheCoupledRun) {
  FinFsiInputs in = inputs();
  in.materials_name = "soft.json";
  FinFsiOptions o = options();
  o.min_frequency_ratio = 1e6;
  try {
    run_fin_fsi(in, o);
    FAIL() << "expected the soft fin to be refused";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("soft.json: the fin's first natural frequency in water"), std::string::npos) << what;
    EXPECT_NE(what.find("--min-frequency-ratio"), std::string::npos) << what;
  }
  o.min_frequency_ratio = 0.5;  // this fin is far above it: the run goes on and records the frequencies
  const FinFsiResult r = run_fin_fsi(in, o);
  EXPECT_GT(r.first_frequency_ratio, 0.5);
  EXPECT_GT(r.first_frequency_vacuum, r.first_frequency_wet);
  EXPECT_EQ(r.summary()["first_frequency_ratio"], r.first_frequency_ratio);
}

// The fin's run is the coupled run every case uses (coupled_run.hpp): a restart from the
// checkpoint of step 3 gives the uninterrupted run's fsi.h5 arrays bit for bit, for the closed body
// and for the sheet; ParaView series of the fin and the flow are written; a restart with other
// options, or from the last step's checkpoint, is refused.
TEST(FinFsi, RestartFromACheckpointContinuesBitForBit) {
  test::ScratchDir dir;
  for (const std::string surface : {"closed", "sheet"}) {
    const FinFsiInputs in = inputs();
    FinFsiOptions o = options();
    o.surface = surface;
    o.checkpoint = dir / (surface + ".h5");
    o.checkpoint_every = 1;
    // The progress line of a step comes after its checkpoint: keep step 3's.
    long seen = 0;
    o.progress = [&](const std::string& line) {
      if (line.find(" it, residual") != std::string::npos && ++seen == 3)
        std::filesystem::copy_file(o.checkpoint, dir / (surface + "_3.h5"),
                                   std::filesystem::copy_options::overwrite_existing);
    };
    const FinFsiResult whole = run_fin_fsi(in, o);
    ASSERT_GE(whole.steps, 5);
    FinFsiOptions resumed = options();
    resumed.surface = surface;
    resumed.restart = dir / (surface + "_3.h5");
    resumed.paraview_dir = dir / (surface + "_paraview");
    const FinFsiResult rest = run_fin_fsi(in, resumed);
    EXPECT_EQ(rest.fsi.time.data, whole.fsi.time.data) << surface;
    EXPECT_EQ(rest.fsi.points.data, whole.fsi.points.data) << surface;
    EXPECT_EQ(rest.fsi.nodal_force.data, whole.fsi.nodal_force.data) << surface;
    EXPECT_EQ(rest.fsi.thrust.data, whole.fsi.thrust.data) << surface;
    EXPECT_EQ(rest.ct_mean, whole.ct_mean) << surface;
    EXPECT_EQ(rest.iterations_mean, whole.iterations_mean) << surface;
    EXPECT_TRUE(std::filesystem::exists(resumed.paraview_dir / "structure.pvd")) << surface;
    EXPECT_TRUE(std::filesystem::exists(resumed.paraview_dir / "flow.pvd")) << surface;
    // The iteration settings may change on a restart (a failed run continued with other
    // numerics); the model and the step may not.
    FinFsiOptions looser = resumed;
    looser.tolerance = 2e-3;
    looser.structure_max_iterations = 60;
    looser.paraview_dir.clear();
    EXPECT_NO_THROW((void)run_fin_fsi(in, looser)) << surface;
    FinFsiOptions other = resumed;
    other.rayleigh_stiffness = 1e-4;
    try {
      (void)run_fin_fsi(in, other);
      ADD_FAILURE() << "a restart with another damping ran";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("rayleigh_stiffness"), std::string::npos) << e.what();
    }
    FinFsiOptions done = resumed;
    done.restart = o.checkpoint;  // written after the last step
    EXPECT_THROW((void)run_fin_fsi(in, done), Error);
  }
}

}  // namespace
}  // namespace finverse::fsi
