// fin-track's per-frame loop: load and segment, predict, fit, assemble kinematics.h5, score
// against the truth (see tracker.hpp).
#include "vision/tracker.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "core/error.hpp"
#include "core/log.hpp"
#include "vision/coverage_residual.hpp"
#include "vision/silhouette_coverage.hpp"
#include "vision/view_data.hpp"
#include "vision/view_roles.hpp"

namespace finverse::vision {

FitOptions tracking_fit_options() {
  // Measured on the 100 validation frames: docs/studies/tracking_fit_defaults.md.
  FitOptions fo;
  fo.ray_views = {"auto"};       // the face-on views (view_roles.hpp)
  fo.coverage_views = {"auto"};  // the edge-on views
  fo.coverage.weight = 5;
  fo.coverage.band_px = 2;
  fo.coverage_chamfer_weight = 0.2;
  fo.iterations = 18;
  fo.max_rejections = 2;
  return fo;
}

TrackingModel make_tracking_model(const mesh::FinTemplate& fin, int surface_subdivisions, int segments) {
  TrackingModel m;
  m.chord = fin.chord;
  m.surface = make_fin_surface(fin, surface_subdivisions);
  m.skeleton = make_skeleton(fin, segments);
  m.binding = bind_skin(fin, m.skeleton, m.surface.rest);
  // Ray axes: the vertices on each ray line (ray_distance 0 at its eta), root to tip.
  const auto& surface = m.surface;
  std::vector<std::int32_t> off{0}, verts;
  for (std::size_t r = 0; r < surface.rays; ++r) {
    const double eta = 1.0 - 2.0 * static_cast<double>(r) / (surface.rays - 1);
    std::vector<std::pair<double, std::int32_t>> on;
    for (std::size_t v = 0; v < surface.size(); ++v)
      if (surface.ray_distance[v] == 0 && std::abs(surface.eta[v] - eta) < 1e-9)
        on.push_back({surface.s[v], static_cast<std::int32_t>(v)});
    std::sort(on.begin(), on.end());
    for (const auto& [s, v] : on) verts.push_back(v);
    off.push_back(static_cast<std::int32_t>(verts.size()));
  }
  m.ray_offsets = NdArray<std::int32_t>({off.size()}, off);
  m.ray_vertices = NdArray<std::int32_t>({verts.size()}, verts);
  return m;
}

RayEnds TrackingModel::ray_ends() const {
  RayEnds e;
  for (std::size_t r = 0; r + 1 < ray_offsets.size(); ++r) {
    e.root.push_back(ray_vertices(static_cast<std::size_t>(ray_offsets(r))));
    e.tip.push_back(ray_vertices(static_cast<std::size_t>(ray_offsets(r + 1)) - 1));
  }
  return e;
}

Pose predict_pose(const Pose& last, const Pose* before, double gap_ratio, double velocity) {
  Pose pred = last;
  if (before)
    for (std::size_t p = 0; p < pred.p.size(); ++p) pred.p[p] += velocity * gap_ratio * (last.p[p] - before->p[p]);
  return pred;
}

Tracker::Tracker(const mesh::FinTemplate& fin, const TrackerOptions& options)
    : options_(options), model_(make_tracking_model(fin, options.surface_subdivisions, options.segments)) {
  fitter_ = std::make_unique<SkeletonFitter>(
      model_.skeleton, model_.binding, model_.surface.triangles,
      std::vector<int>(model_.ray_vertices.data.begin(), model_.ray_vertices.data.end()), options_.fit);
  fitter_->set_ray_ends(model_.ray_ends());
}

Tracker::~Tracker() = default;

namespace {

// kinematics.h5 without the per-frame data: the template, its ray axes, the skeleton, the views.
stage::Kinematics empty_record(const TrackingModel& m, const std::vector<Camera>& cameras, std::size_t nf,
                               const TrackerOptions& o) {
  const std::size_t nv = m.surface.size(), nj = m.skeleton.joint_count(), nview = cameras.size();
  stage::Kinematics kin;
  kin.template_points = m.surface.rest;
  kin.template_triangles = m.surface.triangles;
  kin.ray_offsets = m.ray_offsets;
  kin.ray_vertices = m.ray_vertices;
  kin.time = NdArray<double>({nf});
  kin.points = NdArray<double>({nf, nv, 3});
  kin.joint_parent = NdArray<std::int32_t>({nj});
  kin.joint_rest = NdArray<double>({nj, 3});
  for (std::size_t j = 0; j < nj; ++j) {
    kin.joint_parent(j) = m.skeleton.parent[j];
    for (int d = 0; d < 3; ++d) kin.joint_rest(j, d) = m.skeleton.joint_rest[j][d];
  }
  kin.joint_angles = NdArray<double>({nf, nj, 3});
  for (const auto& c : cameras) kin.views.push_back(c.name);
  kin.silhouette_iou = NdArray<double>({nf, nview});
  kin.reprojection_rms = NdArray<double>({nf, nview});
  kin.view_valid = NdArray<std::uint8_t>({nf, nview});
  kin.fps = o.fps;
  kin.period = o.period;
  return kin;
}

// Scoring only (with a truth), per view, the worst over frames of
//   fit_truth_iou: the fitted surface against the true surface, both as area-coverage
//     silhouettes (silhouette_coverage.hpp: the same rasteriser for both, 4 x 4 sub-pixel
//     samples per pixel, so a sub-pixel offset of a thin edge-on sheet costs its true area and
//     not whole pixels) - the graded silhouette accuracy;
//   fit_truth_pixel_iou: the same with binary pixel-centre silhouettes (reported);
//   truth_iou: the true surface's pixel-centre silhouette against the segmentation, the most
//     the fit-vs-segmentation IoU (kinematics' quality/silhouette_iou) can reach (reported).
class TruthScorer {
 public:
  TruthScorer(const TruthReference& truth, const TrackingModel& m, const FitOptions& fo)
      : t_(truth), m_(m), fo_(fo), edges_(mesh_edges(m.surface.triangles)) {
    const std::size_t nview = t_.cameras.size();
    truth_iou.assign(nview, 1.0), fit_truth_iou.assign(nview, 1.0), fit_truth_pixel_iou.assign(nview, 1.0);
    truth_cover_.resize(nview), truth_pixels_.resize(nview);
  }

  // The true surface of frame index k against the segmented views, before the fit.
  void segmentation(long k, const std::vector<ViewData>& views) {
    const auto P = true_points(k);
#pragma omp parallel for schedule(dynamic)
    for (std::ptrdiff_t v = 0; v < static_cast<std::ptrdiff_t>(t_.cameras.size()); ++v) {
      truth_pixels_[v] = project_model(t_.cameras[v], P, m_.surface.triangles).mask;
      truth_cover_[v] = silhouette_coverage(t_.cameras[v], P, m_.surface.triangles, kSupersample);
      if (views[v].valid) truth_iou[v] = std::min(truth_iou[v], mask_iou(truth_pixels_[v], views[v].mask, views[v].body));
    }
  }

  // The fit of frame index k in every view the calibration defines, also one left out or
  // without this frame: the fit is a 3-D surface and must project onto the truth in every camera.
  void fit(long k, const std::vector<ViewData>& views, const FrameFit& fit) {
    const auto& tri = m_.surface.triangles;
#pragma omp parallel for schedule(dynamic)
    for (std::ptrdiff_t v = 0; v < static_cast<std::ptrdiff_t>(t_.cameras.size()); ++v) {
      const auto& cam = t_.cameras[v];
      const auto cover = silhouette_coverage(cam, fit.points, tri, kSupersample);
      const double a = coverage_iou(cover, truth_cover_[v]);
      const double b = mask_iou(project_model(cam, fit.points, tri).mask, truth_pixels_[v]);
      // Diagnostics (--log-level debug): silhouette areas in px of the fit and the truth (both
      // by coverage) and of the segmentation, which tell whether a low IoU is a thin fit, and,
      // where the coverage term is fitted, its cost at the fit and at the truth and the soft
      // segmentation's IoU against the true coverage (is a shortfall the optimiser's or the data's).
      char line[320];
      double cost_fit = -1, cost_truth = -1, soft_iou = -1;
      if (views[v].valid && fits_coverage(fo_.coverage_views, cam)) {
        const auto P = true_points(k);
        NormalEquations ne_fit(0), ne_truth(0);
        add_coverage_residuals(views[v], project_model(cam, fit.points, tri), tri, edges_, nullptr, fo_.coverage,
                               ne_fit);
        add_coverage_residuals(views[v], project_model(cam, P, tri), tri, edges_, nullptr, fo_.coverage, ne_truth);
        cost_fit = ne_fit.cost(), cost_truth = ne_truth.cost();
        cv::Mat soft;
        cv::max(views[v].coverage, 0.0, soft);
        cv::min(soft, 1.0, soft);
        soft_iou = coverage_iou(soft, truth_cover_[v]);
      }
      std::snprintf(
          line, sizeof line,
          "score frame %ld view %s: fit-truth IoU %.4f, areas fit %.1f truth %.1f segmented %d; coverage cost fit %.3f "
          "truth %.3f, soft-truth IoU %.4f",
          k, cam.name.c_str(), a, cv::sum(cover)[0], cv::sum(truth_cover_[v])[0],
          views[v].valid ? cv::countNonZero(views[v].mask) : -1, cost_fit, cost_truth, soft_iou);
#pragma omp critical
      {
        log::debug(line);
        fit_truth_iou[v] = std::min(fit_truth_iou[v], a), fit_truth_pixel_iou[v] = std::min(fit_truth_pixel_iou[v], b);
      }
    }
    // Diagnostics: the frame's worst vertex, its place on the fin and its error vector.
    const auto& T = *t_.points;
    const auto& s = m_.surface;
    const std::size_t nv = s.size();
    std::size_t worst = 0;
    double e2 = -1;
    for (std::size_t i = 0; i < nv; ++i) {
      double d2 = 0;
      for (int d = 0; d < 3; ++d) d2 += std::pow(fit.points(i, d) - T(k, i, d), 2);
      if (d2 > e2) e2 = d2, worst = i;
    }
    char line[224];
    std::snprintf(
        line, sizeof line,
        "score frame %ld: worst vertex %zu (eta %.3f, s %.3f) error %.3f %% c, (dx, dy, dz) = (%.3f, %.3f, %.3f) %% c",
        k, worst, s.eta[worst], s.s[worst], 100 * std::sqrt(e2) / m_.chord,
        100 * (fit.points(worst, 0) - T(k, worst, 0)) / m_.chord,
        100 * (fit.points(worst, 1) - T(k, worst, 1)) / m_.chord,
        100 * (fit.points(worst, 2) - T(k, worst, 2)) / m_.chord);
    log::debug(line);
  }

  std::vector<double> truth_iou, fit_truth_iou, fit_truth_pixel_iou;

 private:
  static constexpr int kSupersample = 4;
  NdArray<double> true_points(long k) const {
    const std::size_t nv = m_.surface.size();
    NdArray<double> P({nv, 3});
    std::copy_n(t_.points->data.begin() + k * nv * 3, nv * 3, P.data.begin());
    return P;
  }
  const TruthReference& t_;
  const TrackingModel& m_;
  const FitOptions& fo_;
  std::vector<MeshEdge> edges_;
  std::vector<cv::Mat> truth_cover_, truth_pixels_;
};

}  // namespace

TrackResult Tracker::track(const TrackInput& in, const TruthReference* truth) const {
  const auto& frames = in.frames;
  const auto& cameras = in.cameras;
  const auto& fo = options_.fit;
  const auto& surface = model_.surface;
  const std::size_t nf = frames.size(), nv = surface.size(), nj = model_.skeleton.joint_count(), nview = cameras.size();
  if (nf == 0) throw Error(in.source + ": no frames to track");
  log::info("template: " + std::to_string(nv) + " vertices, skeleton " + std::to_string(nj) + " joints (" +
            std::to_string(model_.skeleton.parameter_count()) + " parameters); " + std::to_string(nf) + " frames, " +
            std::to_string(nview) + " views");
  std::optional<TruthScorer> scorer;
  if (truth) {
    const auto& T = *truth->points;
    const std::size_t last = static_cast<std::size_t>(frames.back());
    if (T.rank() != 3 || T.dim(0) <= last || T.dim(1) != nv)
      throw Error(truth->name + ": /points: " + shape_string(T.shape) + ", expected [>" + std::to_string(last) + "," +
                  std::to_string(nv) +
                  ",3] (the tracked frames on the tracking template, same --surface-subdivisions as fin-synth)");
    if (truth->cameras.size() != nview)
      throw Error(truth->name + ": scoring needs the calibration of every fitted view");
    scorer.emplace(*truth, model_, fo);
  }

  // Static background per view (segmentation.hpp): the temporal median of up to 31 frames
  // spread evenly over the record, when the record is long enough for the fish to move on.
  const auto& so = options_.segmentation;
  std::vector<cv::Mat> medians(nview);
  const bool use_median = (so.background == BackgroundModel::median && nf >= 3) ||
                          (so.background == BackgroundModel::automatic && nf >= static_cast<std::size_t>(kMedianMinFrames));
  if (so.background == BackgroundModel::median && !use_median)
    log::warn(in.source + ": a median background needs at least 3 frames; the background model is used");
  if (use_median) {
    const std::size_t k = std::min<std::size_t>(nf, 31);
    std::string failure;
#pragma omp parallel for schedule(dynamic)
    for (std::ptrdiff_t v = 0; v < static_cast<std::ptrdiff_t>(nview); ++v) {
      try {
        std::vector<cv::Mat> sample;
        for (std::size_t j = 0; j < k; ++j) {
          cv::Mat img = in.load(static_cast<std::size_t>(v), frames[k > 1 ? j * (nf - 1) / (k - 1) : 0]);
          if (!img.empty()) sample.push_back(img);
        }
        if (sample.size() >= 3)
          medians[v] = temporal_median(sample, so.background == BackgroundModel::median ? 0.5 : kStaticQuantile);
      } catch (const std::exception& e) {
#pragma omp critical
        if (failure.empty()) failure = e.what();
      }
    }
    if (!failure.empty()) throw Error(failure);
    log::info("background: temporal " + std::string(so.background == BackgroundModel::automatic ? "90th percentile" : "median") +
              " of " + std::to_string(k) + " frames per view" +
              (so.background == BackgroundModel::automatic ? " (static dark structure touching the border)" : ""));
  }
  std::vector<cv::Mat> last_mask(nview);  // the fish's mask in each view's last frame that showed it
  std::vector<int> lost(nview, 0), at_border(nview, 0);

  TrackResult r;
  r.frames = frames;
  r.kinematics = empty_record(model_, cameras, nf, options_);
  auto& kin = r.kinematics;
  log::Progress progress("track", nf);
  std::vector<Pose> poses;
  std::vector<FrameQuality> quality(nf);
  for (std::size_t i = 0; i < nf; ++i) {
    const double t0 = log::elapsed_seconds();
    std::vector<ViewData> views(nview);
    std::string failure;
#pragma omp parallel for schedule(dynamic)
    for (std::ptrdiff_t v = 0; v < static_cast<std::ptrdiff_t>(nview); ++v) {
      try {
        const cv::Mat img = in.load(static_cast<std::size_t>(v), frames[i]);
        // Rays are detected only where they are fitted (FitOptions::ray_views).
        auto ro = fo.rays;
        if (!fits_rays(fo.ray_views, cameras[v])) ro.weight = 0;
        SegmentationContext ctx;
        ctx.median = medians[v], ctx.previous = last_mask[v];
        if (const auto it = options_.fin_regions.find(cameras[v].name); it != options_.fin_regions.end()) ctx.fin_region = it->second;
        // The body is cut off at the root plane where the view sees it as a line; elsewhere (from
        // behind) it lies behind the fin and is marked (Segmentation::body) and left out.
        if (options_.cut_at_root_plane || so.fin_cut) {
          const bool line = root_plane_line(cameras[v], model_.chord, ctx.root_line);
          ctx.cut_at_line = line && options_.cut_at_root_plane;
          ctx.orient_by_line = line && so.fin_cut;
          ctx.find_body = !line;
          // The cut lies a fiftieth of a chord upstream of the root; the band reaches as far
          // downstream of the root, and the body's rim beyond (fin_separation.hpp).
          if (ctx.cut_at_line) {
            const auto q = cameras[v].project({0.02 * model_.chord, 0, 0});
            ctx.root_band_px = ctx.root_line[0] * q.x + ctx.root_line[1] * q.y + ctx.root_line[2] + so.body_rim_px;
          }
        }
        views[v] = prepare_view(cameras[v], img, so, ro, ctx);
        if (views[v].valid) last_mask[v] = views[v].mask;
        lost[v] += views[v].lost, at_border[v] += views[v].valid && views[v].touches_border;
      } catch (const std::exception& e) {
#pragma omp critical
        if (failure.empty()) failure = e.what();
      }
    }
    if (!failure.empty()) throw Error(failure);
    if (std::none_of(views.begin(), views.end(), [](const auto& w) { return w.valid; }))
      throw Error(in.source + ": frame " + std::to_string(frames[i]) + ": the fin is not visible in any view");
    // Scoring only: the true surface against the segmented frames. Its IoU is the most the fit
    // can reach in each view (segmentation, blur and pixels limit it, not the fit).
    if (scorer) {
      const double ts = log::elapsed_seconds();
      scorer->segmentation(frames[i], views);
      r.seconds -= log::elapsed_seconds() - ts;  // not part of the tracking time
    }
    FrameFit fit;
    const FrameKeypoints* keypoints = nullptr;
    if (in.keypoints)
      if (const auto it = in.keypoints->find(frames[i]); it != in.keypoints->end()) keypoints = &it->second;
    if (poses.empty()) {
      fit = fitter_->fit(views, Pose::rest(model_.skeleton), nullptr, fo.first_iterations, keypoints);
    } else {
      // Over the possibly uneven frame spacing.
      const bool two = poses.size() >= 2;
      const double ratio =
          two ? static_cast<double>(frames[i] - frames[i - 1]) / static_cast<double>(frames[i - 1] - frames[i - 2])
              : 0.0;
      const Pose pred =
          predict_pose(poses.back(), two ? &poses[poses.size() - 2] : nullptr, ratio, options_.prediction_velocity);
      fit = fitter_->fit(views, pred, &pred, fo.iterations, keypoints);
    }
    r.seconds += log::elapsed_seconds() - t0;
    if (i == 0) r.first_seconds = r.seconds;
    if (scorer) scorer->fit(frames[i], views, fit);
    poses.push_back(fit.pose);
    kin.time(i) = static_cast<double>(frames[i]) / options_.fps;
    std::copy(fit.points.data.begin(), fit.points.data.end(), kin.points.data.begin() + i * nv * 3);
    for (std::size_t j = 0; j < nj; ++j)
      for (int d = 0; d < 3; ++d) kin.joint_angles(i, j, d) = fit.pose.p[3 + 3 * j + d];
    auto& q = quality[i];
    q.frame = frames[i];
    q.iou = fit.iou, q.area_ratio = fit.area_ratio, q.valid = fit.valid;
    q.doubt.assign(nview, 0);
    for (std::size_t v = 0; v < nview; ++v) q.doubt[v] = views[v].touches_border || views[v].lost;
    // The root translation is in chords (skeleton.hpp).
    q.root_drift = std::hypot(fit.pose.p[0] - poses[0].p[0], fit.pose.p[1] - poses[0].p[1], fit.pose.p[2] - poses[0].p[2]);
    for (std::size_t v = 0; v < nview; ++v) {
      kin.silhouette_iou(i, v) = fit.iou[v];
      kin.reprojection_rms(i, v) = fit.rms_px[v];
      kin.view_valid(i, v) = fit.valid[v];
      if (fit.valid[v]) r.worst_iou = std::min(r.worst_iou, fit.iou[v]);
    }
    if (std::isfinite(fit.keypoint_rms_px))  // summed as squares here, the root taken at the end
      r.keypoint_rms_px += fit.keypoint_rms_px * fit.keypoint_rms_px, ++r.keypoint_frames;
    char status[96];
    std::snprintf(status, sizeof status, "frame %ld, %d LM iterations, worst IoU so far %.4f", frames[i],
                  fit.iterations, r.worst_iou);
    progress.update(i + 1, status);
  }
  progress.finish();
  if (r.keypoint_frames) r.keypoint_rms_px = std::sqrt(r.keypoint_rms_px / static_cast<double>(r.keypoint_frames));
  for (std::size_t v = 0; v < nview; ++v) {
    if (lost[v] > 0)
      log::warn("view '" + cameras[v].name + "': in " + std::to_string(lost[v]) +
                " frame(s) no dark blob was near the previous frame's fish; those frames are fitted without this view");
    if (at_border[v] > 0)
      log::warn("view '" + cameras[v].name + "': in " + std::to_string(at_border[v]) +
                " frame(s) the fish's blob touches the image border (no other candidate); check the framing or --fin-region");
  }
  std::vector<std::string> names;
  for (const auto& c : cameras) names.push_back(c.name);
  r.verdict = judge_fit(quality, names, options_.quality);
  if (r.verdict.flagged()) {
    kin.frame_flags = NdArray<std::uint8_t>({nf}, r.verdict.flags);
    const auto n = std::count_if(r.verdict.flags.begin(), r.verdict.flags.end(), [](std::uint8_t f) { return f != 0; });
    log::warn(in.source + ": " + std::to_string(n) + " of " + std::to_string(nf) +
              " frames flagged in kinematics.h5 quality/flags (1 few views, 2 low IoU, 4 root drift, 8 scale, 16 segmentation)");
  }
  if (!r.verdict.failure.empty()) kin.fit_status = r.verdict.failure;
  // Steady state: the first frame starts cold from the rest pose and takes many more steps.
  r.seconds_per_frame = nf > 1 ? (r.seconds - r.first_seconds) / (nf - 1) : r.seconds;
  if (scorer) {
    r.truth_iou = scorer->truth_iou;
    r.fit_truth_iou = scorer->fit_truth_iou;
    r.fit_truth_pixel_iou = scorer->fit_truth_pixel_iou;
  }
  return r;
}

}  // namespace finverse::vision
