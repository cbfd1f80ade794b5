// The numeric flags' ranges, in one place for every executable (issue 46): after parsing, every
// numeric value given on the command line or in a --config file is checked before any work.
//   - No flag takes NaN or an infinity: a number must be finite.
//   - A flag named in the table of flag_ranges.cpp must lie in its range: counts and sizes
//     (rays, population, width, ...) >= 1 or >= 0, physical scales and tolerances (chord, fps,
//     viscosity, ...) > 0 or >= 0. The table goes by the flag's name because a name means the same
//     in every executable; a flag whose sign carries meaning (a phase, an offset) is not in it.
// The error names the flag, the range as a person writes it and the value given.
#pragma once

#include <optional>
#include <string>

#include <CLI/CLI.hpp>

namespace finverse::cli {

// The range a flag must lie in, in words ("a number > 0", "a whole number >= 1"); nullopt for a
// flag the table does not name.
std::optional<std::string> flag_range(const std::string& long_name);

// Throws CLI::ValidationError naming the first flag (of app and its parsed subcommands) whose
// value is not finite or is outside its range.
void check_flag_ranges(const CLI::App& app);

}  // namespace finverse::cli
