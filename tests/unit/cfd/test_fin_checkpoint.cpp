// Checkpoint and restart of fin-cfd's fin run (cfd/io/fin_flow_checkpoint.hpp) on the tiny heaving
// and pitching plate: a run interrupted after a checkpoint and restarted from it gives the loads
// history of the uninterrupted run bit for bit; a restart with another option or other inputs is
// refused naming the difference; an injected blow-up (NaN, CFL) ends the run with a one-line error
// naming the step and the last checkpoint, which stays readable and continues the run.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "cfd/io/fin_flow_case.hpp"
#include "cfd/validation/thin_plate_case.hpp"
#include "tiny_fin_case.hpp"
#include "core/error.hpp"

namespace finverse::cfd::io {
namespace {

namespace fs = std::filesystem;

using test::tiny_plate;

// 20 ms: four outputs 5 ms apart.
FinFlowOptions tiny_options() { return test::tiny_options(0.1); }

fs::path scratch(const std::string& name) {
  return fs::temp_directory_path() / ("finverse_fin_ckpt_" + std::to_string(::getpid()) + "_" + name + ".h5");
}

// Multiplies the solver's velocity (u^n and the face velocities) by `factor` through its state.
void scale_velocity(FlowSolver& s, double factor) {
  auto st = s.state();
  for (auto& a : st)
    if (a.name.rfind("u_", 0) == 0 || a.name.rfind("face_velocity_", 0) == 0)
      for (double& v : a.values) v *= factor;
  s.restore(st);
}

void expect_same(const NdArray<double>& a, const NdArray<double>& b, const char* what) {
  ASSERT_EQ(a.shape, b.shape) << what;
  for (std::size_t k = 0; k < a.data.size(); ++k) EXPECT_EQ(a.data[k], b.data[k]) << what << "[" << k << "]";
}

void expect_same(const stage::Loads& a, const stage::Loads& b) {
  expect_same(a.time, b.time, "time");
  expect_same(a.nodal_force, b.nodal_force, "nodal_force");
  expect_same(a.force_total, b.force_total, "force_total");
  expect_same(a.pressure_jump, b.pressure_jump, "pressure_jump");
  expect_same(a.thrust, b.thrust, "thrust");
  expect_same(a.lateral, b.lateral, "lateral");
  expect_same(a.vertical, b.vertical, "vertical");
}

// One uninterrupted run, then a run that writes a checkpoint at step `at` and is stopped right
// after step at + 1 (its checkpoint file is returned).
struct Interrupted {
  stage::Loads full;
  FinFlowStats full_stats;
  long at = 0;
  std::size_t cleared = 0;  // freshly cleared cells over the whole uninterrupted run
  fs::path checkpoint;
};

Interrupted interrupted_run(const FinInput& in, const FinFlowOptions& o, const std::string& name) {
  Interrupted r;
  FinCheckpointing count;
  count.after_step = [&](long, FlowSolver& s) { r.cleared += s.freshly_cleared().size(); };
  r.full = run_fin_flow(in, o, r.full_stats, {}, count);
  // Between outputs, past the first one, so the record so far is not empty.
  r.at = r.full_stats.steps / 2 + 1;
  r.checkpoint = scratch(name);
  FinCheckpointing ck;
  ck.every = r.at;
  ck.file = r.checkpoint;
  const long stop = r.at + 1;
  ck.after_step = [stop](long n, FlowSolver&) {
    if (n == stop) throw Error("interrupted");
  };
  FinFlowStats st;
  try {
    run_fin_flow(in, o, st, {}, ck);
    ADD_FAILURE() << "the interrupted run finished";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("interrupted"), std::string::npos) << e.what();
  }
  return r;
}

TEST(FinCheckpoint, RestartReproducesTheUninterruptedLoadsBitwise) {
  const FinInput in = tiny_plate();
  const FinFlowOptions o = tiny_options();
  const Interrupted r = interrupted_run(in, o, "restart");
  ASSERT_EQ(r.full.time.size(), 4u);
  ASSERT_GT(r.full_stats.steps, 4);
  EXPECT_GT(r.cleared, 0u);  // the moving body clears cells: their treatment is exercised
  ASSERT_TRUE(fs::exists(r.checkpoint));
  EXPECT_FALSE(fs::exists(r.checkpoint.string() + ".tmp"));

  FinCheckpointing ck;
  ck.restart = r.checkpoint;
  FinFlowStats st;
  long first_reported = 0;
  const auto progress = [&](long n, long, const StepStats&) {
    if (!first_reported) first_reported = n;
  };
  const stage::Loads again = run_fin_flow(in, o, st, progress, ck);
  EXPECT_EQ(st.first_step, r.at);
  EXPECT_EQ(first_reported, r.at + 1);
  EXPECT_EQ(st.steps, r.full_stats.steps);
  EXPECT_EQ(st.poisson_iterations, r.full_stats.poisson_iterations);
  EXPECT_EQ(st.max_cfl, r.full_stats.max_cfl);
  expect_same(again, r.full);
  fs::remove(r.checkpoint);
}

TEST(FinCheckpoint, ASheetRestartsBitwiseWithItsBandCorrection) {
  // The sheet's loads less the band's inertia (on by default) use the markers' acceleration over
  // the step, taken from the sheet's states at both ends: a restart needs nothing more.
  const FinInput in = tiny_plate();
  FinFlowOptions o = tiny_options();
  o.surface = "sheet";
  const Interrupted r = interrupted_run(in, o, "sheet_restart");
  ASSERT_TRUE(fs::exists(r.checkpoint));
  FinCheckpointing ck;
  ck.restart = r.checkpoint;
  FinFlowStats st;
  const stage::Loads again = run_fin_flow(in, o, st, {}, ck);
  EXPECT_EQ(st.first_step, r.at);
  expect_same(again, r.full);
  fs::remove(r.checkpoint);
}

TEST(FinCheckpoint, RestartWithOtherOptionsOrInputsIsRefused) {
  const FinInput in = tiny_plate();
  FinFlowOptions o = tiny_options();
  o.periods = 0.05;
  const Interrupted r = interrupted_run(in, o, "mismatch");
  const auto expect_refused = [&](const FinInput& input, const FinFlowOptions& opt, const std::string& needle) {
    FinCheckpointing ck;
    ck.restart = r.checkpoint;
    FinFlowStats st;
    try {
      run_fin_flow(input, opt, st, {}, ck);
      ADD_FAILURE() << "restart accepted; expected a refusal naming " << needle;
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(needle), std::string::npos) << what;
      EXPECT_NE(what.find(r.checkpoint.string()), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  };
  FinFlowOptions other = o;
  other.reynolds = 200;
  expect_refused(in, other, "--reynolds");
  other = o;
  other.cells_per_chord = 7;
  expect_refused(in, other, "--cells-per-chord");
  expect_refused(tiny_plate(0.25), o, "different inputs");
  // The blow-up guard changes no result: a run stopped by it may continue with another limit.
  other = o;
  other.cfl_limit = 3;
  FinCheckpointing ck;
  ck.restart = r.checkpoint;
  FinFlowStats st;
  expect_same(run_fin_flow(in, other, st, {}, ck), r.full);
  fs::remove(r.checkpoint);
}

TEST(FinCheckpoint, BlowUpNamesTheStepAndTheLastCheckpoint) {
  const FinInput in = tiny_plate();
  FinFlowOptions o = tiny_options();
  o.periods = 0.05;
  FinFlowStats full_stats;
  const stage::Loads full = run_fin_flow(in, o, full_stats);
  const long every = full_stats.steps / 2;
  ASSERT_GE(every, 2);
  struct Fault {
    double factor;
    const char* cause;
  };
  for (const Fault f : {Fault{std::numeric_limits<double>::quiet_NaN(), "not finite"}, Fault{1e3, "CFL number"}}) {
    SCOPED_TRACE(f.cause);
    const fs::path file = scratch("blowup");
    fs::remove(file);
    FinCheckpointing ck;
    ck.every = every;
    ck.file = file;
    ck.after_step = [&](long n, FlowSolver& s) {
      if (n == every + 1) scale_velocity(s, f.factor);
    };
    FinFlowStats st;
    try {
      run_fin_flow(in, o, st, {}, ck);
      ADD_FAILURE() << "no error for the injected fault";
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(f.cause), std::string::npos) << what;
      EXPECT_NE(what.find("step " + std::to_string(every + 2)), std::string::npos) << what;
      EXPECT_NE(what.find("last checkpoint: " + file.string() + " (step " + std::to_string(every) + ")"),
                std::string::npos)
          << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
    // The checkpoint from before the fault is intact: continuing from it completes the run.
    ASSERT_TRUE(fs::exists(file));
    FinCheckpointing resume;
    resume.restart = file;
    FinFlowStats st2;
    expect_same(run_fin_flow(in, o, st2, {}, resume), full);
    fs::remove(file);
  }
}

}  // namespace
}  // namespace finverse::cfd::io
