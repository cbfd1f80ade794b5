// fin-track: the fin's 3-D motion from synchronized multi-view frames (DESIGN.md sections 1 and
// 5.5; seed paper section 2.1 step 1 and section 4.1). Per frame: segment the fin in every view,
// then fit the virtual skeleton (ray chains with 3-DOF joints, the template skinned on it) so
// that the projected template matches every silhouette, warm-started from and regularised
// towards the previous frames' motion.
//
//   fin-track --frames results/c/frames --cameras results/c/cameras.yml --out results/c/kinematics.h5
//
// Frames are <frames>/<view>/NNNNNN.png (any format cv::imread reads), NNNNNN the frame index.
// A view without frames, or a frame missing in some views, is warned about and fitted with the
// views that are there. With --truth the reconstruction is scored (--summary), with --bench
// timed (--bench-json).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <numbers>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "core/log.hpp"
#include "core/stage_files.hpp"
#include "core/summary.hpp"
#include "mesh/template_options.hpp"
#include "vision/camera.hpp"
#include "vision/fin_surface.hpp"
#include "vision/silhouette_coverage.hpp"
#include "vision/skeleton_fit.hpp"
#include "vision/tracking_score.hpp"

namespace fs = std::filesystem;
using namespace finverse;

namespace {

// frame index -> file, per view.
std::map<long, fs::path> list_frames(const fs::path& dir) {
  std::map<long, fs::path> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    const auto stem = e.path().stem().string();
    if (stem.empty() || !std::all_of(stem.begin(), stem.end(), [](char ch) { return std::isdigit(static_cast<unsigned char>(ch)); }))
      continue;
    out[std::stol(stem)] = e.path();
  }
  return out;
}

std::vector<std::size_t> trailing_edge(const vision::FinSurface& f) {
  std::vector<std::size_t> te;
  for (std::size_t v = 0; v < f.size(); ++v)
    if (f.s[v] >= 1 - 1e-12) te.push_back(v);
  return te;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fin-track: reconstruct the fin's 3-D motion from multi-view frames (skeleton fit to silhouettes)"};
  cli::Standard standard(app, "fin-track");
  mesh::TemplateOptions tmpl;
  mesh::add_template_options(app, tmpl);
  vision::FitOptions fo;
  vision::SegmentationOptions so;
  fs::path frames_dir, cameras_file, out, truth_file, summary_out, bench_out, mesh_summary;
  double fps = 500, perturb_px = 0, velocity_factor = 0.5;
  std::optional<double> period;
  int subdivisions = 4, segments = 7;
  std::uint64_t seed = 1;
  std::vector<std::string> ignore_views, also_score;
  app.add_option("--frames", frames_dir, "frames directory: <view>/NNNNNN.png")->required()->check(CLI::ExistingDirectory);
  app.add_option("--cameras", cameras_file, "cameras.yml (OpenCV FileStorage)")->required()->check(CLI::ExistingFile);
  app.add_option("--out", out, "output kinematics.h5")->required();
  app.add_option("--fps", fps, "camera frame rate (1/s)")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--period", period, "period of the motion (s), stored as the T attribute when the record is periodic");
  app.add_option("--surface-subdivisions", subdivisions, "template surface columns per gap between rays (even)")->capture_default_str();
  app.add_option("--segments", segments, "skeleton segments per ray")->capture_default_str();
  app.add_option("--iterations", fo.iterations, "LM iterations per frame")->capture_default_str();
  app.add_option("--tolerance", fo.tolerance, "LM: stop when the cost falls by less than this fraction")->capture_default_str();
  app.add_option("--step-tolerance", fo.step_tolerance, "LM: stop when no parameter moves by more than this (rad, chords)")->capture_default_str();
  app.add_option("--max-rejections", fo.max_rejections, "LM: stop after this many rejected steps in a row (0: never)")->capture_default_str();
  app.add_option("--first-iterations", fo.first_iterations, "LM iterations for the first frame")->capture_default_str();
  app.add_option("--temporal-sigma", fo.temporal_sigma, "temporal prior: rad (translation: chords)")->capture_default_str();
  app.add_option("--neighbour-sigma", fo.neighbour_sigma, "prior on joint differences of neighbouring rays (rad)")->capture_default_str();
  app.add_option("--out-of-plane-sigma", fo.out_of_plane_sigma, "prior on twist and in-plane bending (rad)")->capture_default_str();
  app.add_option("--span-curvature-sigma", fo.span_curvature_sigma, "prior on the second difference of joint angles across three rays (rad; 0: off)")->capture_default_str();
  app.add_option("--contour-stride", fo.silhouette.contour_stride, "use every n-th silhouette contour pixel")->capture_default_str();
  app.add_option("--prediction-velocity", velocity_factor,
                 "fraction of the last frame-to-frame change carried into the next frame's prediction (1: constant velocity)")
      ->capture_default_str();
  // Ray features only where the fin is seen face-on: in the edge-on views (back, ventral) the
  // whole silhouette is a strip a few pixels wide that the black-hat detector takes for one dark
  // line, and pulling the model's rays onto it narrows the fitted strip (measured on the 100
  // validation frames: with ray features in all views the fitted edge-on silhouettes are about
  // 1 % smaller in area than the truth's on average, with the side view's within 0.2 %, and the vertex errors
  // fall, mean / p95 / max 0.52 / 1.26 / 4.27 -> 0.49 / 1.09 / 2.45 % c).
  fo.ray_views = {"side"};
  app.add_option("--ray-views", fo.ray_views, "views whose ray features are fitted ('all': every view)")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--ray-weight", fo.rays.weight, "weight of the ray-feature residuals (0: silhouettes only)")->capture_default_str();
  // Sub-pixel area term (tools/vision/coverage_residual.hpp) in the edge-on views, whose strips
  // of a few pixels the pixel-centre chamfer places only to about a pixel. Defaults measured on
  // the 100 validation frames (noise 2, blur; worst fit-truth coverage IoU back / ventral): no
  // coverage term 0.959 / 0.939; weight 10 (band 3 px, chamfer x0.2 there) 0.962 / 0.960, the
  // cost at the fit still above the cost at the truth; + 18 LM iterations 0.971 / 0.959; + 7
  // segments per ray (5 cannot bend a lobe as the truth does) 0.974 / 0.972; band 2 px, weight 5
  // 0.976 / 0.974 in fewer LM steps; weight 3: 0.970 / 0.975; chamfer x0: unstable (max vertex
  // error 5 % c); chamfer x0.4 with every other contour pixel: one back frame 0.885. The same
  // defaults without the coverage term (--coverage-weight 0): 0.961 / 0.939.
  fo.coverage_views = {"back", "ventral"};
  fo.coverage.weight = 5;
  fo.coverage.band_px = 2;
  fo.coverage_chamfer_weight = 0.2;
  fo.iterations = 18;
  // Stop after two rejected LM steps in a row: 27 % of all steps were rejections in runs of 4-10
  // at the end of a frame's fit; stopping changed no metric beyond 0.001 (seg 7, weight 10).
  fo.max_rejections = 2;
  app.add_option("--coverage-views", fo.coverage_views, "views fitted with the sub-pixel coverage term ('none': no view)")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--coverage-weight", fo.coverage.weight, "weight of a pixel's coverage residual (0: off)")->capture_default_str();
  app.add_option("--coverage-chamfer-weight", fo.coverage_chamfer_weight,
                 "factor on the silhouette chamfer weight in the coverage views while the coverage term is on")
      ->capture_default_str();
  app.add_option("--coverage-band", fo.coverage.band_px, "coverage term: pixels within this distance of the data outline (px)")
      ->capture_default_str();
  app.add_option("--ray-contrast", fo.rays.min_contrast, "ray detection: black-hat threshold (8-bit levels)")->capture_default_str();
  app.add_option("--min-contrast", so.min_contrast, "segmentation: smallest darkening that counts as fin (8-bit levels)")->capture_default_str();
  app.add_option("--ignore-view", ignore_views, "leave these views out (validation: one view removed)")->delimiter(',');
  app.add_option("--perturb-calibration-px", perturb_px, "shift every principal point by this many px in a seeded direction (validation)")
      ->capture_default_str();
  app.add_option("--seed", seed, "seed of --perturb-calibration-px")->capture_default_str();
  app.add_option("--truth", truth_file, "truth.h5 of fin-synth: score the reconstruction")->check(CLI::ExistingFile);
  auto* sum_opt = app.add_option("--summary", summary_out, "validation summary.json (needs --truth)");
  app.add_option("--also-score", also_score, "label=kinematics.h5: score another reconstruction too (reported only)")->needs(sum_opt);
  app.add_option("--bench-json", bench_out, "benchmark json: seconds per frame set");
  app.add_option("--bench-mesh-summary", mesh_summary, "fin-mesh --summary file whose mesh_wall_time joins the benchmark")->check(CLI::ExistingFile);

  return cli::run(app, standard, argc, argv, [&] {
    if (!summary_out.empty() && truth_file.empty()) throw Error("--summary: needs --truth");
    const auto fin = mesh::make_template(tmpl);
    const auto surface = vision::make_fin_surface(fin, subdivisions);
    const auto skeleton = vision::make_skeleton(fin, segments);
    const auto binding = vision::bind_skin(fin, skeleton, surface.rest);

    auto cameras = vision::read_cameras(cameras_file);
    const auto calibrated = cameras;  // scoring projects with the calibration as given, never perturbed
    if (perturb_px > 0) {
      std::mt19937_64 rng(seed);
      for (auto& c : cameras) {
        const double a = 2 * std::numbers::pi * (static_cast<double>(rng() >> 11) * 0x1.0p-53);
        c.K(0, 2) += perturb_px * std::cos(a);
        c.K(1, 2) += perturb_px * std::sin(a);
      }
    }
    // Views: the calibration defines them; the frames must not hold views it does not know.
    std::set<std::string> known;
    for (const auto& c : cameras) known.insert(c.name);
    for (const auto& e : fs::directory_iterator(frames_dir))
      if (e.is_directory() && !known.count(e.path().filename().string()))
        throw Error(cameras_file.string() + ": calibration inconsistent with the frames: " + frames_dir.string() + " has view '" +
                    e.path().filename().string() + "' but the camera file defines " + std::to_string(cameras.size()) + " view(s)");
    if (fo.ray_views.size() == 1 && fo.ray_views[0] == "all") fo.ray_views.clear();
    if (fo.coverage_views.size() == 1 && fo.coverage_views[0] == "none") fo.coverage_views.clear();
    for (const auto& name : fo.coverage_views)
      if (!known.count(name)) log::warn("--coverage-views: no view '" + name + "' in " + cameras_file.string() + "; not used");
    for (const auto& name : fo.ray_views)
      if (!known.count(name)) log::warn("--ray-views: no view '" + name + "' in " + cameras_file.string() + "; its ray features are not used");
    const std::size_t nview = cameras.size();
    std::vector<std::map<long, fs::path>> files(nview);
    std::set<long> indices;
    for (std::size_t v = 0; v < nview; ++v) {
      const auto dir = frames_dir / cameras[v].name;
      if (std::find(ignore_views.begin(), ignore_views.end(), cameras[v].name) != ignore_views.end()) {
        log::info("view '" + cameras[v].name + "' left out (--ignore-view)");
        continue;
      }
      if (!fs::is_directory(dir)) {
        log::warn("view '" + cameras[v].name + "': no frames directory " + dir.string() + "; fitting without this view");
        continue;
      }
      files[v] = list_frames(dir);
      if (files[v].empty()) log::warn("view '" + cameras[v].name + "': no frames in " + dir.string() + "; fitting without this view");
      for (const auto& [k, p] : files[v]) indices.insert(k);
    }
    if (indices.empty()) throw Error(frames_dir.string() + ": no frames (expected <view>/NNNNNN.png for the views in " + cameras_file.string() + ")");
    const std::vector<long> frames(indices.begin(), indices.end());
    for (std::size_t i = 1; i < frames.size(); ++i)
      if (frames[i] != frames[i - 1] + 1)
        log::warn("frames " + std::to_string(frames[i - 1] + 1) + ".." + std::to_string(frames[i] - 1) +
                  " are missing in every view (dropped); fitting the frames that are there");
    for (std::size_t v = 0; v < nview; ++v)
      if (!files[v].empty() && files[v].size() < frames.size())
        log::warn("view '" + cameras[v].name + "': " + std::to_string(frames.size() - files[v].size()) +
                  " frame(s) missing; those frames are fitted from the other views");
    const std::size_t nf = frames.size(), nv = surface.size(), nj = skeleton.joint_count();
    log::info("template: " + std::to_string(nv) + " vertices, skeleton " + std::to_string(nj) + " joints (" +
              std::to_string(skeleton.parameter_count()) + " parameters); " + std::to_string(nf) + " frames, " +
              std::to_string(nview) + " views");

    stage::Kinematics kin;
    kin.template_points = surface.rest;
    kin.template_triangles = surface.triangles;
    {
      std::vector<std::int32_t> off{0}, verts;
      for (std::size_t r = 0; r < surface.rays; ++r) {
        const double eta = 1.0 - 2.0 * static_cast<double>(r) / (surface.rays - 1);
        std::vector<std::pair<double, std::int32_t>> on;
        for (std::size_t v = 0; v < nv; ++v)
          if (surface.ray_distance[v] == 0 && std::abs(surface.eta[v] - eta) < 1e-9) on.push_back({surface.s[v], static_cast<std::int32_t>(v)});
        std::sort(on.begin(), on.end());
        for (const auto& [s, v] : on) verts.push_back(v);
        off.push_back(static_cast<std::int32_t>(verts.size()));
      }
      kin.ray_offsets = NdArray<std::int32_t>({off.size()}, off);
      kin.ray_vertices = NdArray<std::int32_t>({verts.size()}, verts);
    }
    kin.time = NdArray<double>({nf});
    kin.points = NdArray<double>({nf, nv, 3});
    kin.joint_parent = NdArray<std::int32_t>({nj});
    kin.joint_rest = NdArray<double>({nj, 3});
    for (std::size_t j = 0; j < nj; ++j) {
      kin.joint_parent(j) = skeleton.parent[j];
      for (int d = 0; d < 3; ++d) kin.joint_rest(j, d) = skeleton.joint_rest[j][d];
    }
    kin.joint_angles = NdArray<double>({nf, nj, 3});
    for (const auto& c : cameras) kin.views.push_back(c.name);
    kin.silhouette_iou = NdArray<double>({nf, nview});
    kin.reprojection_rms = NdArray<double>({nf, nview});
    kin.view_valid = NdArray<std::uint8_t>({nf, nview});
    kin.fps = fps;
    if (period) {
      if (!(*period > 0)) throw Error("--period: expected > 0");
      kin.period = *period;
    }

    const vision::SkeletonFitter fitter(skeleton, binding, surface.triangles, std::vector<int>(kin.ray_vertices.data.begin(), kin.ray_vertices.data.end()), fo);
    std::optional<stage::Truth> truth;
    if (!summary_out.empty()) {
      truth = stage::read<stage::Truth>(truth_file);
      const std::size_t last = static_cast<std::size_t>(frames.back());
      if (truth->points.rank() != 3 || truth->points.dim(0) <= last || truth->points.dim(1) != nv)
        throw Error(truth_file.string() + ": /points: " + shape_string(truth->points.shape) + ", expected [>" + std::to_string(last) + "," +
                    std::to_string(nv) + ",3] (the tracked frames on the tracking template, same --surface-subdivisions as fin-synth)");
    }
    // Scoring only (with --truth): per view, the worst over frames of
    //   fit_truth_iou: the fitted surface against the true surface, both as area-coverage
    //     silhouettes (silhouette_coverage.hpp: the same rasteriser for both, 4 x 4 sub-pixel
    //     samples per pixel, so a sub-pixel offset of a thin edge-on sheet costs its true area and
    //     not whole pixels) - the graded silhouette accuracy;
    //   fit_truth_pixel_iou: the same with binary pixel-centre silhouettes (reported);
    //   truth_iou: the true surface's pixel-centre silhouette against the segmentation, the most
    //     the fit-vs-segmentation IoU (kinematics' quality/silhouette_iou) can reach (reported).
    constexpr int kScoreSupersample = 4;
    const auto edges = vision::mesh_edges(surface.triangles);  // diagnostics of the coverage term
    std::vector<double> truth_iou(nview, 1.0), fit_truth_iou(nview, 1.0), fit_truth_pixel_iou(nview, 1.0);
    std::vector<cv::Mat> truth_cover(nview), truth_pixels(nview);
    log::Progress progress("track", nf);
    std::vector<vision::Pose> poses;
    double fit_seconds = 0, first_seconds = 0;
    double worst_iou = 1;
    for (std::size_t i = 0; i < nf; ++i) {
      const double t0 = log::elapsed_seconds();
      std::vector<cv::Mat> images(nview);
      std::vector<vision::ViewData> views(nview);
      std::string failure;
#pragma omp parallel for schedule(dynamic)
      for (std::ptrdiff_t v = 0; v < static_cast<std::ptrdiff_t>(nview); ++v) {
        try {
          const auto it = files[v].find(frames[i]);
          cv::Mat img;
          if (it != files[v].end()) {
            img = cv::imread(it->second.string(), cv::IMREAD_GRAYSCALE);
            if (img.empty()) throw Error(it->second.string() + ": unreadable image");
          }
          // Rays are detected only where they are fitted (--ray-views).
          auto ro = fo.rays;
          if (!fo.ray_views.empty() && std::find(fo.ray_views.begin(), fo.ray_views.end(), cameras[v].name) == fo.ray_views.end())
            ro.weight = 0;
          views[v] = vision::prepare_view(cameras[v], img, so, ro);
        } catch (const std::exception& e) {
#pragma omp critical
          if (failure.empty()) failure = e.what();
        }
      }
      if (!failure.empty()) throw Error(failure);
      if (std::none_of(views.begin(), views.end(), [](const auto& w) { return w.valid; }))
        throw Error(frames_dir.string() + ": frame " + std::to_string(frames[i]) + ": the fin is not visible in any view");
      // Scoring only: the true surface against the segmented frames. Its IoU is the most the fit
      // can reach in each view (segmentation, blur and pixels limit it, not the fit).
      if (truth) {
        const double ts = log::elapsed_seconds();
        NdArray<double> P({nv, 3});
        std::copy_n(truth->points.data.begin() + frames[i] * nv * 3, nv * 3, P.data.begin());
#pragma omp parallel for schedule(dynamic)
        for (std::ptrdiff_t v = 0; v < static_cast<std::ptrdiff_t>(nview); ++v) {
          truth_pixels[v] = vision::project_model(calibrated[v], P, surface.triangles).mask;
          truth_cover[v] = vision::silhouette_coverage(calibrated[v], P, surface.triangles, kScoreSupersample);
          if (views[v].valid) truth_iou[v] = std::min(truth_iou[v], vision::mask_iou(truth_pixels[v], views[v].mask));
        }
        fit_seconds -= log::elapsed_seconds() - ts;  // not part of the tracking time
      }
      vision::FrameFit fit;
      if (poses.empty()) {
        fit = fitter.fit(views, vision::Pose::rest(skeleton), nullptr, fo.first_iterations);
      } else {
        // Prediction: the last pose plus a fraction of the last change (over the possibly uneven
        // frame spacing). Less than the full velocity, so a direction the images barely constrain
        // cannot keep drifting on its own momentum.
        vision::Pose pred = poses.back();
        if (poses.size() >= 2) {
          const double ratio = static_cast<double>(frames[i] - frames[i - 1]) / static_cast<double>(frames[i - 1] - frames[i - 2]);
          for (std::size_t p = 0; p < pred.p.size(); ++p)
            pred.p[p] += velocity_factor * ratio * (poses.back().p[p] - poses[poses.size() - 2].p[p]);
        }
        fit = fitter.fit(views, pred, &pred, fo.iterations);
      }
      fit_seconds += log::elapsed_seconds() - t0;
      if (i == 0) first_seconds = fit_seconds;
      if (truth) {
        // Every view the calibration defines, also one left out or without this frame: the fit
        // is a 3-D surface and must project onto the truth in every camera.
#pragma omp parallel for schedule(dynamic)
        for (std::ptrdiff_t v = 0; v < static_cast<std::ptrdiff_t>(nview); ++v) {
          const auto cover = vision::silhouette_coverage(calibrated[v], fit.points, surface.triangles, kScoreSupersample);
          const double a = vision::coverage_iou(cover, truth_cover[v]);
          const double b = vision::mask_iou(vision::project_model(calibrated[v], fit.points, surface.triangles).mask, truth_pixels[v]);
          // Diagnostics (--log-level debug): silhouette areas in px of the fit and the truth (both
          // by coverage) and of the segmentation, which tell whether a low IoU is a thin fit.
          char line[320];
          // ... and, where the coverage term is fitted, its cost at the fit and at the truth and
          // the soft segmentation's IoU against the true coverage (is a shortfall the optimiser's
          // or the data's).
          double cost_fit = -1, cost_truth = -1, soft_iou = -1;
          if (views[v].valid && std::find(fo.coverage_views.begin(), fo.coverage_views.end(), cameras[v].name) != fo.coverage_views.end()) {
            NdArray<double> P({nv, 3});
            std::copy_n(truth->points.data.begin() + frames[i] * nv * 3, nv * 3, P.data.begin());
            vision::NormalEquations ne_fit(0), ne_truth(0);
            vision::add_coverage_residuals(views[v], vision::project_model(calibrated[v], fit.points, surface.triangles), surface.triangles,
                                           edges, nullptr, fo.coverage, ne_fit);
            vision::add_coverage_residuals(views[v], vision::project_model(calibrated[v], P, surface.triangles), surface.triangles, edges,
                                           nullptr, fo.coverage, ne_truth);
            cost_fit = ne_fit.cost(), cost_truth = ne_truth.cost();
            cv::Mat soft;
            cv::max(views[v].coverage, 0.0, soft);
            cv::min(soft, 1.0, soft);
            soft_iou = vision::coverage_iou(soft, truth_cover[v]);
          }
          std::snprintf(line, sizeof line,
                        "score frame %ld view %s: fit-truth IoU %.4f, areas fit %.1f truth %.1f segmented %d; coverage cost fit %.3f "
                        "truth %.3f, soft-truth IoU %.4f",
                        frames[i], cameras[v].name.c_str(), a, cv::sum(cover)[0], cv::sum(truth_cover[v])[0],
                        views[v].valid ? cv::countNonZero(views[v].mask) : -1, cost_fit, cost_truth, soft_iou);
#pragma omp critical
          {
            log::debug(line);
            fit_truth_iou[v] = std::min(fit_truth_iou[v], a), fit_truth_pixel_iou[v] = std::min(fit_truth_pixel_iou[v], b);
          }
        }
      }
      if (truth) {
        // Diagnostics: the frame's worst vertex, its place on the fin and its error vector.
        std::size_t worst = 0;
        double e2 = -1;
        for (std::size_t k = 0; k < nv; ++k) {
          double d2 = 0;
          for (int d = 0; d < 3; ++d) d2 += std::pow(fit.points(k, d) - truth->points(frames[i], k, d), 2);
          if (d2 > e2) e2 = d2, worst = k;
        }
        char line[224];
        std::snprintf(line, sizeof line, "score frame %ld: worst vertex %zu (eta %.3f, s %.3f) error %.3f %% c, (dx, dy, dz) = (%.3f, %.3f, %.3f) %% c",
                      frames[i], worst, surface.eta[worst], surface.s[worst], 100 * std::sqrt(e2) / fin.chord,
                      100 * (fit.points(worst, 0) - truth->points(frames[i], worst, 0)) / fin.chord,
                      100 * (fit.points(worst, 1) - truth->points(frames[i], worst, 1)) / fin.chord,
                      100 * (fit.points(worst, 2) - truth->points(frames[i], worst, 2)) / fin.chord);
        log::debug(line);
      }
      poses.push_back(fit.pose);
      kin.time(i) = static_cast<double>(frames[i]) / fps;
      std::copy(fit.points.data.begin(), fit.points.data.end(), kin.points.data.begin() + i * nv * 3);
      for (std::size_t j = 0; j < nj; ++j)
        for (int d = 0; d < 3; ++d) kin.joint_angles(i, j, d) = fit.pose.p[3 + 3 * j + d];
      for (std::size_t v = 0; v < nview; ++v) {
        kin.silhouette_iou(i, v) = fit.iou[v];
        kin.reprojection_rms(i, v) = fit.rms_px[v];
        kin.view_valid(i, v) = fit.valid[v];
        if (fit.valid[v]) worst_iou = std::min(worst_iou, fit.iou[v]);
      }
      char status[96];
      std::snprintf(status, sizeof status, "frame %ld, %d LM iterations, worst IoU so far %.4f", frames[i], fit.iterations, worst_iou);
      progress.update(i + 1, status);
    }
    progress.finish();
    // Steady state: the first frame starts cold from the rest pose and takes many more steps.
    const double per_frame = nf > 1 ? (fit_seconds - first_seconds) / (nf - 1) : fit_seconds;
    log::info("tracking: " + std::to_string(per_frame) + " s per frame set after the first (" + std::to_string(first_seconds) +
              " s, cold start); " + std::to_string(nview) + " views, " + std::to_string(cli::threads_in_use()) +
              " threads; worst silhouette IoU " + std::to_string(worst_iou));

    Provenance prov{"fin-track", cli::effective_config(app), {cameras_file}};
    if (!tmpl.file.empty()) prov.inputs.push_back(tmpl.file);
    stage::write(out, kin, prov);
    log::info("wrote " + out.string());

    int status = kExitOk;
    if (!summary_out.empty()) {
      const auto te = trailing_edge(surface);
      std::vector<std::size_t> rows;  // truth frames matching the tracked ones
      for (long k : frames) {
        if (static_cast<std::size_t>(k) >= truth->time.size())
          throw Error(truth_file.string() + ": /time: has " + std::to_string(truth->time.size()) + " frames, the frames go to " + std::to_string(k));
        rows.push_back(static_cast<std::size_t>(k));
      }
      auto truth_rows = [&](const NdArray<double>& all) {
        if (all.rank() != 3 || all.dim(1) != nv)
          throw Error(truth_file.string() + ": /points: " + shape_string(all.shape) + ", expected [nf," + std::to_string(nv) +
                      ",3] on the tracking template (same --surface-subdivisions as fin-synth)");
        NdArray<double> sel({rows.size(), nv, 3});
        for (std::size_t i = 0; i < rows.size(); ++i)
          std::copy_n(all.data.begin() + rows[i] * nv * 3, nv * 3, sel.data.begin() + i * nv * 3);
        return sel;
      };
      const auto truth_points = truth_rows(truth->points);
      const auto sc = vision::score_tracking(kin.points, truth_points, fin.chord, te);
      Summary sum("validation", "tracking",
                  "fin-track on fin-synth frames (noise, blur) scored against truth.h5: vertex error, silhouette IoU, trailing-edge amplitude");
      const std::string src = "issue 5 accuracy criteria";
      sum.at_most("mean_vertex_error", sc.mean_error, 0.01, src + ": mean <= 1% of chord", "1");
      sum.at_most("p95_vertex_error", sc.p95_error, 0.02, src + ": 95th percentile <= 2% of chord", "1");
      sum.at_most("max_vertex_error", sc.max_error, 0.04, src + ": max <= 4% of chord", "1");
      for (std::size_t v = 0; v < nview; ++v) {
        const auto& name = cameras[v].name;
        sum.at_most("iou_shortfall_" + name, 0.97 - fit_truth_iou[v], 0.0,
                    src + ": silhouette IoU >= 0.97 in every view and frame (0.97 - worst IoU of the fitted against the true surface, "
                          "area-coverage silhouettes at the image resolution)",
                    "1");
        sum.info("worst_fit_truth_iou_" + name, fit_truth_iou[v], "1");
        sum.info("worst_fit_truth_pixel_iou_" + name, fit_truth_pixel_iou[v], "1");
        double lo = 1;
        bool any = false;
        for (std::size_t i = 0; i < nf; ++i)
          if (kin.view_valid(i, v)) lo = std::min(lo, kin.silhouette_iou(i, v)), any = true;
        if (any) sum.info("worst_iou_" + name, lo, "1");  // fit against the segmentation
        if (any) sum.info("worst_truth_iou_" + name, truth_iou[v], "1");  // truth against the segmentation
      }
      sum.at_most("te_amplitude_error", sc.te_amplitude_error, 0.02,
                  src + ": trailing-edge peak-to-peak amplitude within 2% (worst TE vertex)", "1");
      sum.info("te_amplitude_truth", sc.te_amplitude_truth, "m");
      sum.info("te_amplitude_fit", sc.te_amplitude_fit, "m");
      for (const auto& spec : also_score) {
        const auto eq = spec.find('=');
        if (eq == std::string::npos) throw Error("--also-score: expected label=kinematics.h5, got '" + spec + "'");
        const auto label = spec.substr(0, eq);
        const auto other = stage::read<stage::Kinematics>(spec.substr(eq + 1));
        if (other.points.shape != kin.points.shape)
          throw Error(spec.substr(eq + 1) + ": /points: " + shape_string(other.points.shape) + ", expected " + shape_string(kin.points.shape));
        const auto o = vision::score_tracking(other.points, truth_points, fin.chord, te);
        sum.info(label + "_mean_vertex_error", o.mean_error, "1");
        sum.info(label + "_p95_vertex_error", o.p95_error, "1");
        sum.info(label + "_max_vertex_error", o.max_error, "1");
        sum.info(label + "_te_amplitude_error", o.te_amplitude_error, "1");
      }
      sum.info("frames", static_cast<double>(nf));
      sum.info("seconds_per_frame_set", per_frame, "s");
      sum.info("first_frame_seconds", first_seconds, "s");
      sum.parameters() = cli::effective_config(app);
      sum.set_timing(fit_seconds, cli::threads_in_use());
      sum.write(summary_out);
      log::info("mean / p95 / max vertex error " + std::to_string(100 * sc.mean_error) + " / " + std::to_string(100 * sc.p95_error) +
                " / " + std::to_string(100 * sc.max_error) + " % of chord; TE amplitude error " + std::to_string(100 * sc.te_amplitude_error) + " %");
      if (!sum.pass()) {
        log::error("a validation metric failed: see " + summary_out.string());
        status = kExitDifferent;
      }
    }
    if (!bench_out.empty()) {
      Summary b("bench", "track", "fin-track seconds per frame set (all views) and fin-mesh wall time, default resolution");
      b.at_most("seconds_per_frame_set", per_frame, 0.5,
                "issue 5: fin-track <= 0.5 s per frame set on 2 cores (load, segment, fit; warm-started frames)", "s");
      b.info("first_frame_seconds", first_seconds, "s");
      if (!mesh_summary.empty()) {
        const auto ms = Summary::read(mesh_summary);
        for (const auto& m : ms.metrics())
          if (m.name == "mesh_wall_time") b.at_most("fin_mesh_wall_time", m.value, 5.0, "issue 5: fin-mesh <= 5 s for the default fin", "s");
      }
      b.info("frames", static_cast<double>(nf));
      b.info("views", static_cast<double>(nview));
      b.info("image_width", cameras[0].width, "px");
      b.parameters() = cli::effective_config(app);
      b.set_timing(fit_seconds, cli::threads_in_use());
      b.write(bench_out);
      if (!b.pass()) status = kExitDifferent;
    }
    return status;
  });
}
