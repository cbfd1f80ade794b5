// fin-track's tracker flags (see tracker_flags.hpp).
#include "vision/tracker_flags.hpp"

#include <algorithm>
#include <cstdio>

#include "core/error.hpp"

namespace finverse::vision {

BackgroundModel background_model(const std::string& name) {
  return name == "model" ? BackgroundModel::model : name == "median" ? BackgroundModel::median : BackgroundModel::automatic;
}

void add_tracker_flags(CLI::App& app, TrackerFlags& f) {
  auto& to = f.options;
  auto& fo = to.fit;
  app.add_option("--surface-subdivisions", to.surface_subdivisions, "template surface columns per gap between rays (even)")
      ->capture_default_str();
  app.add_option("--segments", to.segments, "skeleton segments per ray")->capture_default_str();
  app.add_option("--iterations", fo.iterations, "LM iterations per frame")->capture_default_str();
  app.add_option("--tolerance", fo.tolerance, "LM: stop when the cost falls by less than this fraction")->capture_default_str();
  app.add_option("--step-tolerance", fo.step_tolerance, "LM: stop when no parameter moves by more than this (rad, chords)")->capture_default_str();
  app.add_option("--max-rejections", fo.max_rejections, "LM: stop after this many rejected steps in a row (0: never)")->capture_default_str();
  app.add_option("--first-iterations", fo.first_iterations, "LM iterations for the first frame")->capture_default_str();
  app.add_option("--temporal-sigma", fo.temporal_sigma, "temporal prior: rad (translation: chords)")->capture_default_str();
  app.add_option("--neighbour-sigma", fo.neighbour_sigma, "prior on joint differences of neighbouring rays (rad)")->capture_default_str();
  app.add_option("--out-of-plane-sigma", fo.out_of_plane_sigma, "prior on twist and in-plane bending (rad)")->capture_default_str();
  app.add_option("--span-curvature-sigma", fo.span_curvature_sigma,
                 "prior on the second difference of joint angles across three rays (rad; 0: off)")
      ->capture_default_str();
  app.add_option("--contour-stride", fo.silhouette.contour_stride, "use every n-th silhouette contour pixel")->capture_default_str();
  app.add_option("--prediction-velocity", to.prediction_velocity,
                 "fraction of the last frame-to-frame change carried into the next frame's prediction (1: constant velocity)")
      ->capture_default_str();
  // Defaults of the ray and coverage terms: docs/studies/tracking_fit_defaults.md.
  app.add_option("--ray-views", fo.ray_views, "views whose ray features are fitted ('auto': the face-on views; 'all': every view)")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--ray-weight", fo.rays.weight, "weight of the ray-feature residuals (0: silhouettes only)")->capture_default_str();
  app.add_option("--coverage-views", fo.coverage_views,
                 "views fitted with the sub-pixel coverage term ('auto': the edge-on views; 'none': no view)")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--coverage-weight", fo.coverage.weight, "weight of a pixel's coverage residual (0: off)")->capture_default_str();
  app.add_option("--coverage-chamfer-weight", fo.coverage_chamfer_weight,
                 "factor on the silhouette chamfer weight in the coverage views while the coverage term is on")
      ->capture_default_str();
  app.add_option("--coverage-band", fo.coverage.band_px, "coverage term: pixels within this distance of the data outline (px)")
      ->capture_default_str();
  app.add_option("--ray-contrast", fo.rays.min_contrast, "ray detection: black-hat threshold (8-bit levels)")->capture_default_str();
  app.add_option("--min-contrast", to.segmentation.min_contrast, "segmentation: smallest darkening that counts as fin (8-bit levels)")
      ->capture_default_str();
  app.add_option("--noise-floor", to.segmentation.noise_floor,
                 "segmentation: the sensor noise is never taken below this (8-bit levels; compressed video reads 0)")
      ->capture_default_str();
  app.add_option("--background", f.background,
                 "segmentation background: model (smooth fit per frame), median (the clip's temporal median) or auto (the model, "
                 "and the temporal 90th percentile for static dark structure touching the border when a view has >= " +
                     std::to_string(kMedianMinFrames) + " frames)")
      ->check(CLI::IsMember({"model", "median", "auto"}))
      ->capture_default_str();
  app.add_flag("!--keep-border-blobs", to.segmentation.reject_border,
               "segmentation: do not prefer blobs clear of the image border (default: a blob touching it is the fish only when no other is)");
  app.add_option("--fin-cut", f.fin_cut,
                 "cut the caudal fin from the body: none; peduncle (the narrowest point behind the body); root-plane (at the "
                 "projected plane x = 0 of the template's root in the views that see it as a line; in a view from behind, the "
                 "opaque body behind the fin is left out of the fit)")
      ->check(CLI::IsMember({"none", "peduncle", "root-plane"}))
      ->capture_default_str();
  app.add_option("--fin-region", f.fin_regions, "view=x0,y0,x1,y1: the rectangle (px) of that view that holds the fin (repeatable)");
  // When the fit cannot be trusted (tools/vision/fit_quality.hpp): exit 1, the record flagged.
  app.add_option("--min-views", to.quality.min_views, "fit check: views per frame that fix the fin in depth")->capture_default_str();
  app.add_option("--min-iou", to.quality.min_iou, "fit check: the worst view's silhouette IoU, median over frames, at least")
      ->capture_default_str();
  app.add_option("--max-root-drift", to.quality.max_root_drift,
                 "fit check: the root's largest distance from its first position (chords; 0: not checked)")
      ->capture_default_str();
  app.add_option("--max-area-ratio", to.quality.max_area_ratio,
                 "fit check: the fitted over segmented silhouette area in a view (median over frames) within this factor")
      ->capture_default_str();
}

void apply_tracker_flags(TrackerFlags& f, const std::vector<Camera>& cameras, const std::string& cameras_file) {
  auto& to = f.options;
  to.segmentation.fin_cut = f.fin_cut == "peduncle";
  to.cut_at_root_plane = f.fin_cut == "root-plane";
  to.segmentation.background = background_model(f.background);
  for (const auto& item : f.fin_regions) {
    const auto eq = item.find('=');
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    char tail = 0;
    if (eq == std::string::npos ||
        std::sscanf(item.c_str() + eq + 1, "%d,%d,%d,%d%c", &x0, &y0, &x1, &y1, &tail) != 4 || x1 <= x0 || y1 <= y0)
      throw Error("--fin-region: expected view=x0,y0,x1,y1 with x1 > x0 and y1 > y0 (px), got '" + item + "'");
    const auto name = item.substr(0, eq);
    if (std::none_of(cameras.begin(), cameras.end(), [&](const auto& c) { return c.name == name; }))
      throw Error("--fin-region: no view '" + name + "' in " + cameras_file);
    to.fin_regions[name] = cv::Rect(x0, y0, x1 - x0, y1 - y0);
  }
}

}  // namespace finverse::vision
