// SHA-256 (FIPS 180-4) of byte strings and files: the content hashes recorded in every output's
// `inputs` attribute, so a result can be traced to the exact files it was made from.
#pragma once

#include <filesystem>
#include <string>

namespace finverse {

std::string sha256_hex(const std::string& bytes);
std::string sha256_file(const std::filesystem::path& path);  // throws finverse::Error if unreadable

}  // namespace finverse
