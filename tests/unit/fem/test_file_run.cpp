// File-driven structural runs (fin-fem run): a small fin-like strip written as mesh.h5 /
// loads.h5 / motion.h5 from the stage structs, run end to end, checked against the in-memory
// solvers; and every kind of bad input ends in a one-line error naming the cause with no output
// file left behind.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <unistd.h>

#include <gtest/gtest.h>

#include "core/stage_files.hpp"
#include "../strip_fin.hpp"
#include "fem/errors.hpp"
#include "fem/io/file_run.hpp"
#include "fem/io/fin_model.hpp"
#include "fem/io/material_spec.hpp"
#include "fem/io/periodic_motion.hpp"
#include "fem/structural_run.hpp"

using namespace finverse;
using namespace finverse::fem;
namespace fs = std::filesystem;

namespace {
using namespace finverse::test::strip;

const char* kMaterials = R"({"membrane": {"E": 2e7, "nu": 0.45, "density": 1050},
                             "rays": {"E": 1e9, "nu": 0.3, "density": 1100},
                             "ray": {"2": {"E": 5e8}},
                             "distal": {"s_from": 0.5, "E_factor": 0.5}})";

class FileRun : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("finverse_file_run_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    mesh_ = strip_mesh();
    stage::write(dir_ / "mesh.h5", mesh_, Provenance{"test", {}, {}});
    auto loads = ramp_loads(2e-3, 5, 0.04);
    stage::write(dir_ / "loads.h5", loads, Provenance{"test", {}, {}});
    write_text("materials.json", kMaterials);
    o_.mesh = dir_ / "mesh.h5";
    o_.materials = dir_ / "materials.json";
    o_.loads = dir_ / "loads.h5";
    o_.out = dir_ / "response.h5";
    o_.ramp = 0.02;
    o_.run.ramp_steps = 4;
  }
  void TearDown() override { fs::remove_all(dir_); }
  void write_text(const std::string& name, const std::string& text) { std::ofstream(dir_ / name) << text; }

  // Runs and expects exception E whose message contains `needle`, and no output file.
  template <class E>
  void expect_failure(const std::string& needle) {
    try {
      io::run_from_files(o_, {});
      ADD_FAILURE() << "no exception, expected one mentioning '" << needle << "'";
    } catch (const E& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(needle), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << "not one line: " << what;
    }
    EXPECT_FALSE(fs::exists(o_.out));
    EXPECT_FALSE(fs::exists(fs::path(o_.out.string() + ".tmp")));
  }

  fs::path dir_;
  stage::Mesh mesh_;
  io::FileRunOptions o_;
};
}  // namespace

TEST_F(FileRun, QuasiStaticRunMatchesTheInMemoryStaticSolution) {
  o_.run.analysis = Analysis::quasi_static;
  o_.pvd = dir_ / "response.pvd";
  const auto summary = io::run_from_files(o_, {});
  EXPECT_EQ(summary.frames, 5);
  ASSERT_TRUE(fs::exists(o_.out));
  EXPECT_TRUE(fs::exists(*o_.pvd));
  const auto response = stage::read<stage::Motion>(o_.out);
  ASSERT_EQ(response.points.dim(0), 5u);

  // Same model in memory, solved statically at every frame.
  io::FinModel fm = io::build_fin_model(mesh_, io::read_material_spec(o_.materials));
  io::apply_loads(fm.model, stage::read<stage::Loads>(*o_.loads), o_.ramp, "loads.h5");
  RunOptions ro;
  ro.analysis = Analysis::static_equilibrium;
  ro.start_time = -o_.ramp;
  ro.ramp_steps = 4;
  const auto frames = run_structural_analysis(fm.model, ro, {0.0, 0.01, 0.02, 0.03, 0.04});
  const int tip = node(nx, nz);
  const Vec3 x_file(response.points(4, tip, 0), response.points(4, tip, 1), response.points(4, tip, 2));
  EXPECT_LT((x_file - frames.back().state.position[tip]).norm(), 1e-9 * chord);
  EXPECT_GT(std::abs(x_file.y()), 0.02 * chord);  // it did bend
  // Root held.
  EXPECT_DOUBLE_EQ(response.points(4, node(0, 1), 1), 0.0);
}

TEST_F(FileRun, DynamicRunFollowsThePrescribedRootHeave) {
  // Root heave y = A sin(2 pi f t) from motion.h5, no loads.
  stage::Motion mo;
  const size_t nf = 9, nv = (nx + 1) * (nz + 1);
  const double A = 2e-3, f = 10;
  mo.time = NdArray<double>({nf});
  mo.points = NdArray<double>({nf, nv, 3});
  for (size_t k = 0; k < nf; ++k) {
    const double t = 0.005 * k;
    mo.time.data[k] = t;
    for (size_t i = 0; i < nv; ++i) {
      for (int d = 0; d < 3; ++d) mo.points(k, i, d) = mesh_.points(i, d);
      mo.points(k, i, 1) += A * std::sin(2 * std::numbers::pi * f * t);
    }
  }
  stage::write(dir_ / "motion.h5", mo, Provenance{"test", {}, {}});
  o_.loads.reset();
  o_.motion = dir_ / "motion.h5";
  o_.run.analysis = Analysis::dynamic;
  o_.run.substeps = 5;
  o_.run.dynamic_options.spectral_radius = 0.8;  // damps the kink of the ramp's start
  o_.ramp = 0.01;
  io::run_from_files(o_, {});
  const auto r = stage::read<stage::Motion>(o_.out);
  ASSERT_EQ(r.velocity.dim(0), nf);
  for (size_t k = 0; k < nf; ++k)
    EXPECT_NEAR(r.points(k, node(0, 1), 1), mo.points(k, node(0, 1), 1), 1e-12) << "frame " << k;
  EXPECT_GT(std::abs(r.points(nf - 1, node(nx, 1), 1)), 1e-5);  // the free edge moved
}

TEST_F(FileRun, NonPhysicalMaterialsAreRejected) {
  write_text("materials.json", R"({"membrane": {"E": 0, "nu": 0.45, "density": 1050},
                                   "rays": {"E": 1e9, "nu": 0.3, "density": 1100}})");
  expect_failure<InvalidInput>("membrane: Young's modulus E = 0");
  write_text("materials.json", R"({"membrane": {"E": 1e7, "nu": 0.5, "density": 1050},
                                   "rays": {"E": 1e9, "nu": 0.3, "density": 1100}})");
  expect_failure<InvalidInput>("Poisson ratio nu = 0.5");
  write_text("materials.json", R"({"membrane": {"E": 1e7, "nu": 0.4, "density": 1050},
                                   "rays": {"E": 1e9, "nu": 0.3, "density": 1100},
                                   "ray": {"3": {"density": 0}}})");
  expect_failure<InvalidInput>("ray.3: density = 0");
  write_text("materials.json", R"({"membrane": {"E": 1e7, "nu": 0.4, "density": 1050},
                                   "rays": {"E": 1e9, "nu": 0.3, "density": 1100, "G": 3}})");
  expect_failure<InvalidInput>("rays.G: unknown key");
}

TEST_F(FileRun, NanLoadIsRejected) {
  auto loads = ramp_loads(2e-3, 5, 0.04);
  loads.nodal_force(2, 7, 1) = std::nan("");
  // The contract refuses to write it; a file written by something else is refused on reading.
  EXPECT_THROW(stage::write(dir_ / "nan_loads.h5", loads, Provenance{"test", {}, {}}), finverse::Error);
  EXPECT_FALSE(fs::exists(dir_ / "nan_loads.h5"));
  // The library path names node and time.
  io::FinModel fm = io::build_fin_model(mesh_, io::read_material_spec(o_.materials));
  try {
    io::apply_loads(fm.model, loads, 0.01, "loads.h5");
    ADD_FAILURE() << "NaN load accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("node 7 fy"), std::string::npos) << e.what();
  }
}

TEST_F(FileRun, UnconstrainedModelIsRejected) {
  mesh_.root_nodes = NdArray<std::int32_t>({0});
  stage::write(dir_ / "mesh.h5", mesh_, Provenance{"test", {}, {}});
  expect_failure<InvalidInput>("/root_nodes is empty");
}

TEST_F(FileRun, DisconnectedPartGivesASingularStiffness) {
  // A ray segment floating free of the clamped strip: a rigid-body mode.
  const size_t nv = mesh_.points.dim(0);
  mesh_.points.shape[0] += 2;
  mesh_.points.data.insert(mesh_.points.data.end(), {0.0, 0.01, 0.0, 0.02, 0.01, 0.0});
  mesh_.beam_elements.shape[0] += 1;
  mesh_.beam_elements.data.insert(mesh_.beam_elements.data.end(), {int(nv), int(nv + 1)});
  for (auto* a : {&mesh_.beam_ray}) a->shape[0] += 1, a->data.push_back(9);
  for (auto* a : {&mesh_.beam_s, &mesh_.beam_thickness, &mesh_.beam_width}) {
    a->shape[0] += 1;
    a->data.insert(a->data.end(), {a == &mesh_.beam_s ? 0.0 : 1e-3, a == &mesh_.beam_s ? 1.0 : 1e-3});
  }
  mesh_.ibm_points = mesh_.points;
  mesh_.ibm_source_node.shape[0] += 2;
  mesh_.ibm_source_node.data.insert(mesh_.ibm_source_node.data.end(), {int(nv), int(nv + 1)});
  mesh_.ibm_offset_sign.shape[0] += 2;
  mesh_.ibm_offset_sign.data.insert(mesh_.ibm_offset_sign.data.end(), {0, 0});
  stage::write(dir_ / "mesh.h5", mesh_, Provenance{"test", {}, {}});
  auto loads = stage::read<stage::Loads>(*o_.loads);
  loads.nodal_force.shape[1] += 2;
  loads.nodal_force.data.assign(loads.nodal_force.shape[0] * loads.nodal_force.shape[1] * 3, 1e-4);
  stage::write(dir_ / "loads.h5", loads, Provenance{"test", {}, {}});
  expect_failure<SingularMatrix>("singular");
}

TEST_F(FileRun, NewtonThatDoesNotConvergeIsReported) {
  o_.run.static_options.max_iterations = 1;  // no nonlinear step converges in one iteration
  o_.run.analysis = Analysis::static_equilibrium;
  expect_failure<NotConverged>("did not converge");
}

TEST_F(FileRun, DynamicStepThatDoesNotConvergeNamesItsFrame) {
  o_.run.analysis = Analysis::dynamic;
  o_.run.substeps = 3;
  o_.run.dynamic_options.max_iterations = 1;
  expect_failure<NotConverged>("in the ramp before frame 0 at 3 sub-steps per frame: generalized-alpha Newton");
}

TEST_F(FileRun, ForceOnARootNodeIsReportedNotDroppedSilently) {
  // ramp_loads pushes every node, the clamped root ones included: apply_loads measures what goes
  // into the support, and the file run says so once.
  io::FinModel fm = io::build_fin_model(mesh_, io::read_material_spec(o_.materials));
  const double dropped = io::apply_loads(fm.model, stage::read<stage::Loads>(*o_.loads), o_.ramp, "loads.h5");
  EXPECT_DOUBLE_EQ(dropped, 2e-3);
  o_.run.analysis = Analysis::quasi_static;
  ::testing::internal::CaptureStderr();
  io::run_from_files(o_, {});
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("prescribed root nodes go into the support"), std::string::npos) << err;
}

TEST_F(FileRun, StructuralLoadCaseNeedsNoFlowFields) {
  // The same forces as nodal_loads.h5 (times and nodal forces only) give the same response as
  // the loads.h5 of a flow solver.
  o_.run.analysis = Analysis::quasi_static;
  io::run_from_files(o_, {});
  const auto with_flow = stage::read<stage::Motion>(o_.out);
  const auto full = stage::read<stage::Loads>(*o_.loads);
  stage::NodalLoads nodal;
  nodal.time = full.time;
  nodal.nodal_force = full.nodal_force;
  o_.loads = dir_ / "nodal_loads.h5";
  stage::write(*o_.loads, nodal, Provenance{"test", {}, {}});
  o_.out = dir_ / "response_nodal.h5";
  io::run_from_files(o_, {});
  EXPECT_EQ(stage::read<stage::Motion>(o_.out).points, with_flow.points);
}

TEST(PeriodicMotion, RepeatsWholePeriodsAndKeepsTheSeamOnce) {
  // Three frames over one period T = 0.3 (t = 0, 0.1, 0.2), covering [0.25, 0.65].
  stage::Motion m;
  m.period = 0.3;
  m.time = NdArray<double>({3}, {0.0, 0.1, 0.2});
  m.points = NdArray<double>({3, 1, 3}, {0, 0, 0, 1, 0, 0, 2, 0, 0});
  EXPECT_FALSE(io::needs_periodic_extension(m, 0.0, 0.2));
  EXPECT_TRUE(io::needs_periodic_extension(m, 0.25, 0.65));
  const stage::Motion e = io::periodic_extension(m, 0.25, 0.65);
  ASSERT_GE(e.time.data.size(), 5u);
  EXPECT_LE(e.time.data.front(), 0.25);
  EXPECT_GE(e.time.data.back(), 0.65);
  for (size_t k = 0; k < e.time.data.size(); ++k) {
    // The frame at t is the original frame at t mod T.
    const double phase = std::fmod(e.time.data[k] + 1e-12, 0.3);
    EXPECT_NEAR(e.points(k, 0, 0), std::round(phase / 0.1), 1e-12) << "t = " << e.time.data[k];
    if (k > 0) {
      EXPECT_GT(e.time.data[k], e.time.data[k - 1]);
    }
  }
  stage::Motion aperiodic = m;
  aperiodic.period.reset();
  EXPECT_FALSE(io::needs_periodic_extension(aperiodic, 0.25, 0.65));
  EXPECT_THROW(io::periodic_extension(aperiodic, 0.25, 0.65), InvalidInput);
}

TEST_F(FileRun, EffectsChangeTheResponseAndAreRecorded) {
  o_.run.analysis = Analysis::quasi_static;
  io::run_from_files(o_, {});
  const auto plain = stage::read<stage::Motion>(o_.out);
  EXPECT_FALSE(plain.effects.has_value());
  const int tip = node(nx, nz);
  // Softer distal rays (EI e^{-2 s/L}) let the loaded tip go further.
  write_text("effects.json", R"([{"name": "distal_softening", "rate": 2.0}])");
  o_.effects = dir_ / "effects.json";
  fs::remove(o_.out);
  io::run_from_files(o_, {});
  const auto soft = stage::read<stage::Motion>(o_.out);
  ASSERT_TRUE(soft.effects.has_value());
  EXPECT_EQ(nlohmann::json::parse(*soft.effects)[0]["name"], "distal_softening");
  EXPECT_GT(std::abs(soft.points(4, tip, 1)), 1.2 * std::abs(plain.points(4, tip, 1)));
  // Out of range: one line naming the file, effect and parameter; nothing written.
  write_text("effects.json", R"([{"name": "distal_softening", "rate": 9.0}])");
  fs::remove(o_.out);
  expect_failure<InvalidInput>("effects.json: effect distal_softening: rate = 9, expected -2 .. 5");
}

TEST_F(FileRun, AnalyticRootDriveMovesTheRootWithoutMotionFile) {
  mesh_.chord = chord;
  stage::write(dir_ / "mesh.h5", mesh_, Provenance{"test", {}, {}});
  write_text("drive.json", R"({"heave_over_chord": 0.05, "pitch_center_deg": 2, "pitch_edge_deg": 4,
                               "frequency_hz": 10, "ramp_periods": 0.5})");
  o_.loads.reset();
  o_.root_drive = dir_ / "drive.json";
  o_.periods = 0.5;
  o_.frames_per_period = 4;
  o_.run.analysis = Analysis::quasi_static;
  EXPECT_EQ(io::run_from_files(o_, {}).frames, 3);
  const auto r = stage::read<stage::Motion>(o_.out);
  ASSERT_TRUE(r.period.has_value());
  EXPECT_NEAR(*r.period, 0.1, 1e-15);
  // Frames from the first whole period after the ramp: t = 0.1, 0.125, 0.15; the root heaves
  // y = h0 sin(2 pi f t) (no pitch displacement at a node turning about itself).
  for (std::size_t k = 0; k < 3; ++k) {
    const double t = 0.1 + 0.025 * static_cast<double>(k);
    EXPECT_NEAR(r.time(k), t, 1e-12);
    EXPECT_NEAR(r.points(k, node(0, 1), 1), 0.05 * chord * std::sin(2 * std::numbers::pi * 10 * t), 1e-12);
  }
  fs::rename(o_.out, dir_ / "motion_copy.h5");  // a motion as well as the drive: refused
  o_.motion = dir_ / "motion_copy.h5";
  expect_failure<InvalidInput>("give --motion or --root-drive, not both");
}
