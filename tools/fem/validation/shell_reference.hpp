// Reading the shell benchmark references from structures.json (DESIGN.md section 6): one object
// per benchmark with scalar parameters and equally long columns.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

namespace finverse::fem::validation {

class ReferenceTable {
 public:
  // Throws InvalidInput naming the file and the key when it cannot be read or lacks the object.
  ReferenceTable(const std::filesystem::path& path, const std::string& key);

  double scalar(const std::string& name) const;
  // Column `name`, row `row`; throws InvalidInput naming the file, object and column.
  double column(const std::string& name, size_t row) const;
  size_t rows(const std::string& name) const;
  // Row whose entry in column `key_column` equals value (to 1e-12); throws when absent.
  size_t find_row(const std::string& key_column, double value) const;
  // "structures.json <key>: <source>"
  std::string source() const;

 private:
  [[noreturn]] void fail(const std::string& what) const;
  std::filesystem::path path_;
  std::string key_;
  nlohmann::json table_;
};

}  // namespace finverse::fem::validation
