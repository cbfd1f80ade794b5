// Output paths checked before the first step (see output_paths.hpp).
#include "core/output_paths.hpp"

#include <unistd.h>

#include <set>
#include <system_error>

namespace finverse::cli {

std::optional<std::string> unwritable_reason(const std::filesystem::path& path, bool directory) {
  namespace fs = std::filesystem;
  if (path.empty()) return "an empty path";
  std::error_code ec;
  const fs::path p = fs::absolute(path, ec);
  if (ec) return "not a usable path";
  if (fs::exists(p, ec)) {
    if (!directory && fs::is_directory(p, ec)) return "is a directory, a file is expected";
    if (directory && !fs::is_directory(p, ec)) return "is a file, a directory is expected";
    const fs::path dir = directory ? p : p.parent_path();
    if (access(dir.c_str(), W_OK | X_OK) != 0) return dir.string() + " is not writable";
    return std::nullopt;
  }
  // The nearest existing ancestor must be a writable directory: the writers create the rest.
  for (fs::path a = p.parent_path(); !a.empty(); a = a.parent_path()) {
    if (fs::exists(a, ec)) {
      if (!fs::is_directory(a, ec)) return a.string() + " is a file, not a directory";
      if (access(a.c_str(), W_OK | X_OK) != 0) return a.string() + " is not writable";
      return std::nullopt;
    }
    if (a == a.root_path()) break;
  }
  return "no existing folder above it";
}

CLI::Validator writable_output() {
  return CLI::Validator(
      [](std::string& value) -> std::string {
        const auto why = unwritable_reason(value);
        return why ? "cannot write " + value + ": " + *why : std::string();
      },
      "", "writable output");
}

namespace {
// Output flags by name in every executable; directories among them.
const std::set<std::string> kFileOutputs = {"out", "summary", "vtu", "motion-pvd", "materials-out", "checkpoint"};
const std::set<std::string> kDirectoryOutputs = {"out-dir"};
}  // namespace

void check_output_flags(const CLI::App& app) {
  for (const CLI::Option* o : app.get_options()) {
    if (o->count() == 0 || o->get_lnames().empty()) continue;
    const std::string& name = o->get_lnames().front();
    const bool file = kFileOutputs.count(name) > 0, dir = kDirectoryOutputs.count(name) > 0;
    if (!file && !dir) continue;
    for (const std::string& v : o->results())
      if (const auto why = unwritable_reason(v, dir)) throw CLI::ValidationError("--" + name, "cannot write " + v + ": " + *why);
  }
  for (const CLI::App* sub : app.get_subcommands()) check_output_flags(*sub);
}

}  // namespace finverse::cli
