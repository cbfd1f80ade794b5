// A fin template from the user's own fish (issue 35 item 6): the spread fin photographed from the
// side, its outline and every ray's root and tip digitised in pixels (a CSV), and one scale, give
// the template.json that fin-synth, fin-track and fin-mesh read (mesh/fin_template.hpp).
//
// The fin plane's axes come from the rays themselves: z (dorsal) along the root segment from the
// root of the last ray to that of ray 1 (rays are numbered dorsal to ventral), x perpendicular to
// it towards the tips, the origin at the root segment's middle; so neither the image's orientation
// nor the side the fish was seen from matters. Interior roots are moved onto the root segment
// (the template's root is straight). Ray sections follow the parametric fin's law
// (mesh::make_caudal_fin: U-shaped root thickness across the fin, linear taper to the tip).
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "mesh/fin_template.hpp"

namespace finverse::vision {

// The CSV, one point a row, header "kind,id,x_px,y_px" (lines starting with # are comments):
//   outline,<order>,x,y   the fin's outline, in order around it (either direction)
//   root,<ray>,x,y        ray <ray>'s root (ray 1: the dorsal edge ray)
//   ray,<ray>,x,y         optional points along ray <ray>, root to tip, in file order
//   tip,<ray>,x,y         ray <ray>'s tip on the trailing edge
//   scale,<1|2>,x,y       optional: the two ends of a known distance (--scale-mm)
struct DigitisedFin {
  std::vector<cv::Point2d> outline;
  std::vector<std::vector<cv::Point2d>> rays;  // ray 1 first; root, inner points, tip (px)
  std::optional<std::array<cv::Point2d, 2>> scale_points;
  std::string source;  // the CSV, named in errors
};

// Throws finverse::Error naming the file and line when a row is malformed, a ray has no root or
// no tip, ray numbers leave gaps, or the outline has fewer than 3 points.
DigitisedFin read_digitised_fin(const std::filesystem::path& csv);

struct DigitisedTemplateOptions {
  double metres_per_px = 0;       // the image scale
  double outline_tolerance_px = 3;  // a ray point may lie this far outside the outline (digitising)
  mesh::CaudalFinParams sections;  // thickness law (fractions of the chord) and points per ray
};

// Throws finverse::Error naming the CSV when a ray leaves the outline (by more than the
// tolerance), a point lies outside the image (`image_size`, when given), or the template built
// from the rays is not valid (mesh::validate).
mesh::FinTemplate template_from_digitised(const DigitisedFin& fin, const DigitisedTemplateOptions& options,
                                          std::optional<cv::Size> image_size = std::nullopt);

// The image with the outline (blue), the rays (red, root marked) and the scale (green) drawn over
// it, to check the digitising by eye.
cv::Mat draw_digitised_fin(const cv::Mat& image, const DigitisedFin& fin);

}  // namespace finverse::vision
