// Logging, progress reports and the shared command-line conventions.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>

#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/flag_ranges.hpp"
#include "core/log.hpp"
#include "test_util.hpp"

using namespace finverse;

TEST(Log, DurationsReadNaturally) {
  EXPECT_EQ(log::format_duration(12.34), "12.3s");
  EXPECT_EQ(log::format_duration(185), "3m05s");
  EXPECT_EQ(log::format_duration(3725), "1h02m");
  EXPECT_THROW(log::parse_level("loud"), Error);
  EXPECT_EQ(log::parse_level("warn"), log::Level::warn);
}

TEST(Log, ProgressReportsStepStatusAndEta) {
  testing::internal::CaptureStderr();
  log::set_level(log::Level::info);
  {
    log::Progress p("step", 100, 0.0);
    p.update(0, "t=0 s");
    p.update(50, "t=0.5 s  res=1e-6");
    p.finish("ok");
  }
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("step 50/100 (50%)  t=0.5 s  res=1e-6"), std::string::npos) << err;
  EXPECT_NE(err.find("ETA"), std::string::npos) << err;
  EXPECT_NE(err.find("step finished in"), std::string::npos) << err;
}

namespace {
int run_exe(const std::string& args, std::string* out = nullptr) {
  const auto tmp = std::filesystem::temp_directory_path() / ("finverse_cli_" + std::to_string(getpid()));
  const int status = std::system((std::string(FIN_DIFF_EXE) + " " + args + " > " + tmp.string() + " 2>&1").c_str());
  if (out) *out = test::slurp(tmp);
  std::filesystem::remove(tmp);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}
}  // namespace

TEST(Cli, VersionHelpAndBadFlags) {
  std::string out;
  EXPECT_EQ(run_exe("--version", &out), 0);
  EXPECT_NE(out.find("fin-diff finverse"), std::string::npos) << out;
  EXPECT_EQ(run_exe("--help", &out), 0);
  EXPECT_NE(out.find("--tolerances"), std::string::npos) << out;
  EXPECT_EQ(run_exe("a.h5 b.h5 --no-such-flag", &out), 2);
  EXPECT_NE(out.find("--no-such-flag"), std::string::npos) << out;
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << "one line: " << out;
  EXPECT_EQ(run_exe("a.h5 b.h5 --atol -1", &out), 2);
}

TEST(Cli, EffectiveConfigurationHoldsEveryOption) {
  CLI::App app{"t"};
  cli::Standard s(app, "t");
  double dt = 1e-3;
  int n = 0;
  app.add_option("--dt", dt)->capture_default_str();
  app.add_option("--steps", n);
  const char* argv[] = {"t", "--steps", "12", "--threads", "1"};
  app.parse(5, const_cast<char**>(argv));
  const auto j = cli::effective_config(app);
  EXPECT_EQ(j["steps"], "12");
  EXPECT_EQ(j["dt"], "0.001");
  EXPECT_EQ(j["threads"], "1");
  EXPECT_FALSE(j.contains("help"));
}

TEST(Cli, ConfigFileSetsOptions) {
  test::ScratchDir dir;
  std::ofstream(dir / "c.toml") << "steps = 7\n";
  CLI::App app{"t"};
  cli::Standard s(app, "t");
  int n = 0;
  app.add_option("--steps", n);
  const std::string cfg = (dir / "c.toml").string();
  const char* argv[] = {"t", "--config", cfg.c_str()};
  app.parse(3, const_cast<char**>(argv));
  EXPECT_EQ(n, 7);
}

// The flags' ranges (core/flag_ranges.hpp): NaN and infinities refused on any numeric flag, the
// table's signs on the flags it names, a flag it does not name left alone, and the error naming
// the flag, its range and the value.
TEST(Cli, FlagRangesRefuseNanAndWrongSigns) {
  auto parse = [](std::vector<std::string> args) {
    CLI::App app{"t"};
    cli::Standard s(app, "t");
    double max_edge = 0.04, phase = 0;
    int population = 0;
    app.add_option("--max-edge", max_edge);
    app.add_option("--population", population);
    app.add_option("--phase", phase);
    args.insert(args.begin(), "t");
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    app.parse(static_cast<int>(argv.size()), argv.data());
    cli::check_flag_ranges(app);
  };
  EXPECT_NO_THROW(parse({"--max-edge", "0.1", "--population", "0", "--phase", "-1.5"}));
  try {
    parse({"--max-edge", "-1"});
    ADD_FAILURE() << "--max-edge -1 accepted";
  } catch (const CLI::ValidationError& e) {
    EXPECT_NE(std::string(e.what()).find("--max-edge: expected a number > 0, got -1"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse({"--max-edge", "0"}), CLI::ValidationError);
  EXPECT_THROW(parse({"--phase", "nan"}), CLI::ValidationError);
  EXPECT_THROW(parse({"--phase", "-inf"}), CLI::ValidationError);
  EXPECT_THROW(parse({"--population", "-1"}), CLI::ValidationError);
  EXPECT_THROW(parse({"--threads", "-2"}), CLI::ValidationError);
  EXPECT_EQ(cli::flag_range("population").value_or(""), "a whole number >= 0");
  EXPECT_FALSE(cli::flag_range("phase").has_value());
}

TEST(Cli, RangesReadAsAPersonWritesThem) {
  EXPECT_EQ(
      cli::readable_ranges("--fps: Value -1 not in range 0.000000 to 179769313486231570814527423731704356798070567"
                           "525844996598917476803157260780028538760589558632766878171540458953514382464234321326"
                           "889464182768467546703537516986049910576551282076245490090389328944075868508455133942"
                           "304583236903222948165808559332123348274797826204144723168738177180919299881250404026"
                           "184124858368.000000"),
      "--fps: expected a number >= 0, got -1");
  EXPECT_EQ(cli::readable_ranges("--cells-per-diameter: Value 100000 not in range 4.000000 to 1000.000000"),
            "--cells-per-diameter: expected a number from 4 to 1000, got 100000");
  EXPECT_EQ(cli::readable_ranges("--x: something else"), "--x: something else");
}

// An MPI launcher's environment gives the rank and the job's size (issue 48); a plain run is rank
// 0 of 1. Ranks above 0 print nothing from cli::run, so a bad flag is said once.
TEST(Cli, MpiLaunchRankAndSizeFromTheEnvironment) {
  for (const char* v :
       {"OMPI_COMM_WORLD_RANK", "OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMIX_SIZE", "PMI_RANK", "PMI_SIZE"})
    ::unsetenv(v);
  EXPECT_EQ(finverse::cli::mpi_launch_rank(), 0);
  EXPECT_EQ(finverse::cli::mpi_launch_size(), 1);
  ::setenv("PMIX_RANK", "2", 1);
  ::setenv("PMIX_SIZE", "4", 1);
  EXPECT_EQ(finverse::cli::mpi_launch_rank(), 2);
  EXPECT_EQ(finverse::cli::mpi_launch_size(), 4);
  CLI::App app{"t"};
  finverse::cli::Standard standard(app, "t");
  int value = 0;
  app.add_option("--value", value)->required();
  char arg0[] = "t";
  char* argv[] = {arg0};
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(finverse::cli::run(app, standard, 1, argv, [] { return 0; }), finverse::kExitError);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");  // rank 2 stays silent; rank 0 says it
  // A tool that does not run on ranks is refused by every rank, rank 0 saying why in one line.
  ::setenv("PMIX_RANK", "0", 1);
  CLI::App plain{"t"};
  finverse::cli::Standard plain_standard(plain, "t");
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(finverse::cli::run(plain, plain_standard, 1, argv, [] { return 0; }), finverse::kExitError);
  const std::string said = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(said.find("t: error: started by an MPI launcher on 4 ranks, but t does not run on MPI ranks"),
            std::string::npos)
      << said;
  plain_standard.mpi = true;
  EXPECT_EQ(finverse::cli::run(plain, plain_standard, 1, argv, [] { return 0; }), finverse::kExitOk);
  // A stage that runs on ranks, built without MPI and started by a launcher: one line naming the
  // rebuild, exit 2 (apps/flow_ranks_launch.hpp calls this in such a build).
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(finverse::cli::run(plain, plain_standard, 1, argv,
                               [] {
                                 finverse::cli::refuse_mpi_launch_without_mpi("fin-cfd");
                                 return 0;
                               }),
            finverse::kExitError);
  const std::string rebuild = ::testing::internal::GetCapturedStderr();
  EXPECT_NE(rebuild.find("t: error: started by an MPI launcher on 4 ranks, but this fin-cfd was built without MPI: "
                         "install libopenmpi-dev and rebuild (cmake -DFINVERSE_MPI=ON)"),
            std::string::npos)
      << rebuild;
  ::unsetenv("PMIX_RANK");
  ::unsetenv("PMIX_SIZE");
  EXPECT_NO_THROW(finverse::cli::refuse_mpi_launch_without_mpi("fin-cfd"));  // one process: nothing to refuse
}
