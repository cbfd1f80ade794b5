// Calibration of a multi-camera rig from synchronized recordings of a planar checkerboard (issue
// 35 item 2), through OpenCV calib3d: corners found per frame (findChessboardCorners, refined by
// cornerSubPix), intrinsics per camera (calibrateCamera, Zhang's method), the cameras chained to
// each other through the frames they share (stereoCalibrate with the intrinsics fixed, along a
// spanning tree of the camera pairs with most shared frames), and the world frame placed by one
// frame's board (its pose in the world given by the user: the board laid in the flume's axes),
// whose pose is fitted to its corners in every camera that sees it. Between the two, a bundle
// adjustment refines every camera and board pose over all frames (rig_bundle_adjustment.hpp).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "vision/camera.hpp"

namespace finverse::vision {

// A checkerboard of cols x rows inner corners, squares of side square_m. Board frame: corner
// (i, j) at (i * square_m, j * square_m, 0), i along a row, z = x cross y into the board (OpenCV's
// convention: away from a camera that sees the printed side); the square before corner (0, 0) is black.
struct CheckerboardSpec {
  int cols = 9, rows = 6;
  double square_m = 0.0015;
  std::string charuco;           // ArUco dictionary of a ChArUco board (charuco_board.hpp); empty: plain
  double marker_fraction = 0.75;  // ChArUco: marker side / square side
  std::vector<cv::Point3f> corners() const;
};

// Parses "COLSxROWS" (inner corners), e.g. "9x6"; throws naming `flag` otherwise.
CheckerboardSpec parse_board(const std::string& text, double square_m, const std::string& flag);

// One camera's recording: the image files or video frames in order, frame k of every camera taken
// at the same instant. `source` names the directory or video in messages.
struct CameraRecording {
  std::string view;
  std::string source;
  std::vector<cv::Mat> frames;  // grey, 8-bit
};

// Frames of a directory (images sorted by the number in their names, any numbering) or of a video
// file (every `every`-th frame). Throws finverse::Error naming `path` when nothing is readable.
CameraRecording read_recording(const std::string& view, const std::filesystem::path& path, int every = 1);

// The board's inner corners found in each frame of one camera (empty where not found).
struct BoardObservations {
  std::string view, source;
  cv::Size image_size;
  std::vector<std::vector<cv::Point2f>> corners;  // per frame
  // Per frame, the index (CheckerboardSpec::corners()) of each corner found; empty: all of them
  // in order (a plain checkerboard is found whole; a ChArUco board may be seen in part).
  std::vector<std::vector<int>> ids;
  int found() const;
};

// Throws finverse::Error naming the recording when frames differ in size.
BoardObservations detect_checkerboard(const CameraRecording& rec, const CheckerboardSpec& board);

struct CalibrationOptions {
  CheckerboardSpec board;
  bool fix_k3 = true;          // narrow lenses cannot separate k3 from k1, k2
  bool fit_tangential = false;  // nor tangential distortion from the principal point
  int world_frame = -1;     // frame whose board defines the world; -1: the first seen by most cameras
  cv::Vec3d board_rvec{0, 0, 0}, board_tvec{0, 0, 0};  // that board's pose: board -> world
  int min_shared_frames = 3;  // to chain two cameras
  bool bundle_adjust = true;  // then refine the whole rig at once (rig_bundle_adjustment.hpp)
  bool bundle_intrinsics = false;  // ... its intrinsics too
};

struct CameraCalibrationReport {
  std::string view;
  int frames_found = 0;
  double intrinsic_rms_px = 0;  // calibrateCamera's RMS corner reprojection error
  double rig_rms_px = 0;        // RMS over its frames in the rig: after the bundle adjustment, or of
                                // its stereoCalibrate link (0 for the root) without it
  std::string chained_from;     // the camera it was chained to ("" for the one that sees the world board)
  int shared_frames = 0;
};

struct RigCalibration {
  std::vector<Camera> cameras;
  std::vector<CameraCalibrationReport> reports;
  int world_frame = -1;
  double max_rms_px() const;
};

// The board description a user writes once for a rig (and the simulated recording writes):
//   {"board": "9x6", "square_mm": 1.5, "world_frame": 0,
//    "board_rvec": [rx, ry, rz], "board_tvec_mm": [tx, ty, tz]}
// board_rvec/board_tvec_mm: the world board's pose (board -> world); world_frame optional (-1).
void write_board_file(const std::filesystem::path& json, const CalibrationOptions& options);
CalibrationOptions read_board_file(const std::filesystem::path& json);

// The per-camera reports as JSON (report.json beside cameras.yml).
std::string rig_report_json(const RigCalibration& rig);

// Throws finverse::Error naming the recording when a camera never sees the board, when a camera
// cannot be chained to the world board (no path of pairs sharing min_shared_frames frames), or
// when the world frame is not seen by any camera.
RigCalibration calibrate_rig(const std::vector<BoardObservations>& observations, const CalibrationOptions& options);

}  // namespace finverse::vision
