// Scores of fin-calibrate against the rig that made its input (see calibration_scores.hpp).
#include "vision/validation/calibration_scores.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "vision/anipose_import.hpp"
#include "vision/dlt_import.hpp"
#include "vision/validation/checkerboard_recording.hpp"

namespace finverse::vision {

namespace {

const Camera& named(const std::vector<Camera>& cams, const std::string& name, const std::string& where) {
  for (const auto& c : cams)
    if (c.name == name) return c;
  throw Error(where + ": no camera '" + name + "'");
}

// Half the smallest camera's field at the rig's focus: the working volume the scores sample.
double working_half(const std::vector<Camera>& cams, const cv::Vec3d& focus) {
  double h = 1e30;
  for (const auto& c : cams) h = std::min(h, 0.5 * c.width / c.K(0, 0) * cv::norm(focus - c.center()));
  return h;
}

}  // namespace

Summary calibration_validation_summary(const std::vector<Camera>& truth, const std::vector<Camera>& calibrated,
                                       const nlohmann::json& report, const std::filesystem::path& work_dir) {
  Summary s("validation", "footage_calibration",
            "fin-calibrate: checkerboard recording simulated through fin-synth's rig, DLTdv and Anipose imports");
  const std::string src = "issue 35 (Validation: calibration)";
  const cv::Vec3d focus = rig_focus(truth);
  const double half = working_half(truth, focus);
  for (const auto& t : truth) {
    const auto& c = named(calibrated, t.name, "calibrated cameras");
    double rms = 0;
    for (const auto& r : report.at("cameras"))
      if (r.at("view") == t.name) rms = std::max(r.at("intrinsic_rms_px").get<double>(), r.at("rig_rms_px").get<double>());
    const auto e = compare_cameras(t, c, focus, half);
    s.at_most(t.name + "_reprojection_rms", rms, 0.2, src, "px");
    s.at_most(t.name + "_centre_error", e.centre_mm, 0.5, src, "mm");
    s.at_most(t.name + "_rotation_error", e.rotation_deg, 0.1, src, "deg");
    s.info(t.name + "_focal_error", e.focal_rel);
    s.info(t.name + "_principal_point_error", e.principal_px, "px");
    s.info(t.name + "_volume_projection_rms", e.projection_rms_px, "px");
  }

  // Imports: the rig written in each format and read back must project like the rig.
  std::filesystem::create_directories(work_dir);
  std::vector<Camera> pinhole = truth;
  std::vector<DltCoefficients> dlt;
  for (auto& c : pinhole) {
    c.dist = {0, 0, 0, 0, 0};
    dlt.push_back(dlt_from_camera(c, DltOrigin::bottom_left, 1e-3));
  }
  write_dlt_file(work_dir / "rig_DLTcoefs.csv", dlt);
  const auto dlt_read = read_dlt_file(work_dir / "rig_DLTcoefs.csv");
  write_anipose_calibration(work_dir / "calibration.toml", truth, 1e-3);
  const auto anipose = read_anipose_calibration(work_dir / "calibration.toml", 1e-3);
  double dlt_px = 0, dlt_mm = 0, dlt_deg = 0, ani_px = 0, ani_mm = 0, ani_deg = 0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    const auto& t = pinhole[i];
    const auto d = compare_cameras(t, camera_from_dlt(dlt_read[i], t.name, t.width, t.height, DltOrigin::bottom_left, 1e-3,
                                                      "rig_DLTcoefs.csv"), focus, half);
    dlt_px = std::max(dlt_px, d.projection_rms_px), dlt_mm = std::max(dlt_mm, d.centre_mm), dlt_deg = std::max(dlt_deg, d.rotation_deg);
    const auto a = compare_cameras(truth[i], named(anipose, truth[i].name, "calibration.toml"), focus, half);
    ani_px = std::max(ani_px, a.projection_rms_px), ani_mm = std::max(ani_mm, a.centre_mm), ani_deg = std::max(ani_deg, a.rotation_deg);
  }
  s.at_most("dlt_import_projection_rms", dlt_px, 1e-3, src, "px");
  s.at_most("dlt_import_centre_error", dlt_mm, 0.5, src, "mm");
  s.at_most("dlt_import_rotation_error", dlt_deg, 0.1, src, "deg");
  s.at_most("anipose_import_projection_rms", ani_px, 1e-3, src, "px");
  s.at_most("anipose_import_centre_error", ani_mm, 0.5, src, "mm");
  s.at_most("anipose_import_rotation_error", ani_deg, 0.1, src, "deg");
  return s;
}

}  // namespace finverse::vision
