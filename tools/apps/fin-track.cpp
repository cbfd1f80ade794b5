// fin-track: the fin's 3-D motion from synchronized multi-view frames (DESIGN.md sections 1 and
// 5.5; seed paper section 2.1 step 1 and section 4.1): the flags, the files and the tracker
// (tools/vision/tracker.hpp: per frame, segment every view and fit the virtual skeleton to all
// the silhouettes, warm-started from and regularised towards the previous frames' motion); its
// flags: tools/vision/tracker_flags.hpp; the 2-D mode midline: tools/vision/midline_command.hpp.
//
//   fin-track --frames results/c/frames --cameras results/c/cameras.yml --out results/c/kinematics.h5
//   fin-track midline --frames clip.avi --out midline.h5 --csv tip.csv --overlay check.avi --mm-per-px 0.1
//
// Frames are image folders or video files, one per view (tools/vision/frame_files.hpp). With --truth the
// reconstruction is scored (--summary), with --bench timed (--bench-json).
#include <algorithm>
#include <cstdio>
#include <map>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/flow_scales.hpp"
#include "core/log.hpp"
#include "core/stage_files.hpp"
#include "core/summary.hpp"
#include "mesh/template_options.hpp"
#include "vision/camera.hpp"
#include "vision/frame_files.hpp"
#include "vision/keypoint_files.hpp"
#include "vision/midline_command.hpp"
#include "vision/tracker.hpp"
#include "vision/tracker_flags.hpp"
#include "vision/tracking_summary.hpp"
#include "vision/view_roles.hpp"

namespace fs = std::filesystem;
using namespace finverse;

int main(int argc, char** argv) {
  CLI::App app{"fin-track: reconstruct the fin's 3-D motion from multi-view frames (skeleton fit to silhouettes)"};
  cli::Standard standard(app, "fin-track");
  mesh::TemplateOptions tmpl;
  mesh::add_template_options(app, tmpl);
  vision::TrackerFlags flags;
  auto& to = flags.options;
  auto& fo = to.fit;
  std::vector<std::string> frames_spec;
  std::optional<double> fps;
  fs::path cameras_file, out, truth_file, summary_out, bench_out, mesh_summary;
  double perturb_px = 0, viscosity = kWaterKinematicViscosity;
  std::optional<double> period, reynolds, strouhal, excursion_over_chord;
  std::uint64_t seed = 1;
  std::vector<std::string> ignore_views, also_score;
  app.add_option("--frames", frames_spec,
                 "a folder of <view>/ image folders (numbered names: 000001.png, frame_0001.png) or <view>.avi|.mp4|.mov, "
                 "or view=path items: side=clip_side.avi,back=frames/back (required)")
      ->delimiter(',');
  app.add_option("--cameras", cameras_file, "cameras.yml (OpenCV FileStorage) (required)")->check(CLI::ExistingFile);
  app.add_option("--out", out, "output kinematics.h5 (required)");
  app.add_option("--fps", fps, "camera frame rate (1/s); default: the videos' own, else " + std::to_string(int(to.fps)))
      ->check(finverse::cli::positive());
  auto* period_opt =
      app.add_option("--period", period, "period of the motion (s), stored as the T attribute when the record is periodic");
  // Or the period from the flow scales, as fin-synth's motion has it (core/flow_scales.hpp).
  auto* re_opt = app.add_option("--reynolds", reynolds, "periodic record: T = A / (St U), U = Re nu / c; Re = U c / nu")
                     ->excludes(period_opt);
  app.add_option("--strouhal", strouhal, "periodic record: St = f A / U, A the trailing edge's peak-to-peak excursion")
      ->needs(re_opt);
  app.add_option("--excursion-over-chord", excursion_over_chord, "periodic record: that excursion A / c (fin-synth's flag)")
      ->needs(re_opt);
  app.add_option("--viscosity", viscosity, "periodic record: kinematic viscosity nu (m^2/s)")->capture_default_str();
  vision::add_tracker_flags(app, flags);
  // Keypoints of the ray roots and tips (DeepLabCut per view, Anipose 3-D): tools/vision/keypoint_files.hpp.
  std::vector<std::string> keypoint_specs;
  fs::path keypoints_3d, keypoints_out;
  std::string keypoints_unit = "mm";
  double keypoint_min_score = 0.6;
  app.add_option("--keypoints", keypoint_specs, "view=dlc.csv: DeepLabCut 2-D keypoints ray<N>_root / ray<N>_tip of that view (repeatable)")
      ->delimiter(',');
  app.add_option("--keypoints-3d", keypoints_3d, "Anipose pose-3d CSV of the keypoints ray<N>_root / ray<N>_tip")->check(CLI::ExistingFile);
  app.add_option("--keypoints-unit", keypoints_unit, "length unit of --keypoints-3d and of the written 3-D CSV: m, cm or mm")
      ->check(CLI::IsMember({"m", "cm", "mm"}))
      ->capture_default_str();
  app.add_option("--keypoint-weight", fo.keypoints.weight, "weight of a keypoint's residual (px; 3-D: per --keypoint-sigma-3d)")
      ->capture_default_str();
  app.add_option("--keypoint-sigma-3d", fo.keypoints.sigma_3d_chords, "3-D keypoints: the distance that weighs like a pixel (chords)")
      ->capture_default_str();
  app.add_option("--keypoint-min-score", keypoint_min_score, "keypoints below this likelihood (DeepLabCut) or score (Anipose) are left out")
      ->capture_default_str();
  app.add_option("--keypoints-out", keypoints_out,
                 "folder: the fitted ray roots and tips as DeepLabCut CSVs (<view>.csv) and an Anipose pose-3d CSV (pose_3d.csv)");
  app.add_option("--ignore-view", ignore_views, "leave these views out (validation: one view removed)")->delimiter(',');
  app.add_option("--perturb-calibration-px", perturb_px, "shift every principal point by this many px in a seeded direction (validation)")
      ->capture_default_str();
  app.add_option("--seed", seed, "seed of --perturb-calibration-px")->capture_default_str();
  app.add_option("--truth", truth_file, "truth.h5 of fin-synth: score the reconstruction")->check(CLI::ExistingFile);
  auto* sum_opt = app.add_option("--summary", summary_out, "validation summary.json (needs --truth)");
  app.add_option("--also-score", also_score, "label=kinematics.h5: score another reconstruction too (reported only)")->needs(sum_opt);
  app.add_option("--bench-json", bench_out, "benchmark json: seconds per frame set");
  app.add_option("--bench-mesh-summary", mesh_summary, "fin-mesh --summary file whose mesh_wall_time joins the benchmark")
      ->check(CLI::ExistingFile);

  // The 2-D single-view mode (tools/vision/midline_command.hpp): one camera, no calibration.
  vision::MidlineCommand midline;
  auto* mid = vision::add_midline_command(app, midline);

  return cli::run(app, standard, argc, argv, [&] {
    if (*mid) return vision::run_midline_command(midline, app);
    if (frames_spec.empty() || cameras_file.empty() || out.empty())
      throw Error("--frames, --cameras and --out are required (or the subcommand midline: fin-track midline --help)");
    if (!summary_out.empty() && truth_file.empty()) throw Error("--summary: needs --truth");
    if (reynolds && !(strouhal && excursion_over_chord))
      throw Error("--reynolds: needs --strouhal and --excursion-over-chord");
    const auto fin = mesh::make_template(tmpl);
    if (reynolds)
      period = flapping_period(*strouhal, free_stream_speed(*reynolds, fin.chord, viscosity), *excursion_over_chord * fin.chord);
    if (period && !(*period > 0))
      throw Error(reynolds ? "--reynolds ...: the period must be > 0" : "--period: expected > 0");
    to.period = period;
    auto cameras = vision::read_cameras(cameras_file);
    vision::apply_tracker_flags(flags, cameras, cameras_file.string());
    const auto calibrated = cameras;  // scoring projects with the calibration as given, never perturbed
    if (perturb_px > 0) vision::perturb_principal_points(cameras, perturb_px, seed);
    const auto files = vision::list_frame_files(frames_spec, cameras, ignore_views, cameras_file.string());
    if (fps)
      to.fps = *fps;
    else if (files.container_fps)
      to.fps = *files.container_fps;
    log::info("frame rate " + std::to_string(to.fps) + " fps (" + (fps ? "--fps" : files.container_fps ? "the videos'" : "default") + ")");
    for (const auto& [flag, names] : {std::pair{"--coverage-views", &fo.coverage_views}, std::pair{"--ray-views", &fo.ray_views}})
      for (const auto& name : *names)
        if (name != "auto" && name != "all" && name != "none" &&
            std::none_of(cameras.begin(), cameras.end(), [&](const auto& c) { return c.name == name; }))
          log::warn(std::string(flag) + ": no view '" + name + "' in " + cameras_file.string() + "; not used");
    // The terms each view carries, as run (stored with the configuration in kinematics.h5).
    auto config = cli::effective_config(app);
    config["fps"] = std::to_string(to.fps);
    for (const auto& c : cameras) {
      const bool rays = vision::fits_rays(fo.ray_views, c), coverage = vision::fits_coverage(fo.coverage_views, c);
      config["view_terms"][c.name] = {{"role", vision::role_name(vision::view_role(c))}, {"rays", rays}, {"coverage", coverage}};
      log::info("view '" + c.name + "' (" + vision::role_name(vision::view_role(c)) + "): silhouette" + (rays ? ", rays" : "") +
                (coverage ? ", coverage" : ""));
    }

    // Keypoints: read, matched to the views by name, and given to the fit frame by frame.
    std::vector<vision::KeypointTable> tables;
    std::vector<std::pair<std::size_t, const vision::KeypointTable*>> image_tables;
    tables.reserve(keypoint_specs.size() + 1);
    for (const auto& spec : keypoint_specs) {
      const auto eq = spec.find('=');
      const auto name = eq == std::string::npos ? "" : spec.substr(0, eq);
      const auto cam = std::find_if(cameras.begin(), cameras.end(), [&](const auto& c) { return c.name == name; });
      if (eq == std::string::npos || cam == cameras.end())
        throw Error("--keypoints: '" + spec + "', expected view=file.csv with a view of " + cameras_file.string());
      tables.push_back(vision::read_deeplabcut_csv(spec.substr(eq + 1)));
      image_tables.emplace_back(static_cast<std::size_t>(cam - cameras.begin()), &tables.back());
    }
    const double unit_m = keypoints_unit == "m" ? 1.0 : keypoints_unit == "cm" ? 1e-2 : 1e-3;
    if (!keypoints_3d.empty()) tables.push_back(vision::read_anipose_csv(keypoints_3d));
    const auto keypoints = vision::keypoint_record(image_tables, keypoints_3d.empty() ? nullptr : &tables.back(), unit_m,
                                                   keypoint_min_score, fin.ray_count());
    if (!keypoint_specs.empty() || !keypoints_3d.empty())
      log::info("keypoints: " + std::to_string(keypoints.size()) + " frames with ray roots or tips (weight " +
                std::to_string(fo.keypoints.weight) + ")");

    const vision::Tracker tracker(fin, to);
    std::optional<stage::Truth> truth;
    vision::TruthReference reference{nullptr, calibrated, truth_file.string()};
    if (!summary_out.empty()) truth = stage::read<stage::Truth>(truth_file), reference.points = &truth->points;
    const vision::FrameLoader load = [&](std::size_t v, long k) { return files.load(v, k); };
    auto r = tracker.track({cameras, files.frames, load, frames_spec.size() == 1 ? frames_spec[0] : "--frames",
                            keypoints.empty() ? nullptr : &keypoints},
                           truth ? &reference : nullptr);
    log::info("tracking: " + std::to_string(r.seconds_per_frame) + " s per frame set after the first (" + std::to_string(r.first_seconds) +
              " s, cold start); " + std::to_string(cameras.size()) + " views, " + std::to_string(cli::threads_in_use()) +
              " threads; worst silhouette IoU " + std::to_string(r.worst_iou));
    if (r.keypoint_frames)
      log::info("keypoints: the fitted ray ends lie " + std::to_string(r.keypoint_rms_px) + " px (RMS) from the 2-D keypoints over " +
                std::to_string(r.keypoint_frames) + " frames");

    Provenance prov{"fin-track", config, {cameras_file}};
    if (!tmpl.file.empty()) prov.inputs.push_back(tmpl.file);
    stage::write(out, r.kinematics, prov);
    log::info("wrote " + out.string());
    if (!keypoints_out.empty()) {
      fs::create_directories(keypoints_out);
      const auto ends = tracker.model().ray_ends();
      for (const auto& c : calibrated)
        vision::write_deeplabcut_csv(keypoints_out / (c.name + ".csv"), vision::fitted_ray_ends(r.frames, r.kinematics.points, ends, &c, 1.0));
      vision::write_anipose_csv(keypoints_out / "pose_3d.csv", vision::fitted_ray_ends(r.frames, r.kinematics.points, ends, nullptr, unit_m));
      log::info("wrote the fitted ray ends to " + keypoints_out.string());
    }

    int status = kExitOk;
    if (!r.verdict.failure.empty()) {
      // The record is written (flagged: quality/flags, fit_status) so the user can look at it.
      log::error("fit failed: " + r.verdict.failure + " (written, flagged: " + out.string() + ")");
      status = kExitDifferent;
    }
    auto finish = [&](Summary& s, const fs::path& path) {
      s.parameters() = cli::effective_config(app);
      s.set_timing(r.seconds, cli::threads_in_use());
      s.write(path);
      if (!s.pass()) status = kExitDifferent;
      return s.pass();
    };
    if (!summary_out.empty()) {
      std::vector<vision::OtherReconstruction> others;
      for (const auto& spec : also_score) {
        const auto eq = spec.find('=');
        if (eq == std::string::npos) throw Error("--also-score: expected label=kinematics.h5, got '" + spec + "'");
        others.push_back({spec.substr(0, eq), spec.substr(eq + 1), stage::read<stage::Kinematics>(spec.substr(eq + 1)).points});
      }
      auto sum = vision::tracking_validation_summary(r, tracker.model(), *truth, truth_file.string(), others);
      if (!finish(sum, summary_out)) log::error("a validation metric failed: see " + summary_out.string());
    }
    if (!bench_out.empty()) {
      std::optional<double> mesh_wall_time;
      if (!mesh_summary.empty()) {
        const auto ms = Summary::read(mesh_summary);
        for (const auto& m : ms.metrics())
          if (m.name == "mesh_wall_time") mesh_wall_time = m.value;
      }
      auto b = vision::tracking_bench_summary(r, cameras[0].width, mesh_wall_time);
      finish(b, bench_out);
    }
    return status;
  });
}
