// Calibrated pinhole cameras in OpenCV conventions (DESIGN.md section 3, "Cameras"): intrinsics
// K, distortion (k1, k2, p1, p2, k3), rvec/tvec mapping world to camera, image y down; stored in
// cameras.yml through cv::FileStorage. The default rig is the paper's three views of the caudal
// fin (section 4.1, Fig. 7: side, back and ventral).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace finverse::vision {

struct Camera {
  std::string name;
  int width = 0, height = 0;
  cv::Matx33d K = cv::Matx33d::eye();
  cv::Vec<double, 5> dist{0, 0, 0, 0, 0};  // k1 k2 p1 p2 k3
  cv::Vec3d rvec{0, 0, 0}, tvec{0, 0, 0};  // world -> camera

  cv::Matx33d rotation() const;  // Rodrigues(rvec)
  cv::Vec3d center() const;      // camera centre in world coordinates
  // The same projection as cv::projectPoints; `depth` gets the camera-frame z (> 0 in front).
  cv::Point2d project(const cv::Vec3d& world, double* depth = nullptr) const;
};

// Camera at `eye` looking at `target` with world direction `up` appearing upward in the image.
Camera look_at(const std::string& name, int width, int height, double focal_px, const cv::Vec3d& eye,
               const cv::Vec3d& target, const cv::Vec3d& up);

// The paper's views of a fin of chord c (root at x = 0, span along z): "side" (from -y, flow to
// the right), "back" (from downstream, +x), "ventral" (from below, -z) and "dorsal" (from above,
// +z: the 2-D mode's lab clips, issue 47). Each sees a square of
// about 2.2 c around the fin with mild barrel distortion, as a macro lens would give. A wider
// field (half_field chords either side of the aim point at x = centre_x chords) frames the whole
// fish, as a 2-D swimming clip does.
std::vector<Camera> default_rig(const std::vector<std::string>& views, double chord, int width, int height,
                                double half_field = 1.1, double centre_x = 0.5);

// Validation of the calibration's influence: every principal point shifted by `px` pixels in a
// direction drawn (uniformly) from `seed`, one draw per camera in order.
void perturb_principal_points(std::vector<Camera>& cameras, double px, std::uint64_t seed);

void write_cameras(const std::filesystem::path& yml, const std::vector<Camera>& cameras);
std::vector<Camera> read_cameras(const std::filesystem::path& yml);

}  // namespace finverse::vision
