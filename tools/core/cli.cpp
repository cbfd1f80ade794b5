// Shared command-line conventions (see cli.hpp).
#include "core/cli.hpp"

#include <omp.h>

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <regex>

#include "core/error.hpp"
#include "core/flag_ranges.hpp"
#include "core/log.hpp"
#include "core/output_paths.hpp"
#include "core/provenance.hpp"

namespace finverse::cli {

Standard::Standard(CLI::App& app, const std::string& tool_name) : tool(tool_name) {
  log::set_tool(tool_name);
  app.set_version_flag("--version", producer_string(tool_name));
  app.set_config("--config", "", "read options from a TOML/INI file (same keys as the long flags)");
  app.allow_config_extras(CLI::config_extras_mode::error);  // a misspelt key is an error, not ignored
  app.add_option("--threads", threads, "OpenMP threads (default: OMP_NUM_THREADS or all cores)")->check(non_negative());
  app.add_option("--log-level", log_level, "debug, info, warn, error or quiet")->capture_default_str();
}

nlohmann::json effective_config(const CLI::App& app) {
  nlohmann::json j = nlohmann::json::object();
  for (const CLI::Option* opt : app.get_options()) {
    const auto& name = opt->get_lnames().empty() ? opt->get_name() : opt->get_lnames().front();
    if (name == "help" || name == "version" || name == "config" || name.empty()) continue;
    std::vector<std::string> values = opt->results();
    if (values.empty() && !opt->get_default_str().empty()) values = {opt->get_default_str()};
    if (values.empty()) {
      j[name] = nullptr;
    } else if (values.size() == 1 && opt->get_expected_max() <= 1) {
      j[name] = values.front();
    } else {
      j[name] = values;
    }
  }
  for (const CLI::App* sub : app.get_subcommands()) {
    j["subcommand"] = sub->get_name();
    j[sub->get_name()] = effective_config(*sub);
  }
  return j;
}

int threads_in_use() { return omp_get_max_threads(); }

namespace {
// A number as a person writes it (CLI11 prints its bounds with std::to_string: "0.000000", and
// the largest double as 309 digits).
std::string plain_number(const std::string& text) {
  const double x = std::strtod(text.c_str(), nullptr);
  char b[32];
  std::snprintf(b, sizeof b, "%g", x);
  return b;
}
}  // namespace

namespace {
CLI::Validator sign_check(bool strict) {
  return CLI::Validator(
      [strict](std::string& value) -> std::string {
        char* end = nullptr;
        const double x = std::strtod(value.c_str(), &end);
        if (value.empty() || *end != '\0') return "expected a number, got " + value;
        if (strict ? !(x > 0) : !(x >= 0))
          return std::string("expected a number ") + (strict ? "> 0" : ">= 0") + ", got " + value;
        return {};
      },
      strict ? "POSITIVE" : "NONNEGATIVE");
}
}  // namespace

CLI::Validator positive() { return sign_check(true); }
CLI::Validator non_negative() { return sign_check(false); }

std::string readable_ranges(const std::string& message) {
  static const std::regex range(R"(Value (\S+) not in range (\S+) to (\S+))");
  std::smatch m;
  if (!std::regex_search(message, m, range)) return message;
  const double hi = std::strtod(m[3].str().c_str(), nullptr);
  const std::string expected = hi >= 1e300
                                   ? "a number >= " + plain_number(m[2].str())
                                   : "a number from " + plain_number(m[2].str()) + " to " + plain_number(m[3].str());
  return m.prefix().str() + "expected " + expected + ", got " + m[1].str() + m.suffix().str();
}

int run(CLI::App& app, Standard& standard, int argc, char** argv, const std::function<int()>& body) {
  // In an MPI job only rank 0 speaks: the other ranks read the same flags and files, so their
  // messages would repeat rank 0's (fin-fit run's evaluations across ranks, issue 48).
  const bool quiet_rank = mpi_launch_rank() > 0;
  try {
    app.parse(argc, argv);
    check_flag_ranges(app);   // before any work (issue 46)
    check_output_flags(app);  // an output that cannot be written, before the first step
  } catch (const CLI::Success& e) {
    return app.exit(e);  // --help, --version
  } catch (const CLI::ConfigError& e) {
    // CLI11 says "INI was not able to parse <key>" for a key no flag has: name the file and the key.
    std::string what = e.what();
    const std::string prefix = "INI was not able to parse ";
    if (what.rfind(prefix, 0) == 0) what = "unknown key '" + what.substr(prefix.size()) + "' (no such flag)";
    const CLI::Option* config = app.get_config_ptr();
    const std::string file = config && config->count() > 0 ? config->as<std::string>() : std::string("config");
    if (!quiet_rank)
      std::fprintf(stderr, "%s: error: --config %s: %s\n", standard.tool.c_str(), file.c_str(), what.c_str());
    return kExitError;
  } catch (const CLI::ParseError& e) {
    if (!quiet_rank)
      std::fprintf(stderr, "%s: error: %s (see --help)\n", standard.tool.c_str(), readable_ranges(e.what()).c_str());
    return kExitError;
  }
  try {
    log::set_level(quiet_rank ? log::Level::quiet : log::parse_level(standard.log_level));
    if (mpi_launch_size() > 1 && !standard.mpi)
      throw Error("started by an MPI launcher on " + std::to_string(mpi_launch_size()) + " ranks, but " +
                  standard.tool +
                  " does not run on MPI ranks (each rank would do the whole work and write the same files); run it "
                  "without mpirun");
    if (standard.threads > 0) omp_set_num_threads(standard.threads);
    log::info(producer_string(standard.tool));
    log::info("configuration: " + effective_config(app).dump());
    const int rc = body();
    log::timing_summary(threads_in_use());
    return rc;
  } catch (const ReportedError&) {
    return kExitError;
  } catch (const std::exception& e) {
    if (!quiet_rank) std::fprintf(stderr, "%s: error: %s\n", standard.tool.c_str(), e.what());
    return kExitError;
  }
}

int mpi_launch_rank() {
  // Open MPI's mpirun, PMIx launchers (srun --mpi=pmix) and Hydra (MPICH) set one of these.
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK", "SLURM_PROCID"})
    if (const char* v = std::getenv(name)) return std::atoi(v);
  return 0;
}

void refuse_mpi_launch_without_mpi(const std::string& tool) {
  if (mpi_launch_size() > 1)
    throw Error("started by an MPI launcher on " + std::to_string(mpi_launch_size()) + " ranks, but this " + tool +
                " was built without MPI: install libopenmpi-dev and rebuild (cmake -DFINVERSE_MPI=ON), or run it "
                "without mpirun");
}

int mpi_launch_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_SIZE", "PMI_SIZE"})
    if (const char* v = std::getenv(name)) return std::atoi(v);
  // srun (with or without an MPI plugin: PMIX_RANK alone says which) sets the step's task count;
  // a batch script itself has none.
  if (const char* v = std::getenv("SLURM_STEP_NUM_TASKS")) return std::atoi(v);
  return 1;
}

}  // namespace finverse::cli
