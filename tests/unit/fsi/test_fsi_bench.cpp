// fsi_bench (results/bench/fsi.json): the FSI3 step-cost ratio from the runs' summaries, and the
// fin's pair (issue 50): fin-fsi fin's summary (a flat object) against fin-cfd fin's on the same
// grid, graded <= 3; a pair on different grids, or half a pair, is an error naming the file.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "core/error.hpp"
#include "fsi/validation/fsi_bench.hpp"
#include "../scratch_dir.hpp"

namespace finverse::fsi::validation {
namespace {

std::filesystem::path coupling_run(const test::ScratchDir& dir, const std::string& name, double seconds_per_step) {
  Summary s("validation", name, "a coupled restart");
  s.info("coupling_iterations_mean_this_run", 3.0);
  s.info("coupling_iterations_max_this_run", 5.0);
  s.info("steps_this_run", 800.0);
  s.info("steps_at_cap", 0.0);
  s.info("wall_seconds_per_step", seconds_per_step, "s");
  const auto path = dir / (name + ".json");
  s.write(path);
  return path;
}

std::filesystem::path fin_coupled(const test::ScratchDir& dir, double cells, double wall_seconds) {
  const auto path = dir / "fin_coupled.json";
  std::ofstream(path) << nlohmann::json{{"wall_seconds", wall_seconds}, {"steps", 100}, {"cells", cells},
                                        {"coupling_iterations_mean", 2.5}}
                             .dump();
  return path;
}

std::filesystem::path fin_flow(const test::ScratchDir& dir, double cells, double solver_seconds) {
  Summary s("validation", "fin", "fin-cfd fin");
  s.info("cells", cells);
  s.info("steps", 50.0);
  s.info("solver_seconds", solver_seconds, "s");
  const auto path = dir / "fin_flow.json";
  s.write(path);
  return path;
}

FsiBenchInputs turek_hron_runs(const test::ScratchDir& dir) {
  FsiBenchInputs in;
  in.fsi3_iqn_ils = coupling_run(dir, "fsi3_iqn", 0.04);
  in.fsi3_aitken = coupling_run(dir, "fsi3_aitken", 0.1);
  in.fsi2_iqn_ils = coupling_run(dir, "fsi2_iqn", 0.03);
  in.fsi2_aitken = coupling_run(dir, "fsi2_aitken", 0.08);
  in.fsi3_rigid = coupling_run(dir, "fsi3_rigid", 0.01);
  return in;
}

double value(const Summary& s, const std::string& name) {
  for (const Metric& m : s.metrics())
    if (m.name == name) return m.value;
  ADD_FAILURE() << "no metric " << name;
  return 0;
}

TEST(FsiBench, TheFinsCoupledStepIsGradedAgainstItsFlowStep) {
  test::ScratchDir dir;
  FsiBenchInputs in = turek_hron_runs(dir);
  const Summary without = fsi_bench(in);
  EXPECT_DOUBLE_EQ(value(without, "fsi3_step_cost_ratio"), 4.0);
  in.fin_coupled = fin_coupled(dir, 1000, 20.0);  // 0.2 s per coupled step
  in.fin_flow = fin_flow(dir, 1000, 2.0);         // 0.04 s per flow step
  const Summary with = fsi_bench(in);
  EXPECT_DOUBLE_EQ(value(with, "fin_step_cost_ratio"), 5.0);
  EXPECT_FALSE(with.pass());
  in.fin_coupled = fin_coupled(dir, 1000, 5.0);  // 0.05 s: 1.25 flow steps
  EXPECT_DOUBLE_EQ(value(fsi_bench(in), "fin_step_cost_ratio"), 1.25);
}

TEST(FsiBench, APairOnDifferentGridsOrHalfAPairIsAnError) {
  test::ScratchDir dir;
  FsiBenchInputs in = turek_hron_runs(dir);
  in.fin_coupled = fin_coupled(dir, 1000, 20.0);
  in.fin_flow = fin_flow(dir, 2000, 2.0);
  try {
    (void)fsi_bench(in);
    FAIL() << "different grids accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not the same grid"), std::string::npos) << e.what();
  }
  in.fin_flow.clear();
  EXPECT_THROW((void)fsi_bench(in), Error);
}

}  // namespace
}  // namespace finverse::fsi::validation
