// Simulated checkerboard recordings through a camera rig and the scores of a calibration against
// the rig (see checkerboard_recording.hpp).
#include "vision/validation/checkerboard_recording.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <opencv2/calib3d.hpp>

#include "core/error.hpp"
#include "vision/charuco_board.hpp"

namespace finverse::vision {

namespace {

double uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

cv::Vec3d optical_axis(const Camera& c) { return c.rotation().t() * cv::Vec3d(0, 0, 1); }

// Rotation by `angle` about unit `axis` (Rodrigues).
cv::Matx33d axis_angle(const cv::Vec3d& axis, double angle) {
  cv::Matx33d R;
  cv::Rodrigues(axis * angle, R);
  return R;
}

cv::Vec3d any_perpendicular(const cv::Vec3d& n) {
  const cv::Vec3d a = std::abs(n[0]) < 0.9 ? cv::Vec3d(1, 0, 0) : cv::Vec3d(0, 1, 0);
  return cv::normalize(a - a.dot(n) * n);
}

bool fully_visible(const Camera& cam, const CheckerboardSpec& board, const cv::Matx33d& R, const cv::Vec3d& t) {
  const double mx = 0.08 * cam.width, my = 0.08 * cam.height;
  // The corners and the outer edge of the squares (one square beyond the corners).
  for (int j = -1; j <= board.rows; ++j)
    for (int i = -1; i <= board.cols; ++i) {
      if (i != -1 && i != board.cols && j != -1 && j != board.rows && (i + j) % 3) continue;
      double depth = 0;
      const auto p = cam.project(R * cv::Vec3d(i * board.square_m, j * board.square_m, 0) + t, &depth);
      if (depth <= 0 || p.x < mx || p.x > cam.width - mx || p.y < my || p.y > cam.height - my) return false;
    }
  const cv::Vec3d n = R * cv::Vec3d(0, 0, 1);
  const cv::Vec3d to_cam = cv::normalize(cam.center() - t);
  return std::abs(n.dot(to_cam)) > std::cos(70.0 * std::numbers::pi / 180);
}

}  // namespace

cv::Vec3d rig_focus(const std::vector<Camera>& cameras) {
  cv::Matx33d A = cv::Matx33d::zeros();
  cv::Vec3d b(0, 0, 0);
  for (const auto& c : cameras) {
    const cv::Vec3d d = optical_axis(c);
    const cv::Matx33d P = cv::Matx33d::eye() - d * d.t();
    A += P;
    b += P * c.center();
  }
  if (cameras.size() == 1) return cameras[0].center() + 0.5 * cv::norm(cameras[0].tvec) * optical_axis(cameras[0]);
  return A.solve(b, cv::DECOMP_SVD);
}

double board_square_for_rig(const std::vector<Camera>& cameras, const CheckerboardSpec& board, double fraction) {
  const cv::Vec3d focus = rig_focus(cameras);
  double extent = 1e30;
  for (const auto& c : cameras)
    extent = std::min(extent, std::min(c.width / c.K(0, 0), c.height / c.K(1, 1)) * cv::norm(focus - c.center()));
  return fraction * extent / (std::max(board.cols, board.rows) + 1);
}

std::vector<BoardPose> checkerboard_poses(const std::vector<Camera>& cameras, const CheckerboardSpec& board,
                                          const RecordingOptions& options) {
  const cv::Vec3d focus = rig_focus(cameras);
  const std::size_t n = cameras.size();
  // The first pose, the world board, faces the whole rig: a user lays it where every camera sees
  // it, and its pose from several views is what fixes the rig's orientation in the world.
  std::vector<std::vector<std::size_t>> aims(1);
  for (std::size_t i = 0; i < n; ++i) aims[0].push_back(i);
  for (std::size_t i = 0; i < n; ++i) aims.push_back({i});
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (n > 2) aims.push_back({i, j});
  const double extent = board.square_m * (std::max(board.cols, board.rows) + 1);
  const cv::Vec3d centre_local(0.5 * (board.cols - 1) * board.square_m, 0.5 * (board.rows - 1) * board.square_m, 0);
  std::mt19937_64 rng(options.seed);
  std::vector<BoardPose> poses;
  for (int k = 0; k < options.poses; ++k) {
    const auto& aim = aims[static_cast<std::size_t>(k) % aims.size()];
    cv::Vec3d n0(0, 0, 0);
    for (auto c : aim) n0 += cv::normalize(cameras[c].center() - focus);
    n0 = -cv::normalize(n0);  // board z into the board: away from the camera(s) seeing its front
    const double max_tilt = (aim.size() == 1 ? 1.0 : 0.4) * options.max_tilt_deg * std::numbers::pi / 180;
    bool ok = false;
    for (int attempt = 0; attempt < 500 && !ok; ++attempt) {
      const double shrink = 1.0 - attempt / 600.0;  // ever milder poses if the wild ones do not fit
      const cv::Vec3d e = any_perpendicular(n0);
      const cv::Vec3d tilt_axis = axis_angle(n0, 2 * std::numbers::pi * uniform(rng)) * e;
      const double tilt = shrink * max_tilt * std::sqrt(uniform(rng));
      const cv::Vec3d normal = axis_angle(tilt_axis, tilt) * n0;
      const cv::Vec3d e1 = axis_angle(normal, 2 * std::numbers::pi * uniform(rng)) * any_perpendicular(normal);
      const cv::Vec3d e2 = normal.cross(e1);
      const cv::Matx33d R(e1[0], e2[0], normal[0], e1[1], e2[1], normal[1], e1[2], e2[2], normal[2]);
      const cv::Vec3d offset((uniform(rng) - 0.5), (uniform(rng) - 0.5), (uniform(rng) - 0.5));
      const cv::Vec3d centre = focus + shrink * 0.3 * extent * offset;
      const cv::Vec3d t = centre - R * centre_local;
      ok = std::all_of(aim.begin(), aim.end(), [&](std::size_t c) { return fully_visible(cameras[c], board, R, t); });
      if (ok) {
        BoardPose p;
        cv::Rodrigues(R, p.rvec);
        p.tvec = t;
        poses.push_back(p);
      }
    }
    if (!ok) throw Error("checkerboard recording: no pose of the board fits the view(s) of " + cameras[aim[0]].name +
                         "; the board is too large for the rig");
  }
  return poses;
}

cv::Mat camera_sample_rays(const Camera& cam, int supersample) {
  const int s = std::max(1, supersample);
  const int W = cam.width * s, H = cam.height * s;
  cv::Mat pix(H * W, 1, CV_64FC2);
  for (int v = 0; v < H; ++v)
    for (int u = 0; u < W; ++u)
      pix.at<cv::Vec2d>(v * W + u) = cv::Vec2d((u + 0.5) / s - 0.5, (v + 0.5) / s - 0.5);
  cv::Mat rays;
  cv::undistortPoints(pix, rays, cv::Mat(cam.K), cv::Mat(cam.dist), cv::noArray(), cv::noArray(),
                          cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 50, 1e-14));
  return rays.reshape(2, H);
}

cv::Mat render_checkerboard(const Camera& cam, const cv::Mat& sample_rays, const CheckerboardSpec& board,
                            const BoardPose& pose, const RecordingOptions& options, std::uint64_t rng_seed) {
  const int s = std::max(1, options.supersample);
  cv::Matx33d R_bw;
  cv::Rodrigues(pose.rvec, R_bw);
  const cv::Matx33d R = cam.rotation() * R_bw;  // board -> camera
  const cv::Vec3d t = cam.rotation() * pose.tvec + cam.tvec;
  const cv::Vec3d n(R(0, 2), R(1, 2), R(2, 2));
  const double nt = n.dot(t), sq = board.square_m;
  constexpr double kBlack = 40, kWhite = 215, kBackground = 100, kBack = 150;
  cv::Mat img(cam.height, cam.width, CV_8U);
  // A ChArUco board: its printed image, sampled at the board coordinates (square (i, j) at
  // pixels (i + 1, j + 1) * pps: the corner numbering of charuco_board.hpp).
  constexpr int pps = 64;
  const cv::Mat printed = board.charuco.empty() ? cv::Mat() : charuco_image(board, pps);
  std::mt19937_64 rng(rng_seed);
  std::normal_distribution<double> noise(0.0, options.noise_sigma);
  for (int v = 0; v < cam.height; ++v)
    for (int u = 0; u < cam.width; ++u) {
      double sum = 0;
      for (int b = 0; b < s; ++b)
        for (int a = 0; a < s; ++a) {
          const cv::Vec2d xy = sample_rays.at<cv::Vec2d>(v * s + b, u * s + a);
          const cv::Vec3d d(xy[0], xy[1], 1.0);
          const double nd = n.dot(d);
          double grey = kBackground;
          if (std::abs(nd) > 1e-12 && nt / nd > 0) {
            const cv::Vec3d local = R.t() * ((nt / nd) * d - t);
            const double bx = local[0] / sq, by = local[1] / sq;
            const bool back = nd < 0;  // the board's z (into it) faces the camera: its plain back
            if (back && bx >= -2 && bx < board.cols + 1 && by >= -2 && by < board.rows + 1) {
              grey = kBack;
            } else if (back) {
            } else if (bx >= -1 && bx < board.cols && by >= -1 && by < board.rows) {
              const long i = static_cast<long>(std::floor(bx)) + 1, j = static_cast<long>(std::floor(by)) + 1;
              if (printed.empty()) {
                grey = (i + j) % 2 == 0 ? kBlack : kWhite;
              } else {
                const int px = std::clamp(static_cast<int>((bx + 1) * pps), 0, printed.cols - 1);
                const int py = std::clamp(static_cast<int>((by + 1) * pps), 0, printed.rows - 1);
                grey = printed.at<unsigned char>(py, px) < 128 ? kBlack : kWhite;
              }
            } else if (bx >= -2 && bx < board.cols + 1 && by >= -2 && by < board.rows + 1) {
              grey = kWhite;
            }
          }
          sum += grey;
        }
      const double value = sum / (s * s) + (options.noise_sigma > 0 ? noise(rng) : 0.0);
      img.at<unsigned char>(v, u) = cv::saturate_cast<unsigned char>(std::lround(value));
    }
  return img;
}

CameraError compare_cameras(const Camera& truth, const Camera& calibrated, const cv::Vec3d& centre, double volume_half_m) {
  CameraError e;
  e.centre_mm = 1000 * cv::norm(truth.center() - calibrated.center());
  const cv::Matx33d dR = calibrated.rotation() * truth.rotation().t();
  e.rotation_deg = std::acos(std::clamp(0.5 * (cv::trace(dR) - 1), -1.0, 1.0)) * 180 / std::numbers::pi;
  e.focal_rel = std::max(std::abs(calibrated.K(0, 0) / truth.K(0, 0) - 1), std::abs(calibrated.K(1, 1) / truth.K(1, 1) - 1));
  e.principal_px = std::hypot(calibrated.K(0, 2) - truth.K(0, 2), calibrated.K(1, 2) - truth.K(1, 2));
  double sum = 0;
  int count = 0;
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j)
      for (int k = -2; k <= 2; ++k) {
        const cv::Vec3d X = centre + 0.5 * volume_half_m * cv::Vec3d(i, j, k);
        const auto a = truth.project(X), b = calibrated.project(X);
        sum += (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y);
        ++count;
      }
  e.projection_rms_px = std::sqrt(sum / count);
  return e;
}

}  // namespace finverse::vision
