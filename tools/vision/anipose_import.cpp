// Anipose calibration.toml <-> cameras (see anipose_import.hpp for the layout and why a small reader).
#include "vision/anipose_import.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace finverse::vision {

namespace {

struct TomlValue {
  enum Kind { number, text, boolean, array } kind = number;
  double num = 0;
  std::string str;
  std::vector<TomlValue> items;
};

using TomlTable = std::map<std::string, TomlValue>;

class TomlParser {
 public:
  TomlParser(std::string text, std::string where) : s_(std::move(text)), where_(std::move(where)) {}

  TomlValue value() {
    skip();
    if (pos_ >= s_.size()) fail("a value");
    const char ch = s_[pos_];
    TomlValue v;
    if (ch == '[') {
      v.kind = TomlValue::array;
      ++pos_;
      for (;;) {
        skip();
        if (pos_ < s_.size() && s_[pos_] == ']') { ++pos_; break; }
        v.items.push_back(value());
        skip();
        if (pos_ < s_.size() && s_[pos_] == ',') ++pos_;
        else if (pos_ < s_.size() && s_[pos_] == ']') { ++pos_; break; }
        else fail("',' or ']' in an array");
      }
    } else if (ch == '"' || ch == '\'') {
      v.kind = TomlValue::text;
      const auto end = s_.find(ch, pos_ + 1);
      if (end == std::string::npos) fail("a closing quote");
      v.str = s_.substr(pos_ + 1, end - pos_ - 1);
      pos_ = end + 1;
    } else if (s_.compare(pos_, 4, "true") == 0 || s_.compare(pos_, 5, "false") == 0) {
      v.kind = TomlValue::boolean;
      v.num = s_[pos_] == 't';
      pos_ += s_[pos_] == 't' ? 4 : 5;
    } else {
      const char* begin = s_.c_str() + pos_;
      char* end = nullptr;
      v.num = std::strtod(begin, &end);
      if (end == begin) fail("a number, string, boolean or array");
      pos_ += static_cast<std::size_t>(end - begin);
    }
    return v;
  }

  // Whitespace, newlines and comments (arrays may span lines).
  void skip() {
    while (pos_ < s_.size()) {
      if (std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
      else if (s_[pos_] == '#') { while (pos_ < s_.size() && s_[pos_] != '\n') ++pos_; }
      else break;
    }
  }

  std::map<std::string, TomlTable> document() {
    std::map<std::string, TomlTable> tables;
    std::string current;
    for (;;) {
      skip();
      if (pos_ >= s_.size()) break;
      if (s_[pos_] == '[') {
        const auto end = s_.find(']', pos_);
        if (end == std::string::npos) fail("']' closing a table name");
        current = trim(s_.substr(pos_ + 1, end - pos_ - 1));
        tables[current];
        pos_ = end + 1;
        continue;
      }
      const auto eq = s_.find('=', pos_);
      const auto nl = s_.find('\n', pos_);
      if (eq == std::string::npos || (nl != std::string::npos && nl < eq)) fail("'key = value'");
      std::string key = trim(s_.substr(pos_, eq - pos_));
      if (key.size() >= 2 && (key.front() == '"' || key.front() == '\'')) key = key.substr(1, key.size() - 2);
      pos_ = eq + 1;
      tables[current][key] = value();
    }
    return tables;
  }

 private:
  static std::string trim(const std::string& t) {
    const auto a = t.find_first_not_of(" \t\r\n");
    const auto b = t.find_last_not_of(" \t\r\n");
    return a == std::string::npos ? "" : t.substr(a, b - a + 1);
  }
  [[noreturn]] void fail(const std::string& expected) const {
    const long line = 1 + std::count(s_.begin(), s_.begin() + static_cast<long>(std::min(pos_, s_.size())), '\n');
    throw Error(where_ + ": line " + std::to_string(line) + ": expected " + expected + " (TOML)");
  }
  std::string s_, where_;
  std::size_t pos_ = 0;
};

std::vector<double> numbers(const TomlValue& v, const std::string& what, std::size_t min_n, std::size_t max_n) {
  std::vector<double> out;
  auto flatten = [&](auto&& self, const TomlValue& x) -> void {
    if (x.kind == TomlValue::array) {
      for (const auto& i : x.items) self(self, i);
    } else if (x.kind == TomlValue::number) {
      out.push_back(x.num);
    } else {
      throw Error(what + ": expected numbers");
    }
  };
  flatten(flatten, v);
  if (out.size() < min_n || out.size() > max_n)
    throw Error(what + ": " + std::to_string(out.size()) + " numbers, expected " +
                (min_n == max_n ? std::to_string(min_n) : std::to_string(min_n) + " to " + std::to_string(max_n)));
  return out;
}

long table_number(const std::string& name) {
  const auto p = name.find_last_not_of("0123456789");
  return p + 1 < name.size() ? std::stol(name.substr(p + 1)) : -1;
}

}  // namespace

std::vector<Camera> read_anipose_calibration(const std::filesystem::path& toml, double metres_per_unit) {
  const std::string where = toml.string();
  if (!(metres_per_unit > 0)) throw Error("--length-unit: metres per Anipose length unit must be > 0");
  std::ifstream in(toml);
  if (!in) throw Error(where + ": cannot open the Anipose calibration");
  std::stringstream buf;
  buf << in.rdbuf();
  const auto tables = TomlParser(buf.str(), where).document();
  std::vector<std::pair<long, std::string>> names;
  for (const auto& [name, t] : tables)
    if (name.rfind("cam_", 0) == 0) names.emplace_back(table_number(name), name);
  std::sort(names.begin(), names.end());
  if (names.empty()) throw Error(where + ": no [cam_N] tables, expected an Anipose calibration.toml");
  std::vector<Camera> out;
  for (const auto& [index, tname] : names) {
    const auto& t = tables.at(tname);
    const std::string at = where + ": [" + tname + "]";
    auto get = [&](const std::string& key) -> const TomlValue& {
      const auto it = t.find(key);
      if (it == t.end()) throw Error(at + ": missing '" + key + "'");
      return it->second;
    };
    if (t.count("fisheye") && t.at("fisheye").kind == TomlValue::boolean && t.at("fisheye").num != 0)
      throw Error(at + ": fisheye camera, expected a pinhole camera (OpenCV's 5-coefficient model)");
    Camera c;
    const auto& name = get("name");
    c.name = name.kind == TomlValue::text ? name.str : tname;
    const auto size = numbers(get("size"), at + " size", 2, 2);
    c.width = static_cast<int>(size[0]);
    c.height = static_cast<int>(size[1]);
    if (c.width <= 0 || c.height <= 0) throw Error(at + " size: expected [width, height] > 0");
    const auto K = numbers(get("matrix"), at + " matrix", 9, 9);
    for (int i = 0; i < 9; ++i) c.K(i / 3, i % 3) = K[static_cast<std::size_t>(i)];
    const auto d = numbers(get("distortions"), at + " distortions", 0, 5);
    for (std::size_t i = 0; i < d.size(); ++i) c.dist[static_cast<int>(i)] = d[i];
    const auto r = numbers(get("rotation"), at + " rotation", 3, 3);
    const auto tr = numbers(get("translation"), at + " translation", 3, 3);
    for (int i = 0; i < 3; ++i) c.rvec[i] = r[static_cast<std::size_t>(i)], c.tvec[i] = tr[static_cast<std::size_t>(i)] * metres_per_unit;
    out.push_back(c);
  }
  return out;
}

void write_anipose_calibration(const std::filesystem::path& toml, const std::vector<Camera>& cameras, double metres_per_unit) {
  std::ostringstream o;
  o.precision(17);
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    const auto& c = cameras[i];
    o << "[cam_" << i << "]\nname = \"" << c.name << "\"\nsize = [ " << c.width << ", " << c.height << ",]\nmatrix = [";
    for (int r = 0; r < 3; ++r) o << " [ " << c.K(r, 0) << ", " << c.K(r, 1) << ", " << c.K(r, 2) << ",],";
    o << "]\ndistortions = [";
    for (int k = 0; k < 5; ++k) o << " " << c.dist[k] << ",";
    o << "]\nrotation = [ " << c.rvec[0] << ", " << c.rvec[1] << ", " << c.rvec[2] << ",]\ntranslation = [ ";
    for (int k = 0; k < 3; ++k) o << c.tvec[k] / metres_per_unit << ", ";
    o << "]\n\n";
  }
  o << "[metadata]\nadjusted = false\nerror = 0.0\n";
  write_text_atomic(toml, o.str());
}

}  // namespace finverse::vision
