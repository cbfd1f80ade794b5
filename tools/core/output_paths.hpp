// Output paths checked before the first step (issue 46): a run whose result cannot be written
// must say so at once, not after an hour of computing. A path is writable when its nearest
// existing ancestor is a directory this user may write into (the writers create the folders
// below it) and the path itself is not an existing directory where a file is expected.
//   - Flags that are outputs in every executable (--out, --out-dir, --summary, --vtu, ...) are
//     checked by cli::run through check_output_flags.
//   - A flag that is an output in one executable only (fin-mesh's --mesh) takes ->check(writable_output()).
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

namespace finverse::cli {

// Why `path` cannot be written (a directory expected when `directory`); nullopt when it can.
std::optional<std::string> unwritable_reason(const std::filesystem::path& path, bool directory = false);

// A CLI11 validator for a file output flag.
CLI::Validator writable_output();

// Throws CLI::ValidationError for the first output flag (by name, in app and its parsed
// subcommands) that cannot be written.
void check_output_flags(const CLI::App& app);

}  // namespace finverse::cli
