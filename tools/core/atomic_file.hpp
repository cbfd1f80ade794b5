// Whole-file writes that never leave a half-written file under the final name: the content goes
// to `<name>.tmp` and is renamed into place (rename is atomic within one file system).
#pragma once

#include <filesystem>
#include <string>

namespace finverse {

void write_text_atomic(const std::filesystem::path& path, const std::string& content);

// Moves a finished temporary into place, creating the parent directory; throws finverse::Error.
void commit_temporary(const std::filesystem::path& temp, const std::filesystem::path& final_path);

// "<path>.tmp": the one temporary-name convention of every writer.
std::filesystem::path temporary_for(const std::filesystem::path& final_path);

}  // namespace finverse
