// Checkerboard calibration of a camera rig (OpenCV calib3d; Zhang 2000 for the intrinsics,
// stereoCalibrate with fixed intrinsics for each link of the chain between cameras).
#include "vision/calibration.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <set>
#include <tuple>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "vision/charuco_board.hpp"
#include "vision/image_file.hpp"
#include "vision/rig_bundle_adjustment.hpp"
#include "vision/video_clip.hpp"

namespace finverse::vision {

namespace fs = std::filesystem;

std::vector<cv::Point3f> CheckerboardSpec::corners() const {
  std::vector<cv::Point3f> out;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i)
      out.emplace_back(static_cast<float>(i * square_m), static_cast<float>(j * square_m), 0.f);
  return out;
}

CheckerboardSpec parse_board(const std::string& text, double square_m, const std::string& flag) {
  CheckerboardSpec b;
  const auto x = text.find_first_of("xX");
  try {
    if (x == std::string::npos) throw std::invalid_argument(text);
    b.cols = std::stoi(text.substr(0, x));
    b.rows = std::stoi(text.substr(x + 1));
  } catch (const std::exception&) {
    throw Error(flag + ": '" + text + "', expected COLSxROWS inner corners, e.g. 9x6");
  }
  if (b.cols < 3 || b.rows < 3 || b.cols == b.rows)
    throw Error(flag + ": '" + text + "', expected at least 3x3 inner corners and cols != rows (so the board has one orientation)");
  if (!(square_m > 0)) throw Error("--square-mm: expected the board's square side > 0");
  b.square_m = square_m;
  return b;
}

namespace {

// The last number in a file name, so frame_1, frame_2, ..., frame_10 sort as numbers.
long frame_number(const fs::path& p) {
  const std::string s = p.stem().string();
  long value = -1;
  for (std::size_t i = 0; i < s.size();) {
    if (std::isdigit(static_cast<unsigned char>(s[i]))) {
      std::size_t j = i;
      while (j < s.size() && std::isdigit(static_cast<unsigned char>(s[j]))) ++j;
      value = std::stol(s.substr(i, std::min<std::size_t>(j - i, 15)));
      i = j;
    } else {
      ++i;
    }
  }
  return value;
}

// A camera of the rig as seen from the root camera (root -> camera: R, t) and the board's
// corners it found in one frame.
struct RigView {
  const Camera* camera;
  cv::Matx33d R;
  cv::Vec3d t;
  std::vector<cv::Point3f> object;  // the board corners it found
  const std::vector<cv::Point2f>* corners;
};

// Gauss-Newton on the board's pose in the root camera's frame (R_b, t_b: board -> root camera)
// over the reprojection errors of its corners in every view; returns their RMS (px).
double refine_board_pose(const std::vector<RigView>& views, cv::Matx33d& R_b, cv::Vec3d& t_b) {
  auto residuals = [&](const cv::Vec3d& rv, const cv::Vec3d& tv) {
    cv::Matx33d R;
    cv::Rodrigues(rv, R);
    std::vector<double> r;
    for (const auto& v : views) {
      cv::Vec3d rvec;
      cv::Rodrigues(v.R * R, rvec);
      const cv::Vec3d tvec = v.R * tv + v.t;
      std::vector<cv::Point2f> p;
      cv::projectPoints(v.object, rvec, tvec, cv::Mat(v.camera->K), cv::Mat(v.camera->dist), p);
      for (std::size_t i = 0; i < p.size(); ++i) r.push_back(p[i].x - (*v.corners)[i].x), r.push_back(p[i].y - (*v.corners)[i].y);
    }
    return r;
  };
  cv::Vec3d rv, tv = t_b;
  cv::Rodrigues(R_b, rv);
  auto r = residuals(rv, tv);
  auto sq = [](const std::vector<double>& x) { double s = 0; for (double e : x) s += e * e; return s; };
  for (int it = 0; it < 20; ++it) {
    cv::Mat J(static_cast<int>(r.size()), 6, CV_64F);
    for (int k = 0; k < 6; ++k) {
      cv::Vec3d drv = rv, dtv = tv;
      const double h = k < 3 ? 1e-7 : 1e-7 * std::max(1e-3, cv::norm(tv));
      (k < 3 ? drv[k] : dtv[k - 3]) += h;
      const auto rp = residuals(drv, dtv);
      for (std::size_t i = 0; i < r.size(); ++i) J.at<double>(static_cast<int>(i), k) = (rp[i] - r[i]) / h;
    }
    cv::Mat delta;
    if (!cv::solve(J, -cv::Mat(r), delta, cv::DECOMP_SVD)) break;
    const cv::Vec3d nrv = rv + cv::Vec3d(delta.ptr<double>()), ntv = tv + cv::Vec3d(delta.ptr<double>() + 3);
    const auto nr = residuals(nrv, ntv);
    if (sq(nr) >= sq(r)) break;
    rv = nrv, tv = ntv, r = nr;
  }
  cv::Rodrigues(rv, R_b);
  t_b = tv;
  return std::sqrt(sq(r) / std::max<std::size_t>(1, r.size() / 2));
}

bool is_image(const fs::path& p) {
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e == ".png" || e == ".jpg" || e == ".jpeg" || e == ".tif" || e == ".tiff" || e == ".bmp" || e == ".pgm";
}

}  // namespace

CameraRecording read_recording(const std::string& view, const fs::path& path, int every) {
  CameraRecording rec;
  rec.view = view;
  rec.source = path.string();
  if (every < 1) throw Error("--every: expected >= 1");
  if (fs::is_directory(path)) {
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(path))
      if (e.is_regular_file() && is_image(e.path())) files.push_back(e.path());
    std::sort(files.begin(), files.end(), [](const fs::path& a, const fs::path& b) {
      const long na = frame_number(a), nb = frame_number(b);
      return na != nb ? na < nb : a.filename() < b.filename();
    });
    for (std::size_t k = 0; k < files.size(); k += static_cast<std::size_t>(every)) {
      rec.frames.push_back(read_image(files[k], cv::IMREAD_GRAYSCALE));
    }
  } else if (fs::is_regular_file(path)) {
    const VideoClip clip(path);  // throws naming the file when it cannot decode it
    for (long k = 0; k < clip.frames(); k += every) rec.frames.push_back(clip.grey(k));
  } else {
    throw Error(path.string() + ": no such directory or video (view " + view + ")");
  }
  if (rec.frames.empty()) throw Error(path.string() + ": no readable frames (view " + view + ")");
  return rec;
}

int BoardObservations::found() const {
  return static_cast<int>(std::count_if(corners.begin(), corners.end(), [](const auto& c) { return !c.empty(); }));
}

BoardObservations detect_checkerboard(const CameraRecording& rec, const CheckerboardSpec& board) {
  BoardObservations obs;
  obs.view = rec.view;
  obs.source = rec.source;
  obs.image_size = rec.frames.front().size();
  const cv::Size pattern(board.cols, board.rows);
  for (std::size_t k = 0; k < rec.frames.size(); ++k) {
    const cv::Mat& img = rec.frames[k];
    if (img.size() != obs.image_size)
      throw Error(rec.source + ": frame " + std::to_string(k) + " is " + std::to_string(img.cols) + "x" +
                  std::to_string(img.rows) + ", expected " + std::to_string(obs.image_size.width) + "x" +
                  std::to_string(obs.image_size.height) + " like the first frame");
    std::vector<cv::Point2f> c;
    std::vector<int> ids;  // empty: every corner, in order
    const bool charuco = !board.charuco.empty();
    bool ok = false;
    if (charuco) {
      detect_charuco_corners(img, board, c, ids);
      ok = !c.empty();
    } else {
      ok = cv::findChessboardCorners(img, pattern, c, cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_FAST_CHECK);
    }
    if (ok) {
      // Sub-pixel window: under half the smallest corner spacing, so it never reaches a neighbour.
      std::map<int, std::size_t> at;
      for (std::size_t k = 0; k < c.size(); ++k) at[ids.empty() ? static_cast<int>(k) : ids[k]] = k;
      double spacing = 1e9;
      for (const auto& [id, k] : at)
        for (const int next : {id % board.cols + 1 < board.cols ? id + 1 : -1, id + board.cols})
          if (const auto it = at.find(next); next >= 0 && it != at.end()) spacing = std::min<double>(spacing, cv::norm(c[it->second] - c[k]));
      // On a ChArUco board the markers start (1 - marker_fraction) / 2 of a square from a corner.
      const double reach = charuco ? 0.45 * (1 - board.marker_fraction) : 0.4;
      const int half = std::clamp(static_cast<int>(reach * spacing), 2, 12);
      cv::cornerSubPix(img, c, cv::Size(half, half), cv::Size(-1, -1),
                       cv::TermCriteria(cv::TermCriteria::EPS | cv::TermCriteria::COUNT, 100, 1e-4));
    }
    if (ok && !charuco) {
      // findChessboardCorners may list the grid in any of its symmetries. The board frame is
      // OpenCV's (z into the board, seen from its printed side): x then y turn clockwise in the
      // image, so a mirrored listing has its rows reversed; and the square before corner (0, 0) is
      // black, so a listing from the far corner (a half turn) is reversed whole.
      auto axes = [&] { return std::pair{c[1] - c[0], c[static_cast<std::size_t>(board.cols)] - c[0]}; };
      auto [dx, dy] = axes();
      if (dx.x * dy.y - dx.y * dy.x < 0)
        for (int j = 0; j < board.rows; ++j) std::reverse(c.begin() + j * board.cols, c.begin() + (j + 1) * board.cols);
      std::tie(dx, dy) = axes();
      auto grey = [&](cv::Point2f p) {
        const int x = std::clamp(static_cast<int>(std::lround(p.x)), 0, img.cols - 1);
        const int y = std::clamp(static_cast<int>(std::lround(p.y)), 0, img.rows - 1);
        return static_cast<int>(img.at<unsigned char>(y, x));
      };
      if (grey(c[0] - 0.5f * dx - 0.5f * dy) > grey(c[0] + 0.5f * dx - 0.5f * dy)) std::reverse(c.begin(), c.end());
    }
    obs.corners.push_back(ok ? c : std::vector<cv::Point2f>{});
    obs.ids.push_back(ok ? ids : std::vector<int>{});
  }
  return obs;
}

void write_board_file(const fs::path& json, const CalibrationOptions& o) {
  nlohmann::json j;
  j["board"] = std::to_string(o.board.cols) + "x" + std::to_string(o.board.rows);
  j["square_mm"] = 1000 * o.board.square_m;
  if (!o.board.charuco.empty()) j["charuco"] = o.board.charuco, j["marker_fraction"] = o.board.marker_fraction;
  j["world_frame"] = o.world_frame;
  j["board_rvec"] = {o.board_rvec[0], o.board_rvec[1], o.board_rvec[2]};
  j["board_tvec_mm"] = {1000 * o.board_tvec[0], 1000 * o.board_tvec[1], 1000 * o.board_tvec[2]};
  write_text_atomic(json, j.dump(1) + "\n");
}

CalibrationOptions read_board_file(const fs::path& json) {
  const std::string where = json.string();
  std::ifstream in(json);
  if (!in) throw Error(where + ": cannot open the board description");
  CalibrationOptions o;
  try {
    const auto j = nlohmann::json::parse(in);
    o.board = parse_board(j.at("board").get<std::string>(), 1e-3 * j.at("square_mm").get<double>(), where + ": board");
    o.board.charuco = j.value("charuco", std::string());
    o.board.marker_fraction = j.value("marker_fraction", 0.75);
    if (!o.board.charuco.empty()) try {
        check_charuco(o.board);
      } catch (const Error& e) {
        throw Error(where + ": " + e.what());
      }
    o.world_frame = j.value("world_frame", -1);
    if (j.contains("board_rvec")) {
      const auto r = j.at("board_rvec").get<std::vector<double>>();
      const auto t = j.at("board_tvec_mm").get<std::vector<double>>();
      if (r.size() != 3 || t.size() != 3) throw Error(where + ": board_rvec and board_tvec_mm must have 3 numbers each");
      for (int i = 0; i < 3; ++i) o.board_rvec[i] = r[static_cast<std::size_t>(i)], o.board_tvec[i] = 1e-3 * t[static_cast<std::size_t>(i)];
    }
  } catch (const nlohmann::json::exception& e) {
    throw Error(where + ": expected {board: \"COLSxROWS\", square_mm, world_frame, board_rvec, board_tvec_mm}: " + std::string(e.what()));
  }
  return o;
}

std::string rig_report_json(const RigCalibration& rig) {
  nlohmann::json j;
  j["world_frame"] = rig.world_frame;
  j["max_rms_px"] = rig.max_rms_px();
  for (const auto& r : rig.reports)
    j["cameras"].push_back({{"view", r.view}, {"frames_found", r.frames_found}, {"intrinsic_rms_px", r.intrinsic_rms_px},
                            {"rig_rms_px", r.rig_rms_px}, {"chained_from", r.chained_from}, {"shared_frames", r.shared_frames}});
  return j.dump(1) + "\n";
}

double RigCalibration::max_rms_px() const {
  double m = 0;
  for (const auto& r : reports) m = std::max({m, r.intrinsic_rms_px, r.rig_rms_px});
  return m;
}

RigCalibration calibrate_rig(const std::vector<BoardObservations>& observations, const CalibrationOptions& options) {
  const std::size_t n = observations.size();
  if (n == 0) throw Error("fin-calibrate: no camera recordings given");
  const auto object = options.board.corners();
  RigCalibration rig;
  rig.cameras.resize(n);
  rig.reports.resize(n);
  std::vector<std::vector<cv::Vec3d>> board_rvec(n), board_tvec(n);  // per camera, per frame
  std::size_t frames = 0;
  for (const auto& o : observations) frames = std::max(frames, o.corners.size());
  // Indices of the corners camera c found in frame k (all of them when ids are not given).
  auto ids_of = [&](std::size_t c, std::size_t k) {
    const auto& o = observations[c];
    std::vector<int> ids = k < o.ids.size() ? o.ids[k] : std::vector<int>{};
    if (ids.empty())
      for (int i = 0; i < static_cast<int>(o.corners[k].size()); ++i) ids.push_back(i);
    return ids;
  };
  auto object_of = [&](std::size_t c, std::size_t k) {
    std::vector<cv::Point3f> out;
    for (int i : ids_of(c, k)) out.push_back(object.at(static_cast<std::size_t>(i)));
    return out;
  };

  for (std::size_t c = 0; c < n; ++c) {
    const auto& o = observations[c];
    std::vector<std::vector<cv::Point3f>> obj;
    std::vector<std::vector<cv::Point2f>> img;
    std::vector<std::size_t> frame_of;
    for (std::size_t k = 0; k < o.corners.size(); ++k)
      if (!o.corners[k].empty()) obj.push_back(object_of(c, k)), img.push_back(o.corners[k]), frame_of.push_back(k);
    if (img.size() < 3)
      throw Error(o.source + ": checkerboard " + std::to_string(options.board.cols) + "x" + std::to_string(options.board.rows) +
                  " found in " + std::to_string(img.size()) + " frames, expected at least 3 (view " + o.view + ")");
    cv::Mat K, dist;
    std::vector<cv::Mat> rvecs, tvecs;
    int flags = (options.fix_k3 ? cv::CALIB_FIX_K3 : 0) | (options.fit_tangential ? 0 : cv::CALIB_ZERO_TANGENT_DIST);
    const double rms = cv::calibrateCamera(obj, img, o.image_size, K, dist, rvecs, tvecs, flags,
                                           cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 200, 1e-12));
    Camera& cam = rig.cameras[c];
    cam.name = o.view;
    cam.width = o.image_size.width;
    cam.height = o.image_size.height;
    for (int i = 0; i < 9; ++i) cam.K(i / 3, i % 3) = K.at<double>(i);
    for (int i = 0; i < 5; ++i) cam.dist[i] = i < static_cast<int>(dist.total()) ? dist.at<double>(i) : 0.0;
    board_rvec[c].assign(frames, cv::Vec3d(0, 0, 0));
    board_tvec[c].assign(frames, cv::Vec3d(0, 0, 0));
    for (std::size_t i = 0; i < frame_of.size(); ++i) {
      board_rvec[c][frame_of[i]] = cv::Vec3d(rvecs[i]);
      board_tvec[c][frame_of[i]] = cv::Vec3d(tvecs[i]);
    }
    rig.reports[c] = {o.view, static_cast<int>(img.size()), rms, 0.0, "", 0};
    log::info(o.view + ": board in " + std::to_string(img.size()) + " of " +
              std::to_string(o.corners.size()) + " frames, intrinsic RMS " + std::to_string(rms) + " px");
  }

  auto seen = [&](std::size_t c, std::size_t k) { return k < observations[c].corners.size() && !observations[c].corners[k].empty(); };
  int w = options.world_frame;
  if (w >= 0) {
    bool any = false;
    for (std::size_t c = 0; c < n; ++c) any = any || seen(c, static_cast<std::size_t>(w));
    if (!any) throw Error("--world-frame " + std::to_string(w) + ": no camera found the checkerboard in that frame");
  } else {
    std::size_t best = 0;
    for (std::size_t k = 0; k < frames; ++k) {
      std::size_t count = 0;
      for (std::size_t c = 0; c < n; ++c) count += seen(c, k);
      if (count > best) best = count, w = static_cast<int>(k);
    }
  }
  rig.world_frame = w;
  std::size_t root = 0;
  while (!seen(root, static_cast<std::size_t>(w))) ++root;

  // The cameras are first chained in the root camera's frame (R_wc, t_wc: root -> camera); the
  // world board then places the whole rig at once (below).
  std::vector<cv::Matx33d> R_wc(n, cv::Matx33d::eye());
  std::vector<cv::Vec3d> t_wc(n, cv::Vec3d(0, 0, 0));
  std::vector<bool> placed(n, false);
  placed[root] = true;

  // Grow the tree: each step links the unplaced camera sharing most frames with a placed one.
  for (std::size_t step = 1; step < n; ++step) {
    std::size_t bi = n, bj = n, best = 0;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) {
        if (!placed[i] || placed[j]) continue;
        std::size_t shared = 0;
        for (std::size_t k = 0; k < frames; ++k) shared += seen(i, k) && seen(j, k);
        if (shared > best) best = shared, bi = i, bj = j;
      }
    if (bi == n || best < static_cast<std::size_t>(options.min_shared_frames)) {
      std::string missing;
      for (std::size_t j = 0; j < n; ++j)
        if (!placed[j]) missing += (missing.empty() ? "" : ", ") + observations[j].source;
      throw Error(missing + ": shares fewer than " + std::to_string(options.min_shared_frames) +
                  " checkerboard frames with the cameras chained to the world board; record the board where two cameras see it at once");
    }
    // Frames whose single-view board poses disagree with the others about where camera j sits
    // relative to camera i (a board seen from behind, a mis-ordered detection) are left out.
    std::vector<std::size_t> shared_frames;
    std::vector<cv::Matx33d> Rk;
    std::vector<cv::Vec3d> tk;
    for (std::size_t k = 0; k < frames; ++k)
      if (seen(bi, k) && seen(bj, k)) {
        cv::Matx33d Ri, Rj;
        cv::Rodrigues(board_rvec[bi][k], Ri);
        cv::Rodrigues(board_rvec[bj][k], Rj);
        shared_frames.push_back(k);
        Rk.push_back(Rj * Ri.t());
        tk.push_back(board_tvec[bj][k] - Rk.back() * board_tvec[bi][k]);
      }
    auto agree = [&](std::size_t a, std::size_t b) {
      const cv::Matx33d d = Rk[a] * Rk[b].t();
      const double angle = std::acos(std::clamp(0.5 * (cv::trace(d) - 1), -1.0, 1.0));
      return angle < 2.0 * CV_PI / 180 && cv::norm(tk[a] - tk[b]) < 0.02 * std::max(cv::norm(tk[a]), cv::norm(tk[b]));
    };
    std::size_t centre = 0, support = 0;
    for (std::size_t a = 0; a < Rk.size(); ++a) {
      std::size_t count = 0;
      for (std::size_t b = 0; b < Rk.size(); ++b) count += agree(a, b);
      if (count > support) support = count, centre = a;
    }
    std::vector<std::vector<cv::Point3f>> obj;
    std::vector<std::vector<cv::Point2f>> img_i, img_j;
    for (std::size_t a = 0; a < shared_frames.size(); ++a) {
      const std::size_t k = shared_frames[a];
      if (agree(a, centre)) {
        // The corners both cameras found (a ChArUco board may be seen in part).
        const auto ids_i = ids_of(bi, k), ids_j = ids_of(bj, k);
        std::vector<cv::Point3f> o;
        std::vector<cv::Point2f> pi, pj;
        for (std::size_t x = 0, y = 0; x < ids_i.size() && y < ids_j.size();) {
          if (ids_i[x] < ids_j[y]) ++x;
          else if (ids_j[y] < ids_i[x]) ++y;
          else {
            o.push_back(object[static_cast<std::size_t>(ids_i[x])]);
            pi.push_back(observations[bi].corners[k][x++]), pj.push_back(observations[bj].corners[k][y++]);
          }
        }
        if (o.size() >= 6) obj.push_back(o), img_i.push_back(pi), img_j.push_back(pj);
      } else
        log::warn(observations[bj].view + ": frame " + std::to_string(k) + " left out of the link to " + observations[bi].view +
                  ": its board pose disagrees with the other shared frames");
    }
    best = obj.size();
    if (best < static_cast<std::size_t>(options.min_shared_frames))
      throw Error(observations[bj].source + ": only " + std::to_string(best) + " consistent checkerboard frames shared with " +
                  observations[bi].source + ", expected at least " + std::to_string(options.min_shared_frames));
    cv::Mat Ki(rig.cameras[bi].K), Kj(rig.cameras[bj].K), di(rig.cameras[bi].dist), dj(rig.cameras[bj].dist);
    cv::Mat R, T, E, F;
    const double rms = cv::stereoCalibrate(obj, img_i, img_j, Ki, di, Kj, dj, observations[bi].image_size, R, T, E, F,
                                           cv::CALIB_FIX_INTRINSIC,
                                           cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 200, 1e-12));
    const cv::Matx33d Rij(R);
    const cv::Vec3d Tij(T);
    R_wc[bj] = Rij * R_wc[bi];
    t_wc[bj] = Rij * t_wc[bi] + Tij;
    placed[bj] = true;
    auto& rep = rig.reports[bj];
    rep.rig_rms_px = rms;
    rep.chained_from = observations[bi].view;
    rep.shared_frames = static_cast<int>(best);
    log::info(observations[bj].view + " chained to " + observations[bi].view + " over " +
              std::to_string(best) + " shared frames, RMS " + std::to_string(rms) + " px");
  }
  if (options.bundle_adjust) {
    // Start: the chained cameras, each frame's board where the first camera that saw it put it.
    RigState st;
    st.cameras = rig.cameras;
    st.board_r.assign(frames, cv::Vec3d(0, 0, 0));
    st.board_t.assign(frames, cv::Vec3d(0, 0, 0));
    std::vector<RigObservation> obs;
    for (std::size_t c = 0; c < n; ++c) cv::Rodrigues(R_wc[c], st.cameras[c].rvec), st.cameras[c].tvec = t_wc[c];
    for (std::size_t k = 0; k < frames; ++k) {
      bool placed_board = false;
      for (std::size_t c = 0; c < n; ++c) {
        if (!seen(c, k)) continue;
        if (!placed_board) {
          cv::Matx33d R_bc;
          cv::Rodrigues(board_rvec[c][k], R_bc);
          cv::Rodrigues(R_wc[c].t() * R_bc, st.board_r[k]);
          st.board_t[k] = R_wc[c].t() * (board_tvec[c][k] - t_wc[c]);
          placed_board = true;
        }
        obs.push_back({c, k, object_of(c, k), &observations[c].corners[k]});
      }
    }
    BundleOptions bo;
    bo.root = root, bo.fix_k3 = options.fix_k3, bo.fit_tangential = options.fit_tangential, bo.intrinsics = options.bundle_intrinsics;
    const auto rms = bundle_adjust_rig(st, obs, bo);
    for (std::size_t c = 0; c < n; ++c) {
      rig.cameras[c].K = st.cameras[c].K, rig.cameras[c].dist = st.cameras[c].dist;
      cv::Rodrigues(st.cameras[c].rvec, R_wc[c]);
      t_wc[c] = st.cameras[c].tvec;
      rig.reports[c].rig_rms_px = rms[c];
      log::info(observations[c].view + ": RMS " + std::to_string(rms[c]) + " px after the rig's bundle adjustment");
    }
    board_rvec[root][w] = st.board_r[w], board_tvec[root][w] = st.board_t[w];  // the world board, in the root's frame
  }

  // World: the world board's pose in the root camera's frame, fitted to its corners in every
  // camera that found it (one view alone leaves its tilt uncertain, and that error rotates the
  // whole rig), composed with the given board -> world pose.
  std::vector<RigView> world_views;
  for (std::size_t c = 0; c < n; ++c)
    if (seen(c, static_cast<std::size_t>(w)))
      world_views.push_back({&rig.cameras[c], R_wc[c], t_wc[c], object_of(c, static_cast<std::size_t>(w)),
                             &observations[c].corners[static_cast<std::size_t>(w)]});
  cv::Matx33d R_b;
  cv::Vec3d t_b = board_tvec[root][w];
  cv::Rodrigues(board_rvec[root][w], R_b);
  const double world_rms = refine_board_pose(world_views, R_b, t_b);
  log::info("world board (frame " + std::to_string(w) + ") seen by " + std::to_string(world_views.size()) +
            " camera(s), RMS " + std::to_string(world_rms) + " px");
  cv::Matx33d R_bw;
  cv::Rodrigues(options.board_rvec, R_bw);
  const cv::Matx33d R_root = R_b * R_bw.t();
  const cv::Vec3d t_root = t_b - R_root * options.board_tvec;
  for (std::size_t c = 0; c < n; ++c) {
    cv::Rodrigues(R_wc[c] * R_root, rig.cameras[c].rvec);
    rig.cameras[c].tvec = R_wc[c] * t_root + t_wc[c];
  }
  return rig;
}

}  // namespace finverse::vision
