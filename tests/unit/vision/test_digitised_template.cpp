// A fin template from a digitised side-view image (vision/digitised_template.hpp): the parametric
// fin drawn into an image (rotated, scaled, seen from either side) and digitised as a CSV comes
// back as the same template; a ray outside the outline is refused naming the ray.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "mesh/fin_template.hpp"
#include "vision/digitised_template.hpp"

using namespace finverse;
using namespace finverse::vision;

namespace {

constexpr double kMetresPerPx = 2e-5;

// Fin plane (x, z) -> image px: rotated by `angle`, mirrored when `mirror` (the fish seen from its
// other side), origin at (300, 200).
cv::Point2d to_image(const mesh::Point2& p, double angle, bool mirror) {
  const double x = p[0] / kMetresPerPx, z = (mirror ? -1 : 1) * p[1] / kMetresPerPx;
  return {300 + std::cos(angle) * x + std::sin(angle) * z, 200 + std::sin(angle) * x - std::cos(angle) * z};
}

std::filesystem::path write_csv(const mesh::FinTemplate& t, double angle, bool mirror, const std::string& name,
                                int moved_tip_ray = -1) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream out(path);
  out.precision(12);
  out << "kind,id,x_px,y_px\n# digitised by hand\n";
  const auto outline = t.outline();
  for (std::size_t i = 0; i < outline.size(); ++i) {
    const auto p = to_image(outline[i], angle, mirror);
    out << "outline," << i << "," << p.x << "," << p.y << "\n";
  }
  for (std::size_t r = 0; r < t.rays.size(); ++r) {
    const auto& pts = t.rays[r].points;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      auto p = to_image(pts[i], angle, mirror);
      if (static_cast<int>(r) == moved_tip_ray && i + 1 == pts.size()) p = to_image({pts[i][0] * 1.3, pts[i][1]}, angle, mirror);
      out << (i == 0 ? "root" : i + 1 == pts.size() ? "tip" : "ray") << "," << r + 1 << "," << p.x << "," << p.y << "\n";
    }
  }
  return path;
}

mesh::FinTemplate parametric() {
  mesh::CaudalFinParams p;
  p.rays = 7;
  p.points_per_ray = 9;
  return mesh::make_caudal_fin(p);
}

}  // namespace

TEST(DigitisedTemplate, ImageOfTheParametricFinGivesItBack) {
  const auto truth = parametric();
  for (const bool mirror : {false, true}) {
    const auto csv = write_csv(truth, 0.4, mirror, "finverse_digitised_fin.csv");
    DigitisedTemplateOptions o;
    o.metres_per_px = kMetresPerPx;
    o.sections.points_per_ray = 9;
    const auto t = template_from_digitised(read_digitised_fin(csv), o, cv::Size(1200, 1200));
    ASSERT_EQ(t.ray_count(), truth.ray_count());
    EXPECT_NEAR(t.chord, truth.chord, 1e-9);
    EXPECT_NEAR(t.membrane_thickness, truth.membrane_thickness, 1e-12);
    // 1e-4 c: re-spacing the parametric ray's points along its polyline moves them ~1e-5 c.
    for (std::size_t r = 0; r < t.ray_count(); ++r)
      for (std::size_t i = 0; i < 9; ++i) {
        EXPECT_NEAR(t.rays[r].points[i][0], truth.rays[r].points[i][0], 1e-6) << "ray " << r + 1 << " point " << i;
        EXPECT_NEAR(t.rays[r].points[i][1], truth.rays[r].points[i][1], 1e-6) << "ray " << r + 1 << " point " << i;
        EXPECT_NEAR(t.rays[r].sections[i].thickness, truth.rays[r].sections[i].thickness, 1e-3 * truth.rays[r].sections[i].thickness);
      }
    std::filesystem::remove(csv);
  }
}

TEST(DigitisedTemplate, RayOutsideTheOutlineIsRefusedNamingIt) {
  const auto csv = write_csv(parametric(), 0.0, false, "finverse_digitised_bad.csv", 2);
  DigitisedTemplateOptions o;
  o.metres_per_px = kMetresPerPx;
  try {
    template_from_digitised(read_digitised_fin(csv), o);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("finverse_digitised_bad.csv"), std::string::npos) << what;
    EXPECT_NE(what.find("ray 3 tip"), std::string::npos) << what;
    EXPECT_NE(what.find("outside the outline"), std::string::npos) << what;
  }
  std::ofstream(csv) << "kind,id,x_px,y_px\noutline,0,1,1\noutline,1,5,1\noutline,2,5,5\nroot,1,2,2\ntip,1,4,2\nroot,2,2,3\n";
  EXPECT_THROW(read_digitised_fin(csv), Error);  // ray 2 has no tip
  std::filesystem::remove(csv);
}
