// Tolerance files of fin-diff (see tolerances.hpp).
#include "core/tolerances.hpp"

#include <fnmatch.h>

#include <fstream>

#include <nlohmann/json.hpp>

#include "core/error.hpp"

namespace finverse {
namespace {

Tolerance parse(const nlohmann::json& j, Tolerance base, const std::string& where) {
  for (const auto& [k, v] : j.items())
    if (k != "atol" && k != "rtol") throw Error(where + ": unknown key '" + k + "' (expected atol, rtol)");
  base.atol = j.value("atol", base.atol);
  base.rtol = j.value("rtol", base.rtol);
  if (base.atol < 0 || base.rtol < 0) throw Error(where + ": tolerances must be non-negative");
  return base;
}

}  // namespace

Tolerances Tolerances::load(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw Error(path.string() + ": cannot open tolerance file");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw Error(path.string() + ": malformed JSON: " + e.what());
  }
  const auto name = path.string();
  Tolerances t;
  try {
    for (const auto& [k, v] : j.items())
      if (k != "default" && k != "datasets" && k != "ignore" && k != "comment")
        throw Error(name + ": unknown key '" + k + "' (expected default, datasets, ignore, comment)");
    if (j.contains("default")) t.default_ = parse(j["default"], {}, name + ": default");
    if (j.contains("datasets"))
      for (const auto& [pattern, v] : j["datasets"].items()) t.rules_.emplace_back(pattern, parse(v, t.default_, name + ": " + pattern));
    if (j.contains("ignore"))
      for (const auto& p : j["ignore"]) t.ignore_.push_back(p.get<std::string>());
  } catch (const nlohmann::json::exception& e) {
    throw Error(name + ": " + e.what());
  }
  return t;
}

Tolerance Tolerances::for_object(const std::string& path) const {
  for (const auto& [pattern, tol] : rules_)
    if (fnmatch(pattern.c_str(), path.c_str(), 0) == 0) return tol;
  return default_;
}

bool Tolerances::ignored(const std::string& path) const {
  for (const auto& pattern : ignore_)
    if (fnmatch(pattern.c_str(), path.c_str(), 0) == 0) return true;
  return false;
}

}  // namespace finverse
