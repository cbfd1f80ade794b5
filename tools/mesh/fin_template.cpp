// The parametric trout caudal fin and the checks every template passes (seed paper section 4.1).
//
// Shape choices where the paper only shows a figure (Figs. 7 and 9): rays are quadratic Bezier
// curves that leave the narrow peduncle nearly parallel to the flow and fan out to the emarginate
// trailing edge, x_te(eta) = c (1 - d (1 - |eta|^1.5)), with eta = +1 at the dorsal tip and -1 at
// the ventral tip. Ray root thickness is U-shaped across the fin (edge rays thickest, as the paper
// finds the largest flexural rigidity at the margins) and tapers linearly to the tip ("tapering
// angle" in the paper).
#include "mesh/fin_template.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace finverse::mesh {
namespace {

double dist(const Point2& a, const Point2& b) { return std::hypot(a[0] - b[0], a[1] - b[1]); }

double orient(const Point2& a, const Point2& b, const Point2& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

bool on_segment(const Point2& a, const Point2& b, const Point2& p) {
  return std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0]) && std::min(a[1], b[1]) <= p[1] &&
         p[1] <= std::max(a[1], b[1]);
}

// Closed-segment intersection (touching counts).
bool segments_intersect(const Point2& p1, const Point2& p2, const Point2& q1, const Point2& q2) {
  const double d1 = orient(q1, q2, p1), d2 = orient(q1, q2, p2), d3 = orient(p1, p2, q1), d4 = orient(p1, p2, q2);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) return true;
  if (d1 == 0 && on_segment(q1, q2, p1)) return true;
  if (d2 == 0 && on_segment(q1, q2, p2)) return true;
  if (d3 == 0 && on_segment(p1, p2, q1)) return true;
  if (d4 == 0 && on_segment(p1, p2, q2)) return true;
  return false;
}

bool inside_polygon(const std::vector<Point2>& poly, const Point2& p) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    if ((poly[i][1] > p[1]) != (poly[j][1] > p[1]) &&
        p[0] < (poly[j][0] - poly[i][0]) * (p[1] - poly[i][1]) / (poly[j][1] - poly[i][1]) + poly[i][0])
      in = !in;
  }
  return in;
}

double signed_area(const std::vector<Point2>& poly) {
  double a = 0;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
    a += poly[j][0] * poly[i][1] - poly[i][0] * poly[j][1];
  return 0.5 * a;
}

std::string ray_name(std::size_t r) { return "ray " + std::to_string(r + 1); }

// Resamples a dense curve to n points evenly spaced in arc length.
std::vector<Point2> resample(const std::vector<Point2>& dense, int n) {
  std::vector<double> cum(dense.size(), 0.0);
  for (std::size_t i = 1; i < dense.size(); ++i) cum[i] = cum[i - 1] + dist(dense[i - 1], dense[i]);
  std::vector<Point2> out;
  std::size_t seg = 1;
  for (int k = 0; k < n; ++k) {
    const double target = cum.back() * k / (n - 1);
    while (seg + 1 < dense.size() && cum[seg] < target) ++seg;
    const double len = cum[seg] - cum[seg - 1];
    const double u = len > 0 ? std::clamp((target - cum[seg - 1]) / len, 0.0, 1.0) : 0.0;
    out.push_back({dense[seg - 1][0] + u * (dense[seg][0] - dense[seg - 1][0]),
                   dense[seg - 1][1] + u * (dense[seg][1] - dense[seg - 1][1])});
  }
  out.front() = dense.front();  // exact ends: roots lie on the root segment, tips on the trailing edge
  out.back() = dense.back();
  return out;
}

}  // namespace

std::vector<double> FinTemplate::arc_fractions(std::size_t r) const {
  const auto& pts = rays.at(r).points;
  std::vector<double> s(pts.size(), 0.0);
  for (std::size_t i = 1; i < pts.size(); ++i) s[i] = s[i - 1] + dist(pts[i - 1], pts[i]);
  const double total = s.back();
  for (auto& v : s) v = total > 0 ? v / total : 0.0;
  s.back() = 1.0;
  return s;
}

namespace {
// Index i and weight u with s between fractions[i] and fractions[i+1].
std::pair<std::size_t, double> locate(const std::vector<double>& f, double s) {
  s = std::clamp(s, 0.0, 1.0);
  const auto it = std::upper_bound(f.begin(), f.end(), s);
  std::size_t i = it == f.begin() ? 0 : static_cast<std::size_t>(it - f.begin()) - 1;
  i = std::min(i, f.size() - 2);
  const double len = f[i + 1] - f[i];
  return {i, len > 0 ? std::clamp((s - f[i]) / len, 0.0, 1.0) : 0.0};
}
}  // namespace

RaySection FinTemplate::section(std::size_t r, double s) const {
  const auto [i, u] = locate(arc_fractions(r), s);
  const auto& a = rays[r].sections[i];
  const auto& b = rays[r].sections[i + 1];
  return {a.thickness + u * (b.thickness - a.thickness), a.width + u * (b.width - a.width)};
}

Point2 FinTemplate::point_at(std::size_t r, double s) const {
  const auto [i, u] = locate(arc_fractions(r), s);
  const auto& a = rays[r].points[i];
  const auto& b = rays[r].points[i + 1];
  return {a[0] + u * (b[0] - a[0]), a[1] + u * (b[1] - a[1])};
}

std::array<Point2, 2> FinTemplate::root_segment() const {
  return {rays.front().points.front(), rays.back().points.front()};
}

std::vector<Point2> FinTemplate::outline() const {
  std::vector<Point2> out;
  const auto& ventral = rays.back().points;
  out.insert(out.end(), ventral.begin(), ventral.end());
  for (std::size_t r = rays.size() - 1; r-- > 1;) out.push_back(rays[r].points.back());
  const auto& dorsal = rays.front().points;
  out.insert(out.end(), dorsal.rbegin(), dorsal.rend());
  return out;
}

double FinTemplate::area() const { return signed_area(outline()); }

FinTemplate make_caudal_fin(const CaudalFinParams& p) {
  auto require = [](bool ok, const std::string& what) {
    if (!ok) throw Error("fin template: " + what);
  };
  require(p.rays >= 2, "--rays " + std::to_string(p.rays) + ": expected at least 2 (the edge rays bound the planform)");
  require(std::isfinite(p.chord_m) && p.chord_m > 0, "--chord: expected > 0 m");
  require(std::isfinite(p.height_over_chord) && p.height_over_chord > 0, "--height-over-chord: expected > 0");
  require(p.fork_depth >= 0 && p.fork_depth < 1, "--fork-depth: expected 0 to 1 chords (1 excluded)");
  require(p.root_height > 0 && p.root_height <= p.height_over_chord,
          "--root-height: expected > 0 and at most --height-over-chord");
  require(p.edge_root_thickness > 0 && p.center_root_thickness > 0,
          "--edge-ray-thickness, --center-ray-thickness: expected > 0");
  require(p.tip_thickness_ratio > 0 && p.tip_thickness_ratio <= 1, "--tip-thickness-ratio: expected > 0 and at most 1");
  require(p.width_over_thickness > 0, "--ray-width-ratio: expected > 0");
  require(p.membrane_thickness > 0, "--membrane-thickness: expected > 0");
  require(p.points_per_ray >= 2 && p.points_per_ray <= 1000,
          "--ray-points " + std::to_string(p.points_per_ray) + ": expected 2 to 1000 points per ray");
  // Fish fins carry 5-40 rays; thousands would mesh for hours (and overlap at the root).
  require(p.rays <= 200, "--rays " + std::to_string(p.rays) + ": expected at most 200 (a fin has a few dozen)");

  const double c = p.chord_m;
  FinTemplate t;
  t.chord = c;
  t.membrane_thickness = p.membrane_thickness * c;
  for (int i = 0; i < p.rays; ++i) {
    const double eta = 1.0 - 2.0 * i / (p.rays - 1);  // +1 dorsal edge, -1 ventral edge
    const Point2 root{0.0, 0.5 * p.root_height * c * eta};
    const Point2 tip{c * (1.0 - p.fork_depth * (1.0 - std::pow(std::abs(eta), 1.5))), 0.5 * p.height_over_chord * c * eta};
    // Control point: the ray leaves the peduncle nearly axially and fans out distally.
    const Point2 ctrl{0.45 * tip[0], root[1] + 0.3 * (tip[1] - root[1])};
    std::vector<Point2> dense;
    const int nd = 50 * p.points_per_ray;
    for (int k = 0; k <= nd; ++k) {
      const double u = static_cast<double>(k) / nd;
      const double a = (1 - u) * (1 - u), b = 2 * u * (1 - u), d = u * u;
      dense.push_back({a * root[0] + b * ctrl[0] + d * tip[0], a * root[1] + b * ctrl[1] + d * tip[1]});
    }
    Ray ray;
    ray.points = resample(dense, p.points_per_ray);
    const double t_root = p.center_root_thickness + (p.edge_root_thickness - p.center_root_thickness) * eta * eta;
    t.rays.push_back(std::move(ray));
    const auto s = t.arc_fractions(t.rays.size() - 1);
    for (double si : s) {
      const double th = t_root * c * (1.0 - (1.0 - p.tip_thickness_ratio) * si);
      t.rays.back().sections.push_back({th, p.width_over_thickness * th});
    }
  }
  validate(t, "fin template");
  return t;
}

void validate(const FinTemplate& t, const std::string& where) {
  auto fail = [&](const std::string& what) { throw Error(where + ": " + what); };
  if (t.rays.size() < 2)
    fail("has " + std::to_string(t.rays.size()) + " rays, expected at least 2 (the edge rays bound the planform)");
  if (!(std::isfinite(t.chord) && t.chord > 0)) fail("--chord: expected > 0 m");
  if (!(std::isfinite(t.membrane_thickness) && t.membrane_thickness > 0)) fail("membrane thickness must be > 0 m");
  for (std::size_t r = 0; r < t.rays.size(); ++r) {
    const auto& ray = t.rays[r];
    if (ray.points.size() < 2) fail(ray_name(r) + " has " + std::to_string(ray.points.size()) + " points, expected >= 2");
    if (ray.sections.size() != ray.points.size())
      fail(ray_name(r) + " has " + std::to_string(ray.sections.size()) + " sections for " +
           std::to_string(ray.points.size()) + " points");
    for (const auto& p : ray.points)
      if (!std::isfinite(p[0]) || !std::isfinite(p[1])) fail(ray_name(r) + " has a non-finite point");
    for (std::size_t i = 1; i < ray.points.size(); ++i)
      if (dist(ray.points[i - 1], ray.points[i]) <= 1e-9 * t.chord) fail(ray_name(r) + " has repeated points");
    for (const auto& s : ray.sections)
      if (!(s.thickness > 0 && s.width > 0)) fail(ray_name(r) + " has a section with thickness or width <= 0");
  }
  const auto poly = t.outline();
  if (signed_area(poly) <= 0)
    fail("outline has non-positive signed area: rays must run from the dorsal edge (ray 1) to the ventral edge");

  // The outline must be simple: no two non-adjacent edges may touch.
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j) {
      if (j == i + 1 || (i == 0 && j == n - 1)) continue;
      if (segments_intersect(poly[i], poly[(i + 1) % n], poly[j], poly[(j + 1) % n]))
        fail("planform outline self-intersects (edges " + std::to_string(i) + " and " + std::to_string(j) +
             "): the rays or the trailing edge cross");
    }

  // Interior rays: roots on the root segment, inside the outline, crossing neither each other
  // nor the outline (they may touch it only at their root and tip).
  const auto root = t.root_segment();
  const double root_len = dist(root[0], root[1]);
  if (root_len <= 0) fail("the root segment (roots of ray 1 and ray n) has zero length");
  for (std::size_t r = 1; r + 1 < t.rays.size(); ++r) {
    const auto& pts = t.rays[r].points;
    if (std::abs(orient(root[0], root[1], pts.front())) / root_len > 1e-6 * t.chord ||
        !on_segment(root[0], root[1], pts.front()))
      fail(ray_name(r) + " does not start on the root segment between the roots of ray 1 and ray " +
           std::to_string(t.rays.size()));
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
      const Point2 mid{0.5 * (pts[i][0] + pts[i + 1][0]), 0.5 * (pts[i][1] + pts[i + 1][1])};
      if (!inside_polygon(poly, mid)) fail(ray_name(r) + " leaves the planform");
      for (std::size_t k = 0; k < n; ++k) {
        const bool touches_root = (i == 0 && k == n - 1);  // outline edge n-1 is the root segment
        if (touches_root) continue;
        const Point2& a = poly[k];
        const Point2& b = poly[(k + 1) % n];
        // The tip is an outline vertex: its two trailing-edge edges touch the last segment there.
        if (i + 2 == pts.size() && (dist(a, pts.back()) == 0 || dist(b, pts.back()) == 0)) continue;
        if (segments_intersect(pts[i], pts[i + 1], a, b))
          fail(ray_name(r) + " crosses the planform outline");
      }
    }
  }
  for (std::size_t r = 0; r < t.rays.size(); ++r)
    for (std::size_t q = r + 1; q < t.rays.size(); ++q) {
      const auto& a = t.rays[r].points;
      const auto& b = t.rays[q].points;
      for (std::size_t i = 0; i + 1 < a.size(); ++i)
        for (std::size_t j = 0; j + 1 < b.size(); ++j)
          if (segments_intersect(a[i], a[i + 1], b[j], b[j + 1]))
            fail(ray_name(r) + " and " + ray_name(q) + " cross: the planform self-intersects");
    }
}

nlohmann::json to_json(const FinTemplate& t) {
  nlohmann::json j;
  j["chord_m"] = t.chord;
  j["membrane_thickness_m"] = t.membrane_thickness;
  j["rays"] = nlohmann::json::array();
  for (const auto& r : t.rays) {
    nlohmann::json jr;
    jr["points"] = nlohmann::json::array();
    jr["thickness_m"] = nlohmann::json::array();
    jr["width_m"] = nlohmann::json::array();
    for (std::size_t i = 0; i < r.points.size(); ++i) {
      jr["points"].push_back({r.points[i][0], r.points[i][1]});
      jr["thickness_m"].push_back(r.sections[i].thickness);
      jr["width_m"].push_back(r.sections[i].width);
    }
    j["rays"].push_back(jr);
  }
  return j;
}

FinTemplate from_json(const nlohmann::json& j, const std::string& where) {
  FinTemplate t;
  try {
    t.chord = j.at("chord_m").get<double>();
    t.membrane_thickness = j.at("membrane_thickness_m").get<double>();
    for (const auto& jr : j.at("rays")) {
      Ray r;
      for (const auto& p : jr.at("points")) {
        if (p.size() != 2) throw Error(where + ": ray points must be [x, z] pairs");
        r.points.push_back({p[0].get<double>(), p[1].get<double>()});
      }
      const auto& th = jr.at("thickness_m");
      const auto& w = jr.at("width_m");
      if (th.size() != w.size()) throw Error(where + ": thickness_m and width_m differ in length");
      for (std::size_t i = 0; i < th.size(); ++i) r.sections.push_back({th[i].get<double>(), w[i].get<double>()});
      t.rays.push_back(std::move(r));
    }
  } catch (const nlohmann::json::exception& e) {
    throw Error(where + ": expected {chord_m, membrane_thickness_m, rays: [{points, thickness_m, width_m}]}: " +
                std::string(e.what()));
  }
  validate(t, where);
  return t;
}

FinTemplate read_template(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw Error(path.string() + ": cannot open fin template");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw Error(path.string() + ": not valid JSON: " + std::string(e.what()));
  }
  return from_json(j, path.string());
}

void write_template(const std::filesystem::path& path, const FinTemplate& t) {
  write_text_atomic(path, to_json(t).dump(1) + "\n");
}

}  // namespace finverse::mesh
