// The tracker over a record (tools/vision/tracker.hpp): a short rendered record of the prescribed
// motion is tracked to a vertex-error bound and scored against its truth, the warm start carries
// a frame's fit into the next, the prediction extrapolates the last change over uneven frame
// gaps, a view without a frame is left out of that frame, a frame no view shows and an
// unreadable frame are errors, and kinematics.h5's ray axes and skeleton come out whole.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "vision/kinematic_model.hpp"
#include "vision/renderer.hpp"
#include "vision/tracker.hpp"
#include "vision/tracking_score.hpp"
#include "vision/tracking_summary.hpp"

using namespace finverse;
using namespace finverse::vision;

namespace {

// A small tracker (2 columns per ray gap, 3 segments per ray) and frames of the prescribed motion
// rendered on its own surface, so the fit and the truth share their vertices.
struct Record {
  mesh::FinTemplate fin = mesh::make_caudal_fin({});
  TrackerOptions options = [] {
    TrackerOptions o;
    o.surface_subdivisions = 2;
    o.segments = 3;
    o.fit.first_iterations = 40;
    o.fit.iterations = 8;
    return o;
  }();
  std::vector<Camera> cameras = default_rig({"side", "back", "ventral"}, 0.01, 384, 384);
  std::vector<long> frames;
  std::map<std::pair<std::size_t, long>, cv::Mat> images;  // (view, frame) -> frame
  NdArray<double> truth;                                   // [last frame + 1, nv, 3]

  // Frames k (of 500 fps) of the prescribed motion; `still`: every frame the pose of frame 0.
  explicit Record(std::vector<long> ks, bool still = false) : frames(std::move(ks)) {
    const auto surface = make_fin_surface(fin, options.surface_subdivisions);
    const PrescribedKinematics motion{KinematicParams{}};
    const Renderer renderer(surface, {});
    const std::size_t nv = surface.size();
    truth = NdArray<double>({static_cast<std::size_t>(frames.back()) + 1, nv, 3});
    for (long k : frames) {
      const auto X = motion.positions(surface, still ? 0.0 : k / options.fps);
      std::copy(X.data.begin(), X.data.end(), truth.data.begin() + k * nv * 3);
      for (std::size_t v = 0; v < cameras.size(); ++v)
        images[{v, k}] = renderer.render_frame(cameras[v], {X}, noise_key(11, v, k));
    }
  }
  TrackInput input() const {
    return {cameras, frames, [this](std::size_t v, long k) { return images.at({v, k}); }, "record"};
  }
  // Per-vertex error of frame i of the tracked record (/ chord): mean and max.
  std::pair<double, double> error(const TrackResult& r, std::size_t i) const {
    const std::size_t nv = truth.dim(1);
    double sum = 0, worst = 0;
    for (std::size_t v = 0; v < nv; ++v) {
      const double e = std::hypot(r.kinematics.points(i, v, 0) - truth(frames[i], v, 0),
                                  r.kinematics.points(i, v, 1) - truth(frames[i], v, 1),
                                  r.kinematics.points(i, v, 2) - truth(frames[i], v, 2)) /
                       fin.chord;
      sum += e, worst = std::max(worst, e);
    }
    return {sum / nv, worst};
  }
};

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Tracker, PredictionExtrapolatesTheLastChangeOverUnevenGaps) {
  const Pose before{{0.0, 1.0, -2.0}}, last{{0.5, 1.0, -1.0}};
  EXPECT_EQ(predict_pose(last, nullptr, 3.0, 1.0).p, last.p);     // one pose: no velocity yet
  EXPECT_EQ(predict_pose(last, &before, 1.0, 0.0).p, last.p);     // no momentum
  const auto constant = predict_pose(last, &before, 1.0, 1.0).p;  // constant velocity
  EXPECT_DOUBLE_EQ(constant[0], 1.0);
  EXPECT_DOUBLE_EQ(constant[1], 1.0);
  EXPECT_DOUBLE_EQ(constant[2], 0.0);
  const auto doubled_gap = predict_pose(last, &before, 2.0, 0.5).p;  // half the velocity over twice the gap
  EXPECT_DOUBLE_EQ(doubled_gap[0], 1.0);
  EXPECT_DOUBLE_EQ(doubled_gap[2], 0.0);
}

TEST(Tracker, TracksARenderedRecordWithinTheVertexErrorBoundAndScoresIt) {
  // Frame 3 missing in every view: the prediction spans the doubled gap.
  const Record rec({0, 1, 2, 4});
  const Tracker tracker(rec.fin, rec.options);
  TruthReference truth{&rec.truth, rec.cameras, "truth"};
  const auto r = tracker.track(rec.input(), &truth);
  ASSERT_EQ(r.kinematics.points.dim(0), 4u);
  for (std::size_t i = 0; i < rec.frames.size(); ++i) {
    const auto [mean, worst] = rec.error(r, i);
    EXPECT_LT(mean, 0.01) << "frame " << rec.frames[i];
    EXPECT_LT(worst, 0.03) << "frame " << rec.frames[i];
    EXPECT_DOUBLE_EQ(r.kinematics.time(i), rec.frames[i] / 500.0);
    for (std::size_t v = 0; v < rec.cameras.size(); ++v) {
      EXPECT_EQ(r.kinematics.view_valid(i, v), 1);
      EXPECT_GT(r.kinematics.silhouette_iou(i, v), 0.85) << rec.cameras[v].name;
    }
  }
  // The truth scores: the fitted against the true surface in every view, and the truth against
  // the segmentation (the most the fit can reach against it).
  ASSERT_EQ(r.fit_truth_iou.size(), 3u);
  for (std::size_t v = 0; v < 3; ++v) {
    EXPECT_GT(r.fit_truth_iou[v], 0.9) << rec.cameras[v].name;
    EXPECT_LE(r.fit_truth_iou[v], 1.0);
    EXPECT_GT(r.truth_iou[v], 0.85) << rec.cameras[v].name;
  }
  EXPECT_GT(r.seconds, 0.0);
  EXPECT_LE(r.first_seconds, r.seconds);
  // The validation summary grades the same vertex errors.
  stage::Truth t;
  t.points = rec.truth;
  t.time = NdArray<double>({rec.truth.dim(0)});
  const auto sum = tracking_validation_summary(r, tracker.model(), t, "truth");
  NdArray<double> rows({4, rec.truth.dim(1), 3});
  for (std::size_t i = 0; i < 4; ++i)
    std::copy_n(rec.truth.data.begin() + rec.frames[i] * rows.dim(1) * 3, rows.dim(1) * 3,
                rows.data.begin() + i * rows.dim(1) * 3);
  const auto sc = score_tracking(r.kinematics.points, rows, rec.fin.chord, {});
  const auto& m = sum.metrics();
  const auto mean = std::find_if(m.begin(), m.end(), [](const Metric& x) { return x.name == "mean_vertex_error"; });
  ASSERT_NE(mean, m.end());
  EXPECT_DOUBLE_EQ(mean->value, sc.mean_error);
  // A truth on another template is refused before any frame is fitted.
  const NdArray<double> other({5, 10, 3});
  TruthReference wrong{&other, rec.cameras, "other.h5"};
  EXPECT_NE(error_of([&] { tracker.track(rec.input(), &wrong); }).find("other.h5: /points"), std::string::npos);
}

TEST(Tracker, WarmStartCarriesAFrameIntoTheNext) {
  // The fin holds still: after the cold first frame every later frame starts at the previous
  // fit, so a single LM step keeps it there (from the rest pose one step would not get near).
  Record rec({0, 1, 2}, /*still=*/true);
  rec.options.fit.iterations = 1;
  const Tracker tracker(rec.fin, rec.options);
  const auto r = tracker.track(rec.input());
  const std::size_t nv = r.kinematics.points.dim(1);
  for (std::size_t i = 1; i < 3; ++i) {
    double moved = 0;
    for (std::size_t v = 0; v < nv; ++v)
      moved = std::max(moved, std::hypot(r.kinematics.points(i, v, 0) - r.kinematics.points(0, v, 0),
                                         r.kinematics.points(i, v, 1) - r.kinematics.points(0, v, 1),
                                         r.kinematics.points(i, v, 2) - r.kinematics.points(0, v, 2)));
    EXPECT_LT(moved / rec.fin.chord, 0.005) << "frame " << i;
    EXPECT_LT(rec.error(r, i).first, 0.01) << "frame " << i;
  }
}

TEST(Tracker, AViewWithoutTheFrameIsLeftOutOfThatFrame) {
  Record rec({0, 1});
  rec.images[{1, 1}] = cv::Mat();  // the back view lacks frame 1
  const Tracker tracker(rec.fin, rec.options);
  const auto r = tracker.track(rec.input());
  EXPECT_EQ(r.kinematics.view_valid(0, 1), 1);
  EXPECT_EQ(r.kinematics.view_valid(1, 1), 0);
  EXPECT_TRUE(std::isnan(r.kinematics.silhouette_iou(1, 1)));
  EXPECT_EQ(r.kinematics.view_valid(1, 0), 1);
  EXPECT_EQ(r.kinematics.view_valid(1, 2), 1);
  EXPECT_LT(rec.error(r, 1).first, 0.015);  // side and ventral still place the fin
}

TEST(Tracker, AFrameNoViewShowsAndAnUnreadableFrameAreErrors) {
  Record rec({0});
  const Tracker tracker(rec.fin, rec.options);
  auto blank = rec.input();
  blank.load = [](std::size_t, long) { return cv::Mat(384, 384, CV_8U, cv::Scalar(200)); };
  EXPECT_NE(error_of([&] { tracker.track(blank); }).find("record: frame 0: the fin is not visible in any view"),
            std::string::npos);
  auto broken = rec.input();
  broken.load = [&](std::size_t v, long k) -> cv::Mat {
    if (v == 2) throw Error("000000.png: unreadable image");
    return rec.images.at({v, k});
  };
  EXPECT_EQ(error_of([&] { tracker.track(broken); }), "000000.png: unreadable image");
}

TEST(Tracker, RecordHoldsTheRayAxesSkeletonAndAttributes) {
  const auto fin = mesh::make_caudal_fin({});
  TrackerOptions o;
  o.period = 0.2;
  o.fps = 250;
  const auto m = make_tracking_model(fin, o.surface_subdivisions, o.segments);
  // Every ray has its axis, root (s = 0) to tip (s = 1), on the ray line (ray_distance 0).
  ASSERT_EQ(m.ray_offsets.dim(0), fin.ray_count() + 1);
  for (std::size_t r = 0; r < fin.ray_count(); ++r) {
    const auto lo = static_cast<std::size_t>(m.ray_offsets(r)), hi = static_cast<std::size_t>(m.ray_offsets(r + 1));
    ASSERT_GE(hi - lo, 2u) << "ray " << r;
    EXPECT_DOUBLE_EQ(m.surface.s[m.ray_vertices(lo)], 0.0) << "ray " << r;
    EXPECT_DOUBLE_EQ(m.surface.s[m.ray_vertices(hi - 1)], 1.0) << "ray " << r;
    for (std::size_t k = lo; k < hi; ++k) {
      EXPECT_EQ(m.surface.ray_distance[m.ray_vertices(k)], 0.0);
      if (k > lo) {
        EXPECT_LT(m.surface.s[m.ray_vertices(k - 1)], m.surface.s[m.ray_vertices(k)]);
      }
    }
  }
  EXPECT_EQ(m.ray_vertices.dim(0), static_cast<std::size_t>(m.ray_offsets(fin.ray_count())));
  // The record of one frame keeps the skeleton and the attributes given.
  Record rec({0});
  rec.options.period = 0.2;
  rec.options.fps = 250;
  const Tracker tracker(rec.fin, rec.options);
  const auto r = tracker.track(rec.input());
  const auto& sk = tracker.model().skeleton;
  ASSERT_EQ(r.kinematics.joint_parent.dim(0), sk.joint_count());
  for (std::size_t j = 0; j < sk.joint_count(); ++j) EXPECT_EQ(r.kinematics.joint_parent(j), sk.parent[j]);
  EXPECT_EQ(r.kinematics.period, 0.2);
  EXPECT_EQ(r.kinematics.fps, 250.0);
  EXPECT_EQ(r.kinematics.time(0), 0.0);
  EXPECT_EQ(r.kinematics.views, (std::vector<std::string>{"side", "back", "ventral"}));
}
