// A fin template from a digitised side-view image of the user's fish (see digitised_template.hpp).
#include "vision/digitised_template.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include "core/error.hpp"

namespace finverse::vision {

namespace {

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r") - a + 1);
}

// Distance from p to the closed polygon's boundary, negative inside.
double signed_outline_distance(const std::vector<cv::Point2d>& poly, const cv::Point2d& p) {
  std::vector<cv::Point2f> f(poly.begin(), poly.end());
  return -cv::pointPolygonTest(f, cv::Point2f(static_cast<float>(p.x), static_cast<float>(p.y)), true);
}

}  // namespace

DigitisedFin read_digitised_fin(const std::filesystem::path& csv) {
  DigitisedFin fin;
  fin.source = csv.string();
  std::ifstream in(csv);
  if (!in) throw Error(fin.source + ": cannot open the digitised fin CSV");
  std::vector<std::pair<long, cv::Point2d>> outline;
  std::map<long, cv::Point2d> roots, tips, scale;
  std::map<long, std::vector<cv::Point2d>> inner;
  std::string line;
  for (int no = 1; std::getline(in, line); ++no) {
    line = trim(line);
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string item; std::getline(ss, item, ',');) f.push_back(trim(item));
    if (f.size() == 4 && f[0] == "kind") continue;  // the header
    const std::string where = fin.source + ":" + std::to_string(no) + ": ";
    long id = 0;
    cv::Point2d p;
    try {
      if (f.size() != 4) throw std::invalid_argument(line);
      std::size_t used = 0;
      id = std::stol(f[1], &used);
      if (used != f[1].size()) throw std::invalid_argument(f[1]);
      p = {std::stod(f[2], &used), 0};
      if (used != f[2].size()) throw std::invalid_argument(f[2]);
      p.y = std::stod(f[3], &used);
      if (used != f[3].size()) throw std::invalid_argument(f[3]);
    } catch (const std::exception&) {
      throw Error(where + "'" + line + "', expected kind,id,x_px,y_px (kind: outline, root, ray, tip or scale)");
    }
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) throw Error(where + "non-finite coordinates");
    if (f[0] == "outline") {
      outline.emplace_back(id, p);
    } else if (f[0] == "root" || f[0] == "tip") {
      auto& m = f[0] == "root" ? roots : tips;
      if (id < 1) throw Error(where + "ray number " + std::to_string(id) + ", expected >= 1 (1: the dorsal edge ray)");
      if (!m.emplace(id, p).second) throw Error(where + "a second " + f[0] + " of ray " + std::to_string(id));
    } else if (f[0] == "ray") {
      inner[id].push_back(p);
    } else if (f[0] == "scale") {
      if (id != 1 && id != 2) throw Error(where + "scale id " + std::to_string(id) + ", expected 1 or 2 (the two ends)");
      if (!scale.emplace(id, p).second) throw Error(where + "a second scale point " + std::to_string(id));
    } else {
      throw Error(where + "kind '" + f[0] + "', expected outline, root, ray, tip or scale");
    }
  }
  std::stable_sort(outline.begin(), outline.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [id, p] : outline) fin.outline.push_back(p);
  if (fin.outline.size() < 3)
    throw Error(fin.source + ": " + std::to_string(fin.outline.size()) + " outline points, expected at least 3");
  const long n = roots.empty() ? 0 : roots.rbegin()->first;
  if (n < 2) throw Error(fin.source + ": " + std::to_string(roots.size()) + " ray roots, expected at least 2 (rays 1 and n)");
  for (long r = 1; r <= n; ++r) {
    if (!roots.count(r) || !tips.count(r))
      throw Error(fin.source + ": ray " + std::to_string(r) + " has no " + (roots.count(r) ? "tip" : "root") +
                  "; expected a root and a tip for every ray 1.." + std::to_string(n));
    std::vector<cv::Point2d> ray{roots[r]};
    if (inner.count(r)) ray.insert(ray.end(), inner[r].begin(), inner[r].end());
    ray.push_back(tips[r]);
    fin.rays.push_back(std::move(ray));
  }
  for (const auto& [id, pts] : inner)
    if (id < 1 || id > n) throw Error(fin.source + ": ray points of ray " + std::to_string(id) + ", which has no root and tip");
  for (const auto& [id, p] : tips)
    if (id > n) throw Error(fin.source + ": tip of ray " + std::to_string(id) + ", which has no root");
  if (scale.size() == 2) fin.scale_points = std::array<cv::Point2d, 2>{scale[1], scale[2]};
  else if (!scale.empty()) throw Error(fin.source + ": one scale point, expected two (scale,1 and scale,2) or none");
  return fin;
}

mesh::FinTemplate template_from_digitised(const DigitisedFin& fin, const DigitisedTemplateOptions& o,
                                          std::optional<cv::Size> image_size) {
  const std::string& src = fin.source;
  if (!(o.metres_per_px > 0)) throw Error(src + ": the image scale must be > 0 m per px");
  auto name = [](std::size_t r) { return "ray " + std::to_string(r + 1); };
  if (image_size) {
    auto check = [&](const cv::Point2d& p, const std::string& what) {
      if (p.x < -0.5 || p.y < -0.5 || p.x > image_size->width - 0.5 || p.y > image_size->height - 0.5)
        throw Error(src + ": " + what + " (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ") px lies outside the " +
                    std::to_string(image_size->width) + "x" + std::to_string(image_size->height) + " image");
    };
    for (const auto& p : fin.outline) check(p, "an outline point");
    for (std::size_t r = 0; r < fin.rays.size(); ++r)
      for (const auto& p : fin.rays[r]) check(p, "a point of " + name(r));
  }
  // Every ray inside the outline: first its digitised points (so the message names the root or
  // tip that is off), then the midpoints between them.
  for (const bool midpoints : {false, true})
    for (std::size_t r = 0; r < fin.rays.size(); ++r) {
      const auto& ray = fin.rays[r];
      for (std::size_t i = 0; i + (midpoints ? 1 : 0) < ray.size(); ++i) {
        const cv::Point2d p = midpoints ? 0.5 * (ray[i] + ray[i + 1]) : ray[i];
        const double d = signed_outline_distance(fin.outline, p);
        if (d > o.outline_tolerance_px) {
          const std::string what = midpoints ? "axis" : i == 0 ? "root" : i + 1 == ray.size() ? "tip" : "point " + std::to_string(i);
          throw Error(src + ": " + name(r) + " " + what + " (" + std::to_string(p.x) + ", " + std::to_string(p.y) + ") px lies " +
                      std::to_string(d) + " px outside the outline; expected every ray inside it (tolerance " +
                      std::to_string(o.outline_tolerance_px) + " px)");
        }
      }
    }
  // Fin-plane axes from the root segment (see the header).
  const cv::Point2d dorsal_root = fin.rays.front().front(), ventral_root = fin.rays.back().front();
  const double root_px = cv::norm(dorsal_root - ventral_root);
  if (root_px < 1e-6) throw Error(src + ": the roots of ray 1 and ray " + std::to_string(fin.rays.size()) + " coincide");
  const cv::Point2d zhat = (dorsal_root - ventral_root) / root_px, mid = 0.5 * (dorsal_root + ventral_root);
  cv::Point2d xhat(zhat.y, -zhat.x), tips(0, 0);
  for (const auto& ray : fin.rays) tips += ray.back() / static_cast<double>(fin.rays.size());
  if ((tips - mid).dot(xhat) < 0) xhat = -xhat;
  const double s = o.metres_per_px;
  auto plane = [&](const cv::Point2d& p) { return mesh::Point2{s * (p - mid).dot(xhat), s * (p - mid).dot(zhat)}; };

  const auto& q = o.sections;
  const int n = static_cast<int>(fin.rays.size());
  mesh::FinTemplate t;
  for (const auto& ray : fin.rays) t.chord = std::max(t.chord, plane(ray.back())[0]);
  if (!(t.chord > 0)) throw Error(src + ": the ray tips do not lie downstream of the root segment");
  t.membrane_thickness = q.membrane_thickness * t.chord;
  for (int r = 0; r < n; ++r) {
    std::vector<mesh::Point2> pts;
    for (const auto& p : fin.rays[static_cast<std::size_t>(r)]) pts.push_back(plane(p));
    pts.front()[0] = 0;  // onto the root segment
    // Evenly spaced in arc length along the digitised polyline.
    std::vector<double> cum(pts.size(), 0.0);
    for (std::size_t i = 1; i < pts.size(); ++i) cum[i] = cum[i - 1] + std::hypot(pts[i][0] - pts[i - 1][0], pts[i][1] - pts[i - 1][1]);
    mesh::Ray out;
    const double eta = n > 1 ? 1.0 - 2.0 * r / (n - 1) : 0.0;
    const double t_root = q.center_root_thickness + (q.edge_root_thickness - q.center_root_thickness) * eta * eta;
    std::size_t seg = 1;
    for (int k = 0; k < q.points_per_ray; ++k) {
      const double u = static_cast<double>(k) / (q.points_per_ray - 1), target = u * cum.back();
      while (seg + 1 < pts.size() && cum[seg] < target) ++seg;
      const double len = cum[seg] - cum[seg - 1], a = len > 0 ? std::clamp((target - cum[seg - 1]) / len, 0.0, 1.0) : 0.0;
      out.points.push_back({pts[seg - 1][0] + a * (pts[seg][0] - pts[seg - 1][0]), pts[seg - 1][1] + a * (pts[seg][1] - pts[seg - 1][1])});
      const double th = t_root * t.chord * (1.0 - (1.0 - q.tip_thickness_ratio) * u);
      out.sections.push_back({th, q.width_over_thickness * th});
    }
    out.points.front() = pts.front();
    out.points.back() = pts.back();
    t.rays.push_back(std::move(out));
  }
  mesh::validate(t, src);
  return t;
}

cv::Mat draw_digitised_fin(const cv::Mat& image, const DigitisedFin& fin) {
  cv::Mat out;
  if (image.channels() == 1) cv::cvtColor(image, out, cv::COLOR_GRAY2BGR);
  else out = image.clone();
  auto pt = [](const cv::Point2d& p) { return cv::Point(static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y))); };
  for (std::size_t i = 0; i < fin.outline.size(); ++i)
    cv::line(out, pt(fin.outline[i]), pt(fin.outline[(i + 1) % fin.outline.size()]), {255, 0, 0}, 1, cv::LINE_AA);
  for (const auto& ray : fin.rays) {
    for (std::size_t i = 0; i + 1 < ray.size(); ++i) cv::line(out, pt(ray[i]), pt(ray[i + 1]), {0, 0, 255}, 1, cv::LINE_AA);
    cv::circle(out, pt(ray.front()), 2, {0, 0, 255}, -1);
  }
  if (fin.scale_points) cv::line(out, pt((*fin.scale_points)[0]), pt((*fin.scale_points)[1]), {0, 160, 0}, 2);
  return out;
}

}  // namespace finverse::vision
