// Command-line conventions shared by every executable (DESIGN.md section 3, "Command line"):
// --help, --version, --threads N (else OMP_NUM_THREADS), --log-level, --config FILE (a TOML/INI
// file with the same keys as the flags, CLI11's format); the effective configuration is echoed
// to the log and returned as JSON for the output files' `config` attribute. Errors end with one
// line on stderr and exit code 2.
//
//   int main(int argc, char** argv) {
//     CLI::App app{"fin-mesh: mesh the fin planform"};
//     finverse::cli::Standard std_opts(app, "fin-mesh");
//     app.add_option("--in", in, "kinematics.h5")->required();
//     return finverse::cli::run(app, std_opts, argc, argv, [&] { ...; return 0; });
//   }
#pragma once

#include <functional>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

namespace finverse::cli {

struct Standard {
  Standard(CLI::App& app, const std::string& tool);
  std::string tool;
  int threads = 0;  // 0: OMP_NUM_THREADS or the OpenMP default
  std::string log_level = "info";
  // Whether the tool runs on MPI ranks (fin-fit run, issue 48). Started by an MPI launcher with
  // more than one rank, any other tool is refused: each rank would do the whole work and write the
  // same files.
  bool mpi = false;
};

// Effective values of every option (defaults included), keyed by long name without dashes.
nlohmann::json effective_config(const CLI::App& app);

// Parses, applies threads and log level, echoes the configuration, runs `body` and maps
// exceptions to exit codes: finverse::Error and other std::exception -> one line + 2,
// CLI11 usage errors -> CLI11's message + 2, --help/--version -> 0.
int run(CLI::App& app, Standard& standard, int argc, char** argv, const std::function<int()>& body);

// This process's rank and its job's size as an MPI launcher (mpirun, srun, Hydra) set them in the
// environment: 0 and 1 for a plain run. Ranks above 0 print nothing from run().
int mpi_launch_rank();
int mpi_launch_size();
// For a tool built without MPI that could run on ranks: throws a one-line Error naming what to
// change when an MPI launcher started it on several ranks.
void refuse_mpi_launch_without_mpi(const std::string& tool);

int threads_in_use();

// Validators whose message says the range as a person writes it ("expected a number > 0, got
// -1"); CLI11's PositiveNumber printed its bounds as "0.000000 to" a 309-digit number.
CLI::Validator positive();
CLI::Validator non_negative();

// CLI11's "Value X not in range A to B" (bounds as std::to_string prints them, the largest double
// as 309 digits) rewritten as "expected a number from A to B, got X"; other messages unchanged.
std::string readable_ranges(const std::string& message);

}  // namespace finverse::cli
