// Validation and benchmark summaries of fin-track (see tracking_summary.hpp).
#include "vision/tracking_summary.hpp"

#include <algorithm>

#include "core/error.hpp"
#include "core/log.hpp"
#include "vision/tracking_score.hpp"

namespace finverse::vision {
namespace {

std::vector<std::size_t> trailing_edge(const FinSurface& f) {
  std::vector<std::size_t> te;
  for (std::size_t v = 0; v < f.size(); ++v)
    if (f.s[v] >= 1 - 1e-12) te.push_back(v);
  return te;
}

// The truth's rows of the tracked frames, [nf,nv,3].
NdArray<double> truth_rows(const stage::Truth& truth, const std::vector<long>& frames, std::size_t nv,
                           const std::string& name) {
  std::vector<std::size_t> rows;
  for (long k : frames) {
    if (static_cast<std::size_t>(k) >= truth.time.size())
      throw Error(name + ": /time: has " + std::to_string(truth.time.size()) + " frames, the frames go to " +
                  std::to_string(k));
    rows.push_back(static_cast<std::size_t>(k));
  }
  const auto& all = truth.points;
  if (all.rank() != 3 || all.dim(1) != nv)
    throw Error(name + ": /points: " + shape_string(all.shape) + ", expected [nf," + std::to_string(nv) +
                ",3] on the tracking template (same --surface-subdivisions as fin-synth)");
  NdArray<double> sel({rows.size(), nv, 3});
  for (std::size_t i = 0; i < rows.size(); ++i)
    std::copy_n(all.data.begin() + rows[i] * nv * 3, nv * 3, sel.data.begin() + i * nv * 3);
  return sel;
}

}  // namespace

Summary tracking_validation_summary(const TrackResult& r, const TrackingModel& m, const stage::Truth& truth,
                                    const std::string& truth_name, const std::vector<OtherReconstruction>& others) {
  const auto& kin = r.kinematics;
  const std::size_t nf = r.frames.size(), nview = kin.views.size();
  if (r.fit_truth_iou.size() != nview) throw Error("tracking summary: the record was tracked without its truth");
  const auto te = trailing_edge(m.surface);
  const auto truth_points = truth_rows(truth, r.frames, m.surface.size(), truth_name);
  const auto sc = score_tracking(kin.points, truth_points, m.chord, te);
  Summary sum("validation", "tracking",
              "fin-track on fin-synth frames (noise, blur) scored against truth.h5: vertex error, silhouette IoU, "
              "trailing-edge amplitude");
  const std::string src = "issue 5 accuracy criteria";
  sum.at_most("mean_vertex_error", sc.mean_error, 0.01, src + ": mean <= 1% of chord", "1");
  sum.at_most("p95_vertex_error", sc.p95_error, 0.02, src + ": 95th percentile <= 2% of chord", "1");
  sum.at_most("max_vertex_error", sc.max_error, 0.04, src + ": max <= 4% of chord", "1");
  for (std::size_t v = 0; v < nview; ++v) {
    const auto& name = kin.views[v];
    sum.at_most("iou_shortfall_" + name, 0.97 - r.fit_truth_iou[v], 0.0,
                src +
                    ": silhouette IoU >= 0.97 in every view and frame (0.97 - worst IoU of the fitted against the true "
                    "surface, "
                    "area-coverage silhouettes at the image resolution)",
                "1");
    sum.info("worst_fit_truth_iou_" + name, r.fit_truth_iou[v], "1");
    sum.info("worst_fit_truth_pixel_iou_" + name, r.fit_truth_pixel_iou[v], "1");
    double lo = 1;
    bool any = false;
    for (std::size_t i = 0; i < nf; ++i)
      if (kin.view_valid(i, v)) lo = std::min(lo, kin.silhouette_iou(i, v)), any = true;
    if (any) sum.info("worst_iou_" + name, lo, "1");                    // fit against the segmentation
    if (any) sum.info("worst_truth_iou_" + name, r.truth_iou[v], "1");  // truth against the segmentation
  }
  sum.at_most("te_amplitude_error", sc.te_amplitude_error, 0.02,
              src + ": trailing-edge peak-to-peak amplitude within 2% (worst TE vertex)", "1");
  sum.info("te_amplitude_truth", sc.te_amplitude_truth, "m");
  sum.info("te_amplitude_fit", sc.te_amplitude_fit, "m");
  for (const auto& o : others) {
    if (o.points.shape != kin.points.shape)
      throw Error(o.file + ": /points: " + shape_string(o.points.shape) + ", expected " +
                  shape_string(kin.points.shape));
    const auto s = score_tracking(o.points, truth_points, m.chord, te);
    sum.info(o.label + "_mean_vertex_error", s.mean_error, "1");
    sum.info(o.label + "_p95_vertex_error", s.p95_error, "1");
    sum.info(o.label + "_max_vertex_error", s.max_error, "1");
    sum.info(o.label + "_te_amplitude_error", s.te_amplitude_error, "1");
  }
  sum.info("frames", static_cast<double>(nf));
  sum.info("seconds_per_frame_set", r.seconds_per_frame, "s");
  sum.info("first_frame_seconds", r.first_seconds, "s");
  log::info("mean / p95 / max vertex error " + std::to_string(100 * sc.mean_error) + " / " +
            std::to_string(100 * sc.p95_error) + " / " + std::to_string(100 * sc.max_error) +
            " % of chord; TE amplitude error " + std::to_string(100 * sc.te_amplitude_error) + " %");
  return sum;
}

Summary tracking_bench_summary(const TrackResult& r, int image_width, std::optional<double> mesh_wall_time) {
  Summary b("bench", "track", "fin-track seconds per frame set (all views) and fin-mesh wall time, default resolution");
  b.at_most("seconds_per_frame_set", r.seconds_per_frame, 0.5,
            "issue 5: fin-track <= 0.5 s per frame set on 2 cores (load, segment, fit; warm-started frames)", "s");
  b.info("first_frame_seconds", r.first_seconds, "s");
  if (mesh_wall_time)
    b.at_most("fin_mesh_wall_time", *mesh_wall_time, 5.0, "issue 5: fin-mesh <= 5 s for the default fin", "s");
  b.info("frames", static_cast<double>(r.frames.size()));
  b.info("views", static_cast<double>(r.kinematics.views.size()));
  b.info("image_width", image_width, "px");
  return b;
}

}  // namespace finverse::vision
