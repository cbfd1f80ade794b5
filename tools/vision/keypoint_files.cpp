// DeepLabCut and Anipose keypoint CSV files (see keypoint_files.hpp).
#include "vision/keypoint_files.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace finverse::vision {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> f;
  std::stringstream ss(line);
  for (std::string item; std::getline(ss, item, ',');) {
    item.erase(std::remove(item.begin(), item.end(), '\r'), item.end());
    if (item.size() >= 2 && item.front() == '"' && item.back() == '"') item = item.substr(1, item.size() - 2);
    f.push_back(item);
  }
  if (!line.empty() && line.back() == ',') f.emplace_back();
  return f;
}

std::vector<std::vector<std::string>> read_rows(const std::filesystem::path& csv, const std::string& what) {
  std::ifstream in(csv);
  if (!in) throw Error(csv.string() + ": cannot open the " + what + " file");
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line != "\r") rows.push_back(split(line));
  if (rows.empty()) throw Error(csv.string() + ": empty " + what + " file");
  return rows;
}

double number(const std::string& s, const std::string& where) {
  if (s.empty() || s == "nan" || s == "NaN") return kNaN;
  std::size_t used = 0;
  try {
    const double v = std::stod(s, &used);
    if (used == s.size()) return v;
  } catch (const std::exception&) {
  }
  throw Error(where + ": '" + s + "' is not a number");
}

// The last number in a row's first field (a frame index or an image name), else the row index.
long frame_of(const std::string& first, long row) {
  long value = -1;
  for (std::size_t i = 0; i < first.size();) {
    if (std::isdigit(static_cast<unsigned char>(first[i]))) {
      std::size_t j = i;
      while (j < first.size() && std::isdigit(static_cast<unsigned char>(first[j]))) ++j;
      value = std::stol(first.substr(i, std::min<std::size_t>(j - i, 15)));
      i = j;
    } else {
      ++i;
    }
  }
  return value >= 0 ? value : row;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string fmt(double v) {
  if (!std::isfinite(v)) return "";
  char b[32];
  std::snprintf(b, sizeof b, "%.10g", v);
  return b;
}

}  // namespace

std::optional<std::pair<std::size_t, RayEnd>> ray_keypoint(const std::string& bodypart) {
  const std::string s = lower(bodypart);
  if (s.rfind("ray", 0) != 0) return std::nullopt;
  std::size_t i = 3, j = 3;
  while (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j]))) ++j;
  if (j == i || j - i > 6) return std::nullopt;
  const long n = std::stol(s.substr(i, j - i));
  const std::string rest = s.substr(j);
  if (n < 1) return std::nullopt;
  if (rest == "_root") return std::pair{static_cast<std::size_t>(n - 1), RayEnd::root};
  if (rest == "_tip") return std::pair{static_cast<std::size_t>(n - 1), RayEnd::tip};
  return std::nullopt;
}

std::string ray_keypoint_name(std::size_t ray, RayEnd end) {
  return "ray" + std::to_string(ray + 1) + (end == RayEnd::root ? "_root" : "_tip");
}

KeypointTable read_deeplabcut_csv(const std::filesystem::path& csv) {
  const auto rows = read_rows(csv, "DeepLabCut");
  const std::string src = csv.string();
  KeypointTable t;
  std::size_t r = 0;
  const std::vector<std::string>* parts = nullptr;
  const std::vector<std::string>* coords = nullptr;
  for (; r < rows.size(); ++r) {
    const std::string head = rows[r].empty() ? "" : lower(rows[r][0]);
    if (head == "scorer") t.scorer = rows[r].size() > 1 ? rows[r][1] : t.scorer;
    else if (head == "bodyparts") parts = &rows[r];
    else if (head == "coords") coords = &rows[r];
    else if (head != "individuals") break;
  }
  if (!parts || !coords)
    throw Error(src + ": expected DeepLabCut's header rows scorer, bodyparts and coords (x, y, likelihood per bodypart)");
  // Column triples (x, y, likelihood) per bodypart, in the order of the coords row.
  std::map<std::string, std::array<int, 3>> columns;
  for (std::size_t c = 1; c < coords->size() && c < parts->size(); ++c) {
    const std::string kind = lower((*coords)[c]);
    const int k = kind == "x" ? 0 : kind == "y" ? 1 : kind == "likelihood" ? 2 : -1;
    if (k < 0) throw Error(src + ": coords column " + std::to_string(c) + " is '" + (*coords)[c] + "', expected x, y or likelihood");
    const std::string& name = (*parts)[c];
    if (!columns.count(name)) columns[name] = {-1, -1, -1}, t.bodyparts.push_back(name);
    auto& col = columns[name][static_cast<std::size_t>(k)];
    if (col < 0) col = static_cast<int>(c);  // a multi-animal file: the first individual
  }
  for (const auto& name : t.bodyparts)
    if (columns[name][0] < 0 || columns[name][1] < 0)
      throw Error(src + ": bodypart '" + name + "' has no x or y column");
  for (long row = 0; r < rows.size(); ++r, ++row) {
    const auto& f = rows[r];
    const std::string where = src + ": row " + std::to_string(r + 1);
    t.frames.push_back(frame_of(f.empty() ? "" : f[0], row));
    auto& xyz = t.xyz.emplace_back();
    auto& score = t.score.emplace_back();
    for (const auto& name : t.bodyparts) {
      const auto& c = columns[name];
      auto at = [&](int col) { return col >= 0 && static_cast<std::size_t>(col) < f.size() ? number(f[static_cast<std::size_t>(col)], where) : kNaN; };
      xyz.emplace_back(at(c[0]), at(c[1]), 0.0);
      score.push_back(c[2] >= 0 ? at(c[2]) : 1.0);
    }
  }
  if (t.frames.empty()) throw Error(src + ": no data rows after the header");
  return t;
}

KeypointTable read_anipose_csv(const std::filesystem::path& csv) {
  const auto rows = read_rows(csv, "Anipose 3-D");
  const std::string src = csv.string();
  const auto& head = rows[0];
  KeypointTable t;
  t.scorer = "anipose";
  std::map<std::string, std::array<int, 4>> columns;  // x, y, z, score
  int fnum = -1;
  for (std::size_t c = 0; c < head.size(); ++c) {
    const std::string& h = head[c];
    if (h == "fnum") fnum = static_cast<int>(c);
    const auto us = h.rfind('_');
    if (us == std::string::npos) continue;
    const std::string name = h.substr(0, us), kind = h.substr(us + 1);
    const int k = kind == "x" ? 0 : kind == "y" ? 1 : kind == "z" ? 2 : kind == "score" ? 3 : -1;
    if (k < 0) continue;
    if (!columns.count(name)) columns[name] = {-1, -1, -1, -1}, t.bodyparts.push_back(name);
    columns[name][static_cast<std::size_t>(k)] = static_cast<int>(c);
  }
  std::erase_if(t.bodyparts, [&](const std::string& n) { return columns[n][0] < 0 || columns[n][1] < 0 || columns[n][2] < 0; });
  if (t.bodyparts.empty()) throw Error(src + ": expected Anipose's 3-D columns <bodypart>_x, _y, _z in the header");
  for (std::size_t r = 1; r < rows.size(); ++r) {
    const auto& f = rows[r];
    const std::string where = src + ": row " + std::to_string(r + 1);
    auto at = [&](int col) { return col >= 0 && static_cast<std::size_t>(col) < f.size() ? number(f[static_cast<std::size_t>(col)], where) : kNaN; };
    t.frames.push_back(fnum >= 0 ? static_cast<long>(at(fnum)) : static_cast<long>(r - 1));
    auto& xyz = t.xyz.emplace_back();
    auto& score = t.score.emplace_back();
    for (const auto& name : t.bodyparts) {
      const auto& c = columns[name];
      xyz.emplace_back(at(c[0]), at(c[1]), at(c[2]));
      score.push_back(c[3] >= 0 ? at(c[3]) : 1.0);
    }
  }
  if (t.frames.empty()) throw Error(src + ": no data rows after the header");
  return t;
}

void write_deeplabcut_csv(const std::filesystem::path& csv, const KeypointTable& t) {
  std::string s = "scorer", b = "bodyparts", c = "coords";
  for (const auto& name : t.bodyparts)
    for (const char* k : {"x", "y", "likelihood"}) s += "," + t.scorer, b += "," + name, c += std::string(",") + k;
  std::string out = s + "\n" + b + "\n" + c + "\n";
  for (std::size_t r = 0; r < t.frames.size(); ++r) {
    out += std::to_string(t.frames[r]);
    for (std::size_t p = 0; p < t.bodyparts.size(); ++p)
      out += "," + fmt(t.xyz[r][p][0]) + "," + fmt(t.xyz[r][p][1]) + "," + fmt(t.score[r][p]);
    out += "\n";
  }
  write_text_atomic(csv, out);
}

void write_anipose_csv(const std::filesystem::path& csv, const KeypointTable& t) {
  std::string out;
  for (const auto& name : t.bodyparts)
    for (const char* k : {"_x", "_y", "_z", "_error", "_ncams", "_score"}) out += name + k + ",";
  out += "fnum\n";
  for (std::size_t r = 0; r < t.frames.size(); ++r) {
    for (std::size_t p = 0; p < t.bodyparts.size(); ++p)
      out += fmt(t.xyz[r][p][0]) + "," + fmt(t.xyz[r][p][1]) + "," + fmt(t.xyz[r][p][2]) + ",0,0," + fmt(t.score[r][p]) + ",";
    out += std::to_string(t.frames[r]) + "\n";
  }
  write_text_atomic(csv, out);
}

KeypointRecord keypoint_record(const std::vector<std::pair<std::size_t, const KeypointTable*>>& image_tables,
                               const KeypointTable* world_table, double metres_per_unit, double min_score, std::size_t rays) {
  KeypointRecord rec;
  auto each = [&](const KeypointTable& t, auto&& add) {
    std::vector<std::optional<std::pair<std::size_t, RayEnd>>> ends;
    for (const auto& name : t.bodyparts) {
      ends.push_back(ray_keypoint(name));
      if (ends.back() && ends.back()->first >= rays)
        throw Error("keypoints: bodypart '" + name + "' names a ray the template does not have (" + std::to_string(rays) + " rays)");
    }
    for (std::size_t r = 0; r < t.frames.size(); ++r)
      for (std::size_t p = 0; p < t.bodyparts.size(); ++p) {
        const auto& x = t.xyz[r][p];
        const double s = t.score[r][p];
        if (!ends[p] || !std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]) || !(s >= min_score)) continue;
        add(rec[t.frames[r]], ends[p]->first, ends[p]->second, x);
      }
  };
  for (const auto& [view, table] : image_tables)
    each(*table, [&, view = view](FrameKeypoints& f, std::size_t ray, RayEnd end, const cv::Vec3d& x) {
      f.image.push_back({ray, end, view, cv::Point2d(x[0], x[1])});
    });
  if (world_table)
    each(*world_table, [&](FrameKeypoints& f, std::size_t ray, RayEnd end, const cv::Vec3d& x) {
      f.world.push_back({ray, end, metres_per_unit * x});
    });
  return rec;
}

KeypointTable fitted_ray_ends(const std::vector<long>& frames, const NdArray<double>& points, const RayEnds& ends,
                              const Camera* camera, double metres_per_unit) {
  KeypointTable t;
  t.scorer = "finverse";
  const std::size_t rays = ends.root.size(), nv = points.dim(1);
  for (std::size_t r = 0; r < rays; ++r)
    for (RayEnd e : {RayEnd::root, RayEnd::tip}) t.bodyparts.push_back(ray_keypoint_name(r, e));
  for (std::size_t i = 0; i < frames.size(); ++i) {
    t.frames.push_back(frames[i]);
    auto& xyz = t.xyz.emplace_back();
    for (std::size_t r = 0; r < rays; ++r)
      for (RayEnd e : {RayEnd::root, RayEnd::tip}) {
        const auto v = static_cast<std::size_t>(ends.vertex(r, e));
        const cv::Vec3d X(points.data[(i * nv + v) * 3], points.data[(i * nv + v) * 3 + 1], points.data[(i * nv + v) * 3 + 2]);
        if (camera) {
          const auto uv = camera->project(X);
          xyz.emplace_back(uv.x, uv.y, 0.0);
        } else {
          xyz.push_back(X / metres_per_unit);
        }
      }
    t.score.emplace_back(2 * rays, 1.0);
  }
  return t;
}

}  // namespace finverse::vision
