// `fin-cfd run CASE.yaml` (case_file.hpp): a validation case's file becomes its subcommand and
// flags, so that a case file and the command line share one parser and one set of checks; a flow
// case runs here and writes <out_dir>/<name>/{forces.csv, summary.json}.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace finverse::cfd::cases {

// argv with `run FILE` of a validation case replaced by `<case> <the file's flags>` (flags after
// FILE come later, so they override the file's); unchanged without `run` or for a flow case.
// `--coarse` before `run` selects the file's coarse: section. `flags_of(name)`: the flags case `name`
// takes; an unknown case (empty optional) or a key that is not one of its flags is an error.
std::vector<std::string> expand_case_file(
    std::vector<std::string> args,
    const std::function<std::optional<std::vector<std::string>>(const std::string& name)>& flags_of);

// A `case: flow` file: runs it and writes its results; the exit code.
int run_flow_case_file(const std::filesystem::path& file, bool coarse, const std::filesystem::path& out_dir);

}  // namespace finverse::cfd::cases
