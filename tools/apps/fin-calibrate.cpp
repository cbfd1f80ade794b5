// fin-calibrate: cameras.yml for a lab's own rig (issue 35 item 2; DESIGN.md section 3, "Cameras").
//
//   fin-calibrate checkerboard --view side=rec/side --view back=rec/back.avi --board-file board.json --out cameras.yml
//   fin-calibrate checkerboard --charuco 4X4_50 --board 9x6 --square-mm 5 --view ... --out cameras.yml   (ChArUco)
//   fin-calibrate dlt --coefficients rig_DLTcoefs.csv --views side,back --image-size 1024x1024 --unit mm --out cameras.yml
//   fin-calibrate anipose --calibration calibration.toml --unit mm --out cameras.yml
//   fin-calibrate simulate --cameras rig.yml --out-dir rec      (validation: a rendered board recording)
//   fin-calibrate score --truth rig.yml --cameras cameras.yml --report report.json --summary summary.json
//   fin-calibrate template --image fin.png --points fin.csv --mm-per-px 0.02 --out template.json
//
// template (issue 35 item 6) lives here rather than in an app of its own: like the rest of
// fin-calibrate it turns what a lab measured on its own images into finverse's inputs, and the
// image scale it needs is a calibration.
//
// checkerboard refuses (exit 1, one line, no cameras.yml) a calibration whose reprojection RMS is
// above --max-reprojection-px; its report.json gives the RMS per camera either way.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "vision/anipose_import.hpp"
#include "vision/calibration.hpp"
#include "vision/camera.hpp"
#include "vision/charuco_board.hpp"
#include "vision/digitised_template.hpp"
#include "vision/dlt_import.hpp"
#include "vision/image_file.hpp"
#include "vision/validation/calibration_scores.hpp"
#include "vision/validation/checkerboard_recording.hpp"

namespace fs = std::filesystem;
using namespace finverse;
using namespace finverse::vision;

namespace {

double metres_per_unit(const std::string& unit, const std::string& flag) {
  if (unit == "m") return 1.0;
  if (unit == "cm") return 1e-2;
  if (unit == "mm") return 1e-3;
  throw Error(flag + ": '" + unit + "', expected m, cm or mm");
}

cv::Size parse_size(const std::string& text, const std::string& flag) {
  const auto x = text.find_first_of("xX");
  try {
    if (x != std::string::npos) {
      const cv::Size s(std::stoi(text.substr(0, x)), std::stoi(text.substr(x + 1)));
      if (s.width > 0 && s.height > 0) return s;
    }
  } catch (const std::exception&) {
  }
  throw Error(flag + ": '" + text + "', expected WIDTHxHEIGHT in pixels, e.g. 1024x768");
}

void write_png_atomic(const fs::path& path, const cv::Mat& img) {
  std::vector<unsigned char> buf;
  cv::imencode(".png", img, buf);
  write_text_atomic(path, std::string(buf.begin(), buf.end()));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fin-calibrate: cameras.yml for a rig, from checkerboard recordings or DLTdv / Anipose calibrations"};
  cli::Standard standard(app, "fin-calibrate");
  app.require_subcommand(1);
  app.fallthrough();  // --threads, --log-level also after the subcommand

  // checkerboard
  auto* cb = app.add_subcommand("checkerboard", "calibrate from synchronized checkerboard recordings (one per camera)");
  std::vector<std::string> views;
  fs::path board_file, out, report;
  std::string board_text = "9x6";
  double square_mm = 0, max_rms = 1.0;
  int every = 1, world_frame = -1;
  bool fit_k3 = false;
  cb->add_option("--view", views, "NAME=PATH: a camera and its recording (image directory or video), repeat per camera")->required();
  cb->add_option("--board-file", board_file, "board description JSON (board, square_mm, world_frame, board pose)")->check(CLI::ExistingFile);
  cb->add_option("--board", board_text, "inner corners COLSxROWS (without --board-file)")->capture_default_str();
  cb->add_option("--square-mm", square_mm, "square side in mm (without --board-file)");
  std::string charuco;
  double marker_fraction = 0.75;
  cb->add_option("--charuco", charuco, "a ChArUco board of this ArUco dictionary, e.g. 4X4_50 (without --board-file; --board: its inner corners)");
  cb->add_option("--marker-fraction", marker_fraction, "ChArUco: marker side / square side")->capture_default_str();
  cb->add_option("--world-frame", world_frame, "frame whose board defines the world (-1: the one most cameras see)")->capture_default_str();
  cb->add_option("--every", every, "use every N-th frame")->capture_default_str();
  cb->add_flag("--fit-k3", fit_k3, "also fit the 6th-order radial coefficient k3 (wide lenses)");
  bool fit_tangential = false, bundle = true;
  cb->add_flag("--fit-tangential", fit_tangential, "also fit the tangential distortion p1, p2 (decentred lenses)");
  cb->add_flag("--bundle-adjust,!--no-bundle-adjust", bundle, "refine every camera and board pose at once over all frames")
      ->capture_default_str();
  bool bundle_intrinsics = false;
  cb->add_flag("--bundle-intrinsics", bundle_intrinsics, "the bundle adjustment also refines every camera's intrinsics");
  cb->add_option("--max-reprojection-px", max_rms, "refuse (exit 1) a calibration with a camera's RMS above this")->capture_default_str();
  cb->add_option("--out", out, "cameras.yml to write")->required();
  cb->add_option("--report", report, "report.json: RMS and frames per camera (default: beside --out)");

  // dlt
  auto* dlt = app.add_subcommand("dlt", "import DLTdv's 11-coefficient DLT file (one column per camera)");
  fs::path coefficients;
  std::vector<std::string> dlt_views, sizes;
  std::string dlt_unit = "m", origin = "bottom-left";
  dlt->add_option("--coefficients", coefficients, "DLT coefficients CSV (11 rows x cameras)")->required()->check(CLI::ExistingFile);
  dlt->add_option("--views", dlt_views, "camera names, in the file's column order")->delimiter(',')->required();
  dlt->add_option("--image-size", sizes, "WIDTHxHEIGHT per camera, or one for all")->delimiter(',')->required();
  dlt->add_option("--unit", dlt_unit, "length unit of the DLT's world coordinates: m, cm or mm")->capture_default_str();
  dlt->add_option("--origin", origin, "image origin of the DLT's pixel coordinates: bottom-left (DLTdv) or top-left")->capture_default_str();
  dlt->add_option("--out", out, "cameras.yml to write")->required();

  // anipose
  auto* ani = app.add_subcommand("anipose", "import Anipose's calibration.toml");
  fs::path toml;
  std::string ani_unit = "mm";
  ani->add_option("--calibration", toml, "calibration.toml")->required()->check(CLI::ExistingFile);
  ani->add_option("--unit", ani_unit, "length unit of its translations (the board's square unit): m, cm or mm")->capture_default_str();
  ani->add_option("--out", out, "cameras.yml to write")->required();

  // simulate (validation)
  auto* sim = app.add_subcommand("simulate", "validation: render a checkerboard recording through the cameras of a cameras.yml");
  fs::path rig, out_dir;
  RecordingOptions rec;
  double board_fraction = 0.45;
  sim->add_option("--cameras", rig, "cameras.yml of the rig (e.g. fin-synth's)")->required()->check(CLI::ExistingFile);
  sim->add_option("--out-dir", out_dir, "writes <view>/frame_NNNN.png and board.json")->required();
  sim->add_option("--board", board_text, "inner corners COLSxROWS")->capture_default_str();
  sim->add_option("--charuco", charuco, "render a ChArUco board of this ArUco dictionary (e.g. 4X4_50)");
  sim->add_option("--marker-fraction", marker_fraction, "ChArUco: marker side / square side")->capture_default_str();
  sim->add_option("--board-fraction", board_fraction, "board width / the narrowest view's width at the rig's focus")->capture_default_str();
  sim->add_option("--poses", rec.poses, "board poses (frames)")->capture_default_str();
  sim->add_option("--supersample", rec.supersample, "anti-aliasing rays per pixel per axis")->capture_default_str();
  sim->add_option("--noise-sigma", rec.noise_sigma, "sensor noise (8-bit levels)")->capture_default_str();
  sim->add_option("--max-tilt-deg", rec.max_tilt_deg, "board tilt away from facing its camera")->capture_default_str();
  sim->add_option("--seed", rec.seed, "seed of the poses and the noise")->capture_default_str();

  // score (validation)
  auto* score = app.add_subcommand("score", "validation: a calibrated rig against the true one -> summary.json");
  fs::path truth, cams, summary, work;
  score->add_option("--truth", truth, "cameras.yml of the true rig")->required()->check(CLI::ExistingFile);
  score->add_option("--cameras", cams, "calibrated cameras.yml")->required()->check(CLI::ExistingFile);
  score->add_option("--report", report, "fin-calibrate checkerboard's report.json")->required()->check(CLI::ExistingFile);
  score->add_option("--summary", summary, "summary.json to write")->required();
  score->add_option("--work-dir", work, "where the DLT and Anipose files of the import check go (default: beside --summary)");

  // template
  auto* tpl = app.add_subcommand("template", "a fin template.json from a side-view image and its digitised outline and rays");
  fs::path image, points, overlay;
  std::optional<double> mm_per_px, scale_mm;
  DigitisedTemplateOptions dto;
  tpl->add_option("--image", image, "side-view image of the spread fin (the pixels the CSV refers to)")->required()->check(CLI::ExistingFile);
  tpl->add_option("--points", points, "CSV kind,id,x_px,y_px: outline, root/ray/tip per ray (1: dorsal), scale")
      ->required()
      ->check(CLI::ExistingFile);
  auto* mpp = tpl->add_option("--mm-per-px", mm_per_px, "image scale")->check(finverse::cli::positive());
  tpl->add_option("--scale-mm", scale_mm, "distance between the CSV's two scale points (mm)")
      ->check(finverse::cli::positive())
      ->excludes(mpp);
  tpl->add_option("--outline-tolerance-px", dto.outline_tolerance_px, "a ray may leave the digitised outline by this much")->capture_default_str();
  tpl->add_option("--ray-points", dto.sections.points_per_ray, "template points per ray")->capture_default_str()->check(CLI::Range(2, 1000));
  tpl->add_option("--edge-ray-thickness", dto.sections.edge_root_thickness, "root thickness of the edge rays / c")->capture_default_str();
  tpl->add_option("--center-ray-thickness", dto.sections.center_root_thickness, "root thickness of the middle ray / c")->capture_default_str();
  tpl->add_option("--tip-thickness-ratio", dto.sections.tip_thickness_ratio, "ray thickness at the tip / at the root")->capture_default_str();
  tpl->add_option("--ray-width-ratio", dto.sections.width_over_thickness, "in-plane ray width / thickness")->capture_default_str();
  tpl->add_option("--membrane-thickness", dto.sections.membrane_thickness, "membrane thickness / c")->capture_default_str();
  tpl->add_option("--overlay", overlay, "PNG of the image with the digitised outline and rays drawn over it");
  tpl->add_option("--out", out, "template.json to write")->required();

  return cli::run(app, standard, argc, argv, [&]() -> int {
    if (*tpl) {
      const cv::Mat img = vision::read_image(image, cv::IMREAD_UNCHANGED);
      const auto fin = read_digitised_fin(points);
      if (mm_per_px) {
        dto.metres_per_px = 1e-3 * *mm_per_px;
      } else if (scale_mm) {
        if (!fin.scale_points) throw Error(points.string() + ": --scale-mm needs two scale rows (scale,1,x,y and scale,2,x,y)");
        const double px = cv::norm((*fin.scale_points)[0] - (*fin.scale_points)[1]);
        if (!(px > 0)) throw Error(points.string() + ": the two scale points coincide");
        dto.metres_per_px = 1e-3 * *scale_mm / px;
      } else {
        throw Error("template: give the image scale, --mm-per-px or --scale-mm (with two scale rows in " + points.string() + ")");
      }
      if (!overlay.empty()) write_png_atomic(overlay, draw_digitised_fin(img, fin));
      const auto t = template_from_digitised(fin, dto, img.size());
      mesh::write_template(out, t);
      log::info("wrote " + out.string() + ": " + std::to_string(t.ray_count()) + " rays, chord " + std::to_string(1e3 * t.chord) +
                " mm, planform " + std::to_string(1e6 * t.area()) + " mm^2 (" + std::to_string(1e3 * dto.metres_per_px) + " mm/px)");
      return kExitOk;
    }
    if (*cb) {
      CalibrationOptions opt;
      if (!board_file.empty()) {
        opt = read_board_file(board_file);
      } else {
        opt.board = parse_board(board_text, 1e-3 * square_mm, "--board");
        opt.board.charuco = charuco, opt.board.marker_fraction = marker_fraction;
        if (!charuco.empty()) check_charuco(opt.board);
      }
      if (cb->count("--world-frame")) opt.world_frame = world_frame;
      opt.fix_k3 = !fit_k3;
      opt.fit_tangential = fit_tangential;
      opt.bundle_adjust = bundle;
      opt.bundle_intrinsics = bundle_intrinsics;
      std::vector<BoardObservations> obs;
      for (const auto& v : views) {
        const auto eq = v.find('=');
        if (eq == std::string::npos || eq == 0 || eq + 1 == v.size())
          throw Error("--view: '" + v + "', expected NAME=PATH (a camera name and its image directory or video)");
        const auto recording = read_recording(v.substr(0, eq), v.substr(eq + 1), every);
        obs.push_back(detect_checkerboard(recording, opt.board));
      }
      const auto result = calibrate_rig(obs, opt);
      const fs::path rep = report.empty() ? out.parent_path() / "report.json" : report;
      write_text_atomic(rep, rig_report_json(result));
      for (const auto& r : result.reports)
        if (std::max(r.intrinsic_rms_px, r.rig_rms_px) > max_rms) {
          log::error("calibration refused: camera " + r.view + " reprojection RMS " +
                     std::to_string(std::max(r.intrinsic_rms_px, r.rig_rms_px)) + " px > --max-reprojection-px " +
                     std::to_string(max_rms) + " (" + rep.string() + ")");
          return kExitDifferent;
        }
      write_cameras(out, result.cameras);
      log::info("wrote " + out.string() + " (max RMS " + std::to_string(result.max_rms_px()) + " px)");
      return kExitOk;
    }
    if (*dlt) {
      const auto coeffs = read_dlt_file(coefficients);
      if (coeffs.size() != dlt_views.size())
        throw Error(coefficients.string() + ": " + std::to_string(coeffs.size()) + " cameras, but --views names " +
                    std::to_string(dlt_views.size()));
      if (sizes.size() != 1 && sizes.size() != dlt_views.size())
        throw Error("--image-size: expected one WIDTHxHEIGHT or one per camera (" + std::to_string(dlt_views.size()) + ")");
      if (origin != "bottom-left" && origin != "top-left") throw Error("--origin: '" + origin + "', expected bottom-left or top-left");
      std::vector<Camera> out_cams;
      for (std::size_t i = 0; i < coeffs.size(); ++i) {
        const auto sz = parse_size(sizes[sizes.size() == 1 ? 0 : i], "--image-size");
        out_cams.push_back(camera_from_dlt(coeffs[i], dlt_views[i], sz.width, sz.height,
                                           origin == "top-left" ? DltOrigin::top_left : DltOrigin::bottom_left,
                                           metres_per_unit(dlt_unit, "--unit"), coefficients.string()));
      }
      write_cameras(out, out_cams);
      return kExitOk;
    }
    if (*ani) {
      write_cameras(out, read_anipose_calibration(toml, metres_per_unit(ani_unit, "--unit")));
      return kExitOk;
    }
    if (*sim) {
      const auto cameras = read_cameras(rig);
      CalibrationOptions opt;
      opt.board = parse_board(board_text, 1.0, "--board");
      opt.board.charuco = charuco, opt.board.marker_fraction = marker_fraction;
      if (!charuco.empty()) check_charuco(opt.board);
      opt.board.square_m = board_square_for_rig(cameras, opt.board, board_fraction);
      const auto poses = checkerboard_poses(cameras, opt.board, rec);
      opt.world_frame = 0;  // the first pose is the world board: its pose is the truth's
      opt.board_rvec = poses[0].rvec;
      opt.board_tvec = poses[0].tvec;
      for (std::size_t c = 0; c < cameras.size(); ++c) {
        const fs::path dir = out_dir / cameras[c].name;
        fs::create_directories(dir);
        const cv::Mat rays = camera_sample_rays(cameras[c], rec.supersample);
        for (std::size_t k = 0; k < poses.size(); ++k) {
          char name[32];
          std::snprintf(name, sizeof name, "frame_%04zu.png", k + 1);
          write_png_atomic(dir / name, render_checkerboard(cameras[c], rays, opt.board, poses[k], rec, rec.seed + 7919 * (c + 1) + k));
        }
        log::info("rendered " + std::to_string(poses.size()) + " frames of " + cameras[c].name);
      }
      write_board_file(out_dir / "board.json", opt);
      return kExitOk;
    }
    if (*score) {
      std::ifstream in(report);
      const auto rep = nlohmann::json::parse(in, nullptr, false);
      if (rep.is_discarded() || !rep.contains("cameras")) throw Error(report.string() + ": expected fin-calibrate's report.json");
      const auto s = calibration_validation_summary(read_cameras(truth), read_cameras(cams), rep,
                                                    work.empty() ? summary.parent_path() / "imports" : work);
      s.write(summary);
      for (const auto& m : s.metrics()) log::info(m.name + " = " + std::to_string(m.value) + " " + m.units);
      return s.pass() ? kExitOk : kExitDifferent;
    }
    return kExitError;
  });
}
