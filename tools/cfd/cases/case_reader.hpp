// The case-file reader's typed access to YAML nodes (case_file.cpp, motion_section.cpp): every
// error names the file, the key and its line, and a misspelt key is an error, not ignored.
#pragma once

#include <yaml-cpp/yaml.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <string>

#include "core/error.hpp"

namespace finverse::cfd::cases {

struct Reader {
  std::filesystem::path file;
  [[noreturn]] void fail(const YAML::Node& n, const std::string& key, const std::string& what) const {
    const int line = n.Mark().line;
    throw Error(file.string() + (line >= 0 ? ":" + std::to_string(line + 1) : std::string()) + ": " + key + ": " +
                what);
  }
  template <class T>
  T scalar(const YAML::Node& n, const std::string& key, const char* expected) const {
    if (!n.IsScalar()) fail(n, key, std::string("expected ") + expected);
    try {
      return n.as<T>();
    } catch (const YAML::Exception&) {
      fail(n, key, "'" + n.Scalar() + "', expected " + expected);
    }
  }
  // A finite number (".nan" and ".inf" are refused); positive / non_negative add the sign.
  double number(const YAML::Node& n, const std::string& key) const {
    const double x = scalar<double>(n, key, "a number");
    if (!std::isfinite(x)) fail(n, key, "'" + n.Scalar() + "', expected a finite number");
    return x;
  }
  double positive(const YAML::Node& n, const std::string& key) const {
    const double x = number(n, key);
    if (!(x > 0)) fail(n, key, n.Scalar() + ", expected a number > 0");
    return x;
  }
  double non_negative(const YAML::Node& n, const std::string& key) const {
    const double x = number(n, key);
    if (!(x >= 0)) fail(n, key, n.Scalar() + ", expected a number >= 0");
    return x;
  }
  template <std::size_t N>
  std::array<double, N> numbers(const YAML::Node& n, const std::string& key) const {
    if (!n.IsSequence() || n.size() != N) fail(n, key, "expected a list of " + std::to_string(N) + " numbers");
    std::array<double, N> a{};
    for (std::size_t i = 0; i < N; ++i) a[i] = number(n[i], key);
    return a;
  }
  std::filesystem::path path(const YAML::Node& n, const std::string& key) const {
    const std::filesystem::path p = scalar<std::string>(n, key, "a file name");
    return p.is_absolute() ? p : (file.parent_path() / p).lexically_normal();
  }
  // Every key of `map` must be one of `known`: a misspelt key must not be silently ignored.
  void only(const YAML::Node& map, const std::string& where, std::initializer_list<const char*> known) const {
    if (!map.IsMap()) fail(map, where, "expected a section of keys");
    for (const auto& kv : map) {
      const std::string k = kv.first.as<std::string>();
      bool ok = false;
      for (const char* q : known) ok = ok || k == q;
      if (!ok) fail(kv.first, where.empty() ? k : where + "." + k, "unknown key");
    }
  }
};

}  // namespace finverse::cfd::cases
