// A simulated checkerboard recording through a rig of cameras (validation of fin-calibrate, issue
// 35): board poses spread around the point the cameras look at, tilted towards one camera or a
// pair of cameras so every camera gets intrinsics-rich frames and every pair shares frames (the
// first pose, the world board, towards the whole rig), each
// view rendered through the camera model (distortion included) with sub-pixel anti-aliasing
// (supersample^2 rays per pixel, each intersected with the board plane) and seeded sensor noise.
// And the scores of a calibrated rig against the true one.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "vision/calibration.hpp"
#include "vision/camera.hpp"

namespace finverse::vision {

struct BoardPose {
  cv::Vec3d rvec, tvec;  // board -> world
};

struct RecordingOptions {
  int poses = 24;
  int supersample = 4;
  double noise_sigma = 1.0;  // 8-bit grey levels
  double max_tilt_deg = 35;  // away from facing the chosen camera(s)
  std::uint64_t seed = 1;
};

// The point nearest to every camera's optical axis (least squares): where the rig looks.
cv::Vec3d rig_focus(const std::vector<Camera>& cameras);

// A square side that makes the board about `fraction` of the narrowest view across at the focus.
double board_square_for_rig(const std::vector<Camera>& cameras, const CheckerboardSpec& board, double fraction);

// Poses each fully visible (every corner inside the image, 8 % margin) in the camera or pair
// they were aimed at. Deterministic in `seed`.
std::vector<BoardPose> checkerboard_poses(const std::vector<Camera>& cameras, const CheckerboardSpec& board,
                                          const RecordingOptions& options);

// The undistorted normalized ray (x/z, y/z) of every sub-pixel sample of `cam`, computed once per
// camera: CV_64FC2, (height * supersample) x (width * supersample).
cv::Mat camera_sample_rays(const Camera& cam, int supersample);

// One 8-bit grey image of the board in `pose` seen by `cam` (white margin of one square around the
// squares, a darker background). `rng_seed` seeds the noise of this image.
cv::Mat render_checkerboard(const Camera& cam, const cv::Mat& sample_rays, const CheckerboardSpec& board,
                            const BoardPose& pose, const RecordingOptions& options, std::uint64_t rng_seed);

// Differences of a calibrated camera from the true one.
struct CameraError {
  double centre_mm = 0, rotation_deg = 0, focal_rel = 0, principal_px = 0;
  double projection_rms_px = 0;  // of points in the working volume, true vs calibrated camera
};
CameraError compare_cameras(const Camera& truth, const Camera& calibrated, const cv::Vec3d& centre, double volume_half_m);

}  // namespace finverse::vision
