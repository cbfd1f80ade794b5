// fin-calibrate's library: checkerboard calibration of a simulated recording, DLTdv and Anipose
// imports of a known rig, and the one-line errors on bad recordings.
#include <cmath>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include "core/error.hpp"
#include "vision/anipose_import.hpp"
#include "vision/calibration.hpp"
#include "vision/camera.hpp"
#include "vision/charuco_board.hpp"
#include "vision/dlt_import.hpp"
#include "vision/rig_bundle_adjustment.hpp"
#include "vision/validation/checkerboard_recording.hpp"

namespace fs = std::filesystem;
using namespace finverse;
using namespace finverse::vision;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("finverse_test_calibration_" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

std::vector<Camera> pinhole_rig() {
  auto rig = default_rig({"side", "back", "ventral"}, 0.01, 640, 480);
  for (auto& c : rig) c.dist = {0, 0, 0, 0, 0};
  return rig;
}

}  // namespace

TEST(DltImport, CoefficientsOfAKnownRigGiveItsCameras) {
  const auto rig = pinhole_rig();
  std::vector<DltCoefficients> coeffs;
  for (const auto& c : rig) coeffs.push_back(dlt_from_camera(c, DltOrigin::bottom_left, 1e-3));
  const fs::path dir = scratch("dlt");
  write_dlt_file(dir / "rig_DLTcoefs.csv", coeffs);
  const auto read = read_dlt_file(dir / "rig_DLTcoefs.csv");
  ASSERT_EQ(read.size(), 3u);
  const cv::Vec3d X(0.004, 0.002, -0.003);  // metres: 4, 2, -3 mm
  for (std::size_t i = 0; i < rig.size(); ++i) {
    const auto& L = read[i];
    // The DLT equations themselves, in DLTdv's frame (mm, v up from the bottom edge).
    const double x = 4, y = 2, z = -3, den = L[8] * x + L[9] * y + L[10] * z + 1;
    const double u = (L[0] * x + L[1] * y + L[2] * z + L[3]) / den, v = (L[4] * x + L[5] * y + L[6] * z + L[7]) / den;
    const auto p = rig[i].project(X);
    EXPECT_NEAR(u, p.x, 1e-6);
    EXPECT_NEAR(v, rig[i].height - p.y, 1e-6);
    const Camera c = camera_from_dlt(L, rig[i].name, rig[i].width, rig[i].height, DltOrigin::bottom_left, 1e-3, "test");
    EXPECT_NEAR(cv::norm(c.center() - rig[i].center()), 0.0, 1e-9);
    EXPECT_NEAR(cv::norm(cv::Mat(c.rotation() - rig[i].rotation())), 0.0, 1e-9);
    EXPECT_NEAR(cv::norm(cv::Mat(c.K - rig[i].K)), 0.0, 1e-6);
  }
}

TEST(DltImport, RejectsAFileWithoutElevenRows) {
  const fs::path dir = scratch("dlt_bad");
  std::ofstream(dir / "bad.csv") << "1,2\n3,4\n";
  try {
    read_dlt_file(dir / "bad.csv");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("expected 11 rows"), std::string::npos);
  }
}

TEST(AniposeImport, ReadsAniposelibsLayout) {
  // As aniposelib's CameraGroup.dump writes it (python toml: trailing commas, nested arrays).
  const fs::path dir = scratch("anipose");
  std::ofstream(dir / "calibration.toml")
      << "[cam_0]\nname = \"A\"\nsize = [ 1280, 1024,]\n"
         "matrix = [ [ 1500.5, 0.0, 640.25,], [ 0.0, 1501.5, 512.75,], [ 0.0, 0.0, 1.0,],]\n"
         "distortions = [ -0.1, 0.02, 0.001, -0.002, 0.0,]\nrotation = [ 0.1, -0.2, 0.3,]\n"
         "translation = [ 10.0, -20.0, 300.0,]\n\n"
         "[cam_1]\nname = \"B\"\nsize = [ 640, 480,]\n"
         "matrix = [ [ 800.0, 0.0, 320.0,], [ 0.0, 800.0, 240.0,], [ 0.0, 0.0, 1.0,],]\n"
         "distortions = [ 0.0, 0.0, 0.0, 0.0, 0.0,]\nrotation = [ 0.0, 1.5707963267948966, 0.0,]\n"
         "translation = [ 0.0, 0.0, 250.0,]\n\n[metadata]\nadjusted = true\nerror = 0.42\n";
  const auto cams = read_anipose_calibration(dir / "calibration.toml", 1e-3);
  ASSERT_EQ(cams.size(), 2u);
  EXPECT_EQ(cams[0].name, "A");
  EXPECT_EQ(cams[0].width, 1280);
  EXPECT_EQ(cams[0].height, 1024);
  EXPECT_DOUBLE_EQ(cams[0].K(1, 2), 512.75);
  EXPECT_DOUBLE_EQ(cams[0].dist[3], -0.002);
  EXPECT_DOUBLE_EQ(cams[0].rvec[2], 0.3);
  EXPECT_NEAR(cams[0].tvec[2], 0.3, 1e-15);  // 300 mm
  EXPECT_EQ(cams[1].name, "B");
  EXPECT_NEAR(cams[1].rvec[1], 1.5707963267948966, 1e-15);
}

TEST(AniposeImport, WrittenRigReadsBackAndFisheyeIsRefused) {
  const auto rig = default_rig({"side", "back"}, 0.01, 320, 240);
  const fs::path dir = scratch("anipose_rt");
  write_anipose_calibration(dir / "calibration.toml", rig, 1e-3);
  const auto back = read_anipose_calibration(dir / "calibration.toml", 1e-3);
  ASSERT_EQ(back.size(), 2u);
  for (int i = 0; i < 2; ++i) EXPECT_NEAR(cv::norm(back[i].center() - rig[i].center()), 0.0, 1e-12);
  std::ofstream(dir / "fish.toml") << "[cam_0]\nname = \"A\"\nfisheye = true\nsize = [ 10, 10,]\n";
  EXPECT_THROW(read_anipose_calibration(dir / "fish.toml", 1e-3), Error);
}

TEST(CheckerboardCalibration, SimulatedRecordingGivesBackTheRig) {
  // Two cameras of fin-synth's rig at a small resolution: intrinsics, the chain and the world board.
  const auto rig = default_rig({"side", "back"}, 0.01, 400, 400);
  CalibrationOptions opt;
  opt.board = parse_board("9x6", 1.0, "--board");
  opt.board.square_m = board_square_for_rig(rig, opt.board, 0.45);
  RecordingOptions rec;
  rec.poses = 18;
  rec.supersample = 3;
  const auto poses = checkerboard_poses(rig, opt.board, rec);
  opt.world_frame = 0;
  opt.board_rvec = poses[0].rvec;
  opt.board_tvec = poses[0].tvec;
  std::vector<BoardObservations> obs;
  for (std::size_t c = 0; c < rig.size(); ++c) {
    const cv::Mat rays = camera_sample_rays(rig[c], rec.supersample);
    CameraRecording r;
    r.view = rig[c].name;
    r.source = "memory/" + r.view;
    for (std::size_t k = 0; k < poses.size(); ++k) r.frames.push_back(render_checkerboard(rig[c], rays, opt.board, poses[k], rec, 10 * c + k));
    obs.push_back(detect_checkerboard(r, opt.board));
  }
  const auto result = calibrate_rig(obs, opt);
  EXPECT_LT(result.max_rms_px(), 0.2);
  for (std::size_t c = 0; c < rig.size(); ++c) {
    const auto e = compare_cameras(rig[c], result.cameras[c], rig_focus(rig), 0.005);
    // Guard, not the goal (graded in the footage_calibration validation): 18 poses of two
    // 400 px cameras measured 0.67 / 0.55 mm, 0.072 / 0.049 deg with the bundle adjustment and the
    // world board fitted in both views (one view alone gave 0.18 deg). A mis-ordered grid: ~180 deg.
    EXPECT_LT(e.centre_mm, 1.0) << rig[c].name;
    EXPECT_LT(e.rotation_deg, 0.15) << rig[c].name;
  }
}

TEST(CheckerboardCalibration, BadRecordingsNameTheirSource) {
  CheckerboardSpec board = parse_board("9x6", 0.001, "--board");
  CameraRecording r;
  r.view = "side";
  r.source = "rec/side";
  r.frames = {cv::Mat(100, 120, CV_8U, cv::Scalar(128)), cv::Mat(100, 121, CV_8U, cv::Scalar(128))};
  try {
    detect_checkerboard(r, board);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("rec/side: frame 1 is 121x100"), std::string::npos) << e.what();
  }
  r.frames.pop_back();
  const auto obs = detect_checkerboard(r, board);
  try {
    calibrate_rig({obs}, CalibrationOptions{});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("rec/side: checkerboard 9x6 found in 0 frames"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_board("6x6", 0.001, "--board"), Error);
}

TEST(CharucoBoard, CornersAreFoundAndNumberedLikeTheBoard) {
  // One rendered view of a ChArUco board: its corners, identified by the markers, land where the
  // board's corners of the same index project (a wrong numbering or frame would be squares off).
  const auto rig = default_rig({"side"}, 0.01, 400, 400);
  CheckerboardSpec board = parse_board("9x6", 1.0, "--board");
  board.charuco = "4X4_50";
  check_charuco(board);
  board.square_m = board_square_for_rig(rig, board, 0.6);
  RecordingOptions rec;
  rec.poses = 1;
  rec.supersample = 2;
  const auto pose = checkerboard_poses(rig, board, rec)[0];
  CameraRecording r;
  r.view = "side";
  r.source = "memory/side";
  r.frames = {render_checkerboard(rig[0], camera_sample_rays(rig[0], rec.supersample), board, pose, rec, 3)};
  const auto obs = detect_checkerboard(r, board);
  ASSERT_EQ(obs.found(), 1);
  const auto& corners = obs.corners[0];
  const auto& ids = obs.ids[0];
  ASSERT_GE(2 * ids.size(), static_cast<std::size_t>(board.cols * board.rows));
  cv::Matx33d R;
  cv::Rodrigues(pose.rvec, R);
  const auto object = board.corners();
  double worst = 0;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    const cv::Point3f& o = object[static_cast<std::size_t>(ids[k])];
    const auto p = rig[0].project(R * cv::Vec3d(o.x, o.y, o.z) + pose.tvec);
    worst = std::max(worst, std::hypot(p.x - corners[k].x, p.y - corners[k].y));
  }
  EXPECT_LT(worst, 0.5) << ids.size() << " corners";  // measured 0.24 px (25 px squares)
  board.charuco = "9X9_1";
  EXPECT_THROW(check_charuco(board), Error);
}

TEST(RigBundleAdjustment, ExactCornersGiveBackPerturbedPoses) {
  // Three cameras of fin-synth's rig, in the first camera's frame; eight board poses seen by all
  // of them, corners projected exactly. Camera poses and board poses start perturbed (1e-3 rad,
  // 0.1 mm: pixels off); the adjustment must bring every camera back.
  auto rig = default_rig({"side", "back", "ventral"}, 0.01, 400, 400);
  const cv::Matx33d R0 = rig[0].rotation();
  const cv::Vec3d t0 = rig[0].tvec;
  CheckerboardSpec board = parse_board("9x6", 0.0004, "--board");
  const auto object = board.corners();
  RigState truth, start;
  for (auto& c : rig) {  // world -> camera becomes root camera -> camera
    const cv::Matx33d R = c.rotation() * R0.t();
    cv::Rodrigues(R, c.rvec);
    c.tvec = c.tvec - R * t0;
  }
  truth.cameras = rig;
  const cv::Vec3d focus = R0 * rig_focus(default_rig({"side", "back", "ventral"}, 0.01, 400, 400)) + t0;
  std::vector<std::vector<std::vector<cv::Point2f>>> image(3);
  for (int k = 0; k < 8; ++k) {
    truth.board_r.emplace_back(0.3 * std::sin(k), 0.2 * std::cos(k), 0.1 * k);
    truth.board_t.push_back(focus + cv::Vec3d(1e-3 * (k % 3), -1e-3 * (k % 2), 5e-4 * k) - cv::Vec3d(0.0016, 0.001, 0));
  }
  std::vector<RigObservation> obs;
  for (std::size_t c = 0; c < 3; ++c) {
    image[c].resize(8);
    for (std::size_t k = 0; k < 8; ++k) {
      cv::Vec3d r, t;
      cv::composeRT(truth.board_r[k], truth.board_t[k], rig[c].rvec, rig[c].tvec, r, t);
      cv::projectPoints(object, r, t, cv::Mat(rig[c].K), cv::Mat(rig[c].dist), image[c][k]);
    }
  }
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t k = 0; k < 8; ++k) obs.push_back({c, k, object, &image[c][k]});
  start = truth;
  for (std::size_t c = 1; c < 3; ++c) start.cameras[c].rvec += cv::Vec3d(1e-3, -1e-3, 1e-3), start.cameras[c].tvec += cv::Vec3d(1e-4, 0, -1e-4);
  for (std::size_t k = 0; k < 8; ++k) start.board_r[k] += cv::Vec3d(0, 1e-3, 0), start.board_t[k] += cv::Vec3d(0, 1e-4, 0);
  BundleOptions o;
  o.intrinsics = false;
  const auto rms = bundle_adjust_rig(start, obs, o);
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_LT(rms[c], 1e-3) << rig[c].name;
    EXPECT_LT(cv::norm(start.cameras[c].rvec - truth.cameras[c].rvec), 1e-6) << rig[c].name;
    EXPECT_LT(cv::norm(start.cameras[c].tvec - truth.cameras[c].tvec), 1e-7) << rig[c].name;
  }
}
