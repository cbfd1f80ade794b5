// The stage-file subcommands of fin-fit, `run` and `evaluate`: their flags, shared where the two
// describe the same fit problem, and how the parsed flags become fit/io/file_fit.hpp's options.
// Flags only: the fit is in the fit/io library.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "fit/io/file_fit.hpp"

namespace finverse::apps {

// The fit problem's flags, shared by run and evaluate (only one subcommand is parsed).
struct ProblemFlags {
  fit::io::FileFitOptions o;
  std::string mesh, motion, materials, loads, parameters;
  std::string root_rotation = "auto", base = "carried", increment = "newton";
};

// `fin-fit run`'s own flags (the problem's are ProblemFlags).
struct RunFlags {
  std::string out, summary, checkpoint;
  std::vector<std::string> methods{"ga"};
  bool no_polish = false;
};

// The help's closing paragraph for run and evaluate: how to give one's own data.
extern const char* const kOwnData;

void add_problem_options(CLI::App* c, ProblemFlags& f);
void add_run_command(CLI::App& app, ProblemFlags& flags, RunFlags& r);
// The parsed flags of run and evaluate into flags.o.
void apply_flags(ProblemFlags& flags, const RunFlags& r);

}  // namespace finverse::apps
