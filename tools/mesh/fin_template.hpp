// The fin template: planform outline, fin rays and their sections, for the caudal fin of a
// juvenile rainbow trout (seed paper section 4.1, Fig. 9: 20 rays numbered 1 = dorsal edge to
// 20 = ventral edge, tapered, root thickness and taper "counted on the image").
//
// Geometry lives in the fin plane at rest, the x-z plane of DESIGN.md section 3 (+x downstream,
// z dorsal, y lateral = 0 at rest). Points here are 2-D (x, z) in metres.
//
// The planform is bounded by the root (the peduncle, a straight segment at x = 0 through every
// ray root), the two edge rays (rays 1 and n are the dorsal and ventral margins) and the trailing
// edge, the polyline through the ray tips. So the outline is derived from the rays: a template is
// its rays, and every quad between two neighbouring rays is membrane. That makes the outline, the
// structural mesh and the truth surface of fin-synth agree exactly along every ray and edge.
#pragma once

#include <array>
#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

namespace finverse::mesh {

using Point2 = std::array<double, 2>;  // (x, z) in the fin plane, metres

// Section of a ray: thickness in the flapping direction (y), width in the fin plane.
struct RaySection {
  double thickness = 0;
  double width = 0;
};

struct Ray {
  std::vector<Point2> points;        // root (index 0) to tip, on the trailing edge
  std::vector<RaySection> sections;  // one per point
};

struct FinTemplate {
  double chord = 0;               // c: root to the lobe tips along x, metres
  double membrane_thickness = 0;  // shell thickness of the membrane between the rays, metres
  std::vector<Ray> rays;          // ordered dorsal (ray 1) to ventral (ray n)

  std::size_t ray_count() const { return rays.size(); }
  // Arc-length fraction of each point of ray r (0 at the root, 1 at the tip).
  std::vector<double> arc_fractions(std::size_t r) const;
  // Section of ray r at arc-length fraction s in [0, 1] (linear between the ray's points).
  RaySection section(std::size_t r, double s) const;
  // Point of ray r at arc-length fraction s.
  Point2 point_at(std::size_t r, double s) const;
  // Root segment: dorsal end (root of ray 1) and ventral end (root of ray n).
  std::array<Point2, 2> root_segment() const;
  // Closed outline, counter-clockwise in the (x, z) plane, first point not repeated:
  // root of ray n -> ray n to its tip -> trailing edge through the tips -> ray 1 back to its root.
  std::vector<Point2> outline() const;
  double area() const;  // planform area, m^2
};

// Parameters of the parametric trout caudal fin. Lengths are in units of the chord unless the
// name says otherwise; defaults are the paper's fin (c = 1 cm, span 1.5 c, 20 rays) with the
// shape values we chose where the paper only shows a figure (see fin_template.cpp).
struct CaudalFinParams {
  double chord_m = 0.01;
  double height_over_chord = 1.5;   // dorsal-ventral distance between the lobe tips
  int rays = 20;
  double fork_depth = 0.25;         // how far the trailing-edge notch lies upstream of the lobe tips
  double root_height = 0.5;         // peduncle: dorsal-ventral extent of the root segment
  double edge_root_thickness = 0.04;    // thickest rays: the two margins
  double center_root_thickness = 0.015; // thinnest: the middle of the fin
  double tip_thickness_ratio = 0.2;     // thickness at the tip / at the root (linear taper)
  double width_over_thickness = 1.0;    // in-plane width of a ray section / its thickness
  double membrane_thickness = 0.005;
  int points_per_ray = 25;              // polyline points per ray, evenly spaced in arc length
};

// Builds the parametric fin; throws finverse::Error naming the parameter when it is out of range.
FinTemplate make_caudal_fin(const CaudalFinParams& p);

// Throws finverse::Error (one line, prefixed by `where`) unless the template is usable: at least
// two rays, matching section counts, positive sections and chord, rays that do not cross
// themselves or each other, and a simple (non-self-intersecting) outline.
void validate(const FinTemplate& t, const std::string& where = "fin template");

// JSON form, for planforms digitised from an image:
//   {"chord_m": 0.01, "membrane_thickness_m": 5e-5,
//    "rays": [{"points": [[x, z], ...], "thickness_m": [...], "width_m": [...]}, ...]}
nlohmann::json to_json(const FinTemplate& t);
FinTemplate from_json(const nlohmann::json& j, const std::string& where);
FinTemplate read_template(const std::filesystem::path& path);  // validated
void write_template(const std::filesystem::path& path, const FinTemplate& t);

}  // namespace finverse::mesh
