// Reference tables from structures.json (see shell_reference.hpp).
#include "fem/validation/shell_reference.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "fem/errors.hpp"

namespace finverse::fem::validation {

ReferenceTable::ReferenceTable(const std::filesystem::path& path, const std::string& key)
    : path_(path), key_(key) {
  std::ifstream in(path);
  if (!in) throw InvalidInput("cannot open reference file " + path.string());
  nlohmann::json all;
  try {
    all = nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw InvalidInput("reference file " + path.string() + " is not valid JSON: " + e.what());
  }
  if (!all.contains(key) || !all[key].is_object())
    throw InvalidInput(path.string() + ": missing object '" + key + "'");
  table_ = all[key];
}

void ReferenceTable::fail(const std::string& what) const {
  throw InvalidInput(path_.string() + ": " + key_ + ": " + what);
}

double ReferenceTable::scalar(const std::string& name) const {
  if (!table_.contains(name) || !table_[name].is_number()) fail("expected a number '" + name + "'");
  return table_[name].get<double>();
}

size_t ReferenceTable::rows(const std::string& name) const {
  if (!table_.contains(name) || !table_[name].is_array()) fail("expected an array '" + name + "'");
  return table_[name].size();
}

double ReferenceTable::column(const std::string& name, size_t row) const {
  if (row >= rows(name) || !table_[name][row].is_number()) {
    std::ostringstream os;
    os << "expected a number at '" << name << "'[" << row << "]";
    fail(os.str());
  }
  return table_[name][row].get<double>();
}

size_t ReferenceTable::find_row(const std::string& key_column, double value) const {
  for (size_t i = 0; i < rows(key_column); ++i)
    if (std::abs(column(key_column, i) - value) < 1e-12) return i;
  std::ostringstream os;
  os << "no row with " << key_column << " = " << value;
  fail(os.str());
}

std::string ReferenceTable::source() const {
  return "structures.json " + key_ + ": " + table_.value("source", std::string());
}

}  // namespace finverse::fem::validation
