// Atomic whole-file writes (see atomic_file.hpp).
#include "core/atomic_file.hpp"

#include <fstream>
#include <system_error>

#include "core/error.hpp"

namespace finverse {

std::filesystem::path temporary_for(const std::filesystem::path& final_path) {
  auto t = final_path;
  t += ".tmp";
  return t;
}

void commit_temporary(const std::filesystem::path& temp, const std::filesystem::path& final_path) {
  std::error_code ec;
  std::filesystem::rename(temp, final_path, ec);
  if (ec) {
    std::filesystem::remove(temp, ec);
    throw Error(final_path.string() + ": cannot move temporary into place");
  }
}

void write_text_atomic(const std::filesystem::path& path, const std::string& content) {
  std::error_code ec;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
  const auto tmp = temporary_for(path);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw Error(path.string() + ": cannot create file (is the directory writable?)");
    out << content;
    out.close();
    if (!out) {
      std::filesystem::remove(tmp, ec);
      throw Error(path.string() + ": write failed (disk full?)");
    }
  }
  commit_temporary(tmp, path);
}

}  // namespace finverse
