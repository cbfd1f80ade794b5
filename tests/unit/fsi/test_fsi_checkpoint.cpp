// Checkpoint / restart and failures of the coupled flow + flag run (tools/fsi/validation/
// fsi_checkpoint.hpp, turek_hron_fsi.hpp; issue 32 "Outputs" and "Bad input") on the tiny_ckpt FSI3 of
// test_turek_hron_fsi.cpp:
//   - 6 steps straight against 3 steps with checkpoints + a restart to step 6: fsi.h5 identical
//     bit for bit (flow, structure incl. accelerations, IQN-ILS's reused columns, the frames), and
//     so are their ParaView series (structure .vtp, flow .vtr; read back with VTK's readers);
//   - a restart with other options is refused naming the option; --restart-new-coupling may change
//     the acceleration;
//   - a coupling that blows up after a restart (omega = 1 at rho_s / rho_f = 1) names the step and the
//     last good checkpoint, which stays as it was, and writes no fsi.h5; an absurd dt is a CFL
//     blow-up naming step 1.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <unistd.h>

#include "core/stage_files.hpp"
#include "core/vtk_compare.hpp"
#include "fsi/implicit_coupling.hpp"
#include "fsi/validation/turek_hron_fsi.hpp"

namespace finverse::fsi::validation {
namespace {

namespace fs = std::filesystem;

// The process id keeps tests that ctest runs side by side off each other's files (a shared
// reference JSON truncated by one test while another parsed it failed CI once).
fs::path scratch(const std::string& name) {
  return fs::temp_directory_path() / ("finverse_test_fsi_ckpt_" + std::to_string(::getpid()) + "_" + name);
}

fs::path ckpt_reference_file() {
  const fs::path path = scratch("turek_hron.json");
  std::ofstream out(path);
  out << R"({"geometry": {"cylinder_centre": [0.2, 0.2], "cylinder_radius": 0.05, "flag_length": 0.35,
              "flag_thickness": 0.02, "point_A": [0.6, 0.2]}, "solid": {"nu_s": 0.4},
             "cases": {"FSI3": {"Ubar": 2.0, "rho_s": 1000, "E": 5.6e6,
                                "ux_A": [-2.69e-3, 2.53e-3], "ux_freq": 10.9, "uy_A": [1.48e-3, 34.38e-3],
                                "uy_freq": 5.3, "drag": [457.3, 22.66], "lift": [2.22, 149.78]}}})";
  return path;
}

TurekHronFsiOptions tiny_ckpt(int steps) {
  TurekHronFsiOptions o;
  o.reference = ckpt_reference_file();
  o.case_name = "FSI3";
  o.cells_per_diameter = 10;
  o.channel_length = 1.0;
  o.circle_vertices = 64;
  o.mesh = {6, 1, 3.0};
  o.dt = 2e-3;
  o.t_end = steps * o.dt;
  o.ramp_time = 0.1;
  o.acceleration = "iqn-ils";
  o.absolute_tolerance = 1e-12;
  o.divergence_iterations = 4;
  o.accept_at_cap = false;
  return o;
}

template <class T>
bool same_bits_ckpt(const NdArray<T>& a, const NdArray<T>& b) {
  return a.shape == b.shape && std::memcmp(a.data.data(), b.data.data(), sizeof(T) * a.data.size()) == 0;
}

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(FsiCheckpoint, RestartWritesTheUninterruptedRunsFileBitForBit) {
  fs::remove_all(scratch("pv_straight"));
  fs::remove_all(scratch("pv_restarted"));
  TurekHronFsiOptions o = tiny_ckpt(6);
  o.fsi_h5 = scratch("straight.h5");
  o.paraview_dir = scratch("pv_straight");
  o.paraview_every = 2;
  const TurekHronFsiRun straight = run_turek_hron_fsi(o);

  TurekHronFsiOptions first = tiny_ckpt(3);
  first.checkpoint = scratch("ckpt.h5");
  first.checkpoint_every = 2;
  first.paraview_dir = scratch("pv_restarted");
  first.paraview_every = 2;
  (void)run_turek_hron_fsi(first);
  ASSERT_TRUE(fs::exists(first.checkpoint));
  TurekHronFsiOptions second = tiny_ckpt(6);
  second.restart = first.checkpoint;
  second.fsi_h5 = scratch("restarted.h5");
  second.paraview_dir = first.paraview_dir;
  second.paraview_every = 2;
  const TurekHronFsiRun restarted = run_turek_hron_fsi(second);
  EXPECT_EQ(restarted.first_step, 3);

  const auto a = stage::read<stage::Fsi>(o.fsi_h5), b = stage::read<stage::Fsi>(second.fsi_h5);
  ASSERT_EQ(a.time.size(), 6u);
  EXPECT_TRUE(same_bits_ckpt(a.time, b.time));
  EXPECT_TRUE(same_bits_ckpt(a.points, b.points));
  EXPECT_TRUE(same_bits_ckpt(a.velocity, b.velocity));
  EXPECT_TRUE(same_bits_ckpt(a.nodal_force, b.nodal_force));
  EXPECT_TRUE(same_bits_ckpt(a.force_total, b.force_total));
  EXPECT_TRUE(same_bits_ckpt(a.coupling_iterations, b.coupling_iterations));
  EXPECT_TRUE(same_bits_ckpt(a.coupling_residual, b.coupling_residual));
  EXPECT_TRUE(same_bits_ckpt(a.coupling_relative_residual, b.coupling_relative_residual));
  EXPECT_TRUE(same_bits_ckpt(a.probe_displacement, b.probe_displacement));
  EXPECT_EQ(straight.uy_a, restarted.uy_a);
  ASSERT_EQ(straight.records.size(), restarted.records.size());
  for (std::size_t k = 0; k < straight.records.size(); ++k)
    EXPECT_EQ(straight.records[k].interface_work, restarted.records[k].interface_work) << "step " << k + 1;

  // ParaView: frames at steps 2, 4, 6 in both series, equal to the last bit.
  for (const char* series : {"structure", "flow"}) {
    EXPECT_TRUE(fs::exists(o.paraview_dir / (std::string(series) + ".pvd"))) << series;
    int frames = 0;
    for (const auto& e : fs::directory_iterator(o.paraview_dir / series)) {
      ++frames;
      const fs::path other = second.paraview_dir / series / e.path().filename();
      ASSERT_TRUE(fs::exists(other)) << other;
      for (const Comparison& c : compare_vtk(e.path(), other, Tolerances()))
        EXPECT_TRUE(c.ok) << e.path().filename() << " " << c.object << ": " << c.status << " " << c.detail;
    }
    EXPECT_EQ(frames, 3) << series;
  }
}

TEST(FsiCheckpoint, RestartWithOtherOptionsIsRefusedNamingTheOption) {
  TurekHronFsiOptions first = tiny_ckpt(2);
  first.checkpoint = scratch("options.h5");
  (void)run_turek_hron_fsi(first);
  TurekHronFsiOptions other = tiny_ckpt(3);
  other.restart = first.checkpoint;
  other.spectral_radius = 0.5;
  try {
    (void)run_turek_hron_fsi(other);
    FAIL() << "expected a refusal";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("spectral_radius"), std::string::npos) << e.what();
  }
  other = tiny_ckpt(3);
  other.restart = first.checkpoint;
  other.acceleration = "aitken";
  EXPECT_THROW((void)run_turek_hron_fsi(other), Error);
  other.restart_new_coupling = true;  // a new acceleration from the checkpoint (the benchmark's use)
  const TurekHronFsiRun run = run_turek_hron_fsi(other);
  EXPECT_EQ(run.statistics.size(), 3u);
  other = tiny_ckpt(2);  // t_end not beyond the checkpoint
  other.restart = first.checkpoint;
  EXPECT_THROW((void)run_turek_hron_fsi(other), Error);
}

TEST(FsiCheckpoint, DivergenceAfterRestartKeepsTheLastGoodCheckpoint) {
  TurekHronFsiOptions first = tiny_ckpt(2);
  first.checkpoint = scratch("kept.h5");
  (void)run_turek_hron_fsi(first);
  const std::string before = bytes(first.checkpoint);
  TurekHronFsiOptions bad = tiny_ckpt(4);
  bad.restart = first.checkpoint;
  bad.restart_new_coupling = true;
  bad.acceleration = "constant";  // omega = 1 at rho_s / rho_f = 1: the added-mass instability
  bad.omega = 1.0;
  bad.checkpoint = first.checkpoint;
  bad.checkpoint_every = 1;
  bad.fsi_h5 = scratch("never.h5");
  fs::remove(bad.fsi_h5);
  try {
    (void)run_turek_hron_fsi(bad);
    FAIL() << "expected the coupling to diverge";
  } catch (const Error& e) {  // the iterates reach the flow's CFL guard before 4 growing residuals
    const std::string what = e.what();
    std::printf("omega = 1 after a restart: %s\n", what.c_str());
    EXPECT_NE(what.find("step 3"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    EXPECT_NE(what.find("last good checkpoint " + first.checkpoint.string() + " (step 2)"), std::string::npos)
        << what;
  }
  EXPECT_EQ(bytes(first.checkpoint), before);
  EXPECT_FALSE(fs::exists(bad.fsi_h5));
}

TEST(FsiCheckpoint, AbsurdTimeStepIsACflBlowUpNamingTheStep) {
  TurekHronFsiOptions o = tiny_ckpt(1);
  o.dt = 0.05;  // CFL about 10 on h = D / 10 at half the inflow
  o.t_end = o.dt;
  o.fsi_h5 = scratch("cfl.h5");
  fs::remove(o.fsi_h5);
  try {
    (void)run_turek_hron_fsi(o);
    FAIL() << "expected a CFL blow-up";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("fsi: step 1"), std::string::npos) << what;
    EXPECT_NE(what.find("CFL"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  EXPECT_FALSE(fs::exists(o.fsi_h5));
}

}  // namespace
}  // namespace finverse::fsi::validation
