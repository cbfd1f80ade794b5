// Levenberg-Marquardt fit of the skeleton pose to multi-view silhouettes (seed paper section
// 2.1, step 1).
#include "vision/skeleton_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "core/error.hpp"
#include "core/log.hpp"
#include "vision/view_roles.hpp"

namespace finverse::vision {

struct SkeletonFitter::Linearisation {
  NormalEquations ne;
  std::vector<SilhouetteStats> stats;
};

SkeletonFitter::SkeletonFitter(const Skeleton& s, const SkinBinding& b, const NdArray<std::int32_t>& tri, std::vector<int> ray_vertices,
                               const FitOptions& o)
    : s_(s), b_(b), tri_(tri), ray_vertices_(std::move(ray_vertices)), edges_(mesh_edges(tri)), o_(o) {
  if (b.size() == 0) throw Error("skeleton fit: empty template");
}

SkeletonFitter::Linearisation SkeletonFitter::linearise(const std::vector<ViewData>& views, const Pose& pose, const Pose* prediction,
                                                        double neighbour_sigma, bool use_rays,
                                                        const FrameKeypoints* keypoints) const {
  const std::size_t P = s_.parameter_count();
  const auto frames = forward_kinematics(s_, pose);
  const auto X = skin(b_, frames);
  const auto J = skin_jacobian(b_, s_, pose);
  std::vector<std::unique_ptr<NormalEquations>> per_view(views.size());
  std::vector<SilhouetteStats> stats(views.size());
#pragma omp parallel for schedule(dynamic)
  for (std::ptrdiff_t v = 0; v < static_cast<std::ptrdiff_t>(views.size()); ++v) {
    per_view[v] = std::make_unique<NormalEquations>(P);
    if (!views[v].valid) continue;
    const auto m = project_model(views[v].camera, X, tri_);
    // The coverage term only near the answer (with the rays): from far off its band sees no
    // model outline and the chamfer terms do the pulling. Where it is on, the chamfer (which
    // knows the outline only to the pixel) steps back to coverage_chamfer_weight.
    const bool coverage_on = use_rays && o_.coverage.weight > 0 && fits_coverage(o_.coverage_views, views[v].camera);
    SilhouetteOptions so = o_.silhouette;
    if (coverage_on) so.weight *= o_.coverage_chamfer_weight;
    stats[v] = add_silhouette_residuals(views[v], m, tri_, &J, so, *per_view[v]);
    if (use_rays && fits_rays(o_.ray_views, views[v].camera) && o_.rays.weight > 0) add_ray_residuals(views[v], m, ray_vertices_, &J, o_.rays, *per_view[v]);
    if (coverage_on) add_coverage_residuals(views[v], m, tri_, edges_, &J, o_.coverage, *per_view[v]);
  }
  Linearisation L{NormalEquations(P), std::move(stats)};
  for (const auto& ne : per_view) L.ne += *ne;
  if (keypoints) add_keypoint_residuals(views, *keypoints, ends_, X, &J, o_.keypoints, s_.chord, L.ne);
  // Priors, one row per parameter (or pair): r = (p - centre) / sigma.
  auto prior = [&](int i, double centre, double sigma) {
    L.ne.add(i, 1.0);
    L.ne.commit(pose.p[i] - centre, 1.0 / (sigma * sigma));
  };
  if (prediction)
    for (std::size_t i = 0; i < P; ++i) prior(static_cast<int>(i), prediction->p[i], o_.temporal_sigma);
  for (std::size_t j = 1; j < s_.joint_count(); ++j) {
    const int i = static_cast<int>(3 + 3 * j);
    prior(i, 0.0, o_.out_of_plane_sigma);
    prior(i + 1, 0.0, o_.out_of_plane_sigma);
    prior(i + 2, 0.0, o_.joint_sigma);
  }
  for (std::size_t r = 0; r + 1 < s_.rays; ++r)
    for (std::size_t k = 0; k < s_.segments; ++k)
      for (int c = 0; c < 3; ++c) {
        const int a = static_cast<int>(3 + 3 * s_.joint(r, k)) + c, b = static_cast<int>(3 + 3 * s_.joint(r + 1, k)) + c;
        L.ne.add(a, 1.0);
        L.ne.add(b, -1.0);
        L.ne.commit(pose.p[a] - pose.p[b], 1.0 / (neighbour_sigma * neighbour_sigma));
      }
  // Across the span the joint angles vary smoothly (U-shaped amplitudes, W-shaped phases): a
  // prior on their second difference over three neighbouring rays leaves linear trends free.
  if (o_.span_curvature_sigma > 0)
    for (std::size_t r = 1; r + 1 < s_.rays; ++r)
      for (std::size_t k = 0; k < s_.segments; ++k)
        for (int c = 0; c < 3; ++c) {
          const int a = static_cast<int>(3 + 3 * s_.joint(r - 1, k)) + c, b = static_cast<int>(3 + 3 * s_.joint(r, k)) + c,
                    d = static_cast<int>(3 + 3 * s_.joint(r + 1, k)) + c;
          L.ne.add(a, 1.0);
          L.ne.add(b, -2.0);
          L.ne.add(d, 1.0);
          L.ne.commit(pose.p[a] - 2 * pose.p[b] + pose.p[d], 1.0 / (o_.span_curvature_sigma * o_.span_curvature_sigma));
        }
  return L;
}

FrameFit SkeletonFitter::fit(const std::vector<ViewData>& views, const Pose& start, const Pose* prediction, int max_iterations,
                             const FrameKeypoints* keypoints) const {
  const std::size_t P = s_.parameter_count();
  if (start.p.size() != P) throw Error("skeleton fit: start pose has the wrong size");
  if (keypoints && keypoints->empty()) keypoints = nullptr;
  if (keypoints && ends_.root.size() != s_.rays) throw Error("skeleton fit: keypoints given but the ray ends are not set");
  FrameFit out;
  Pose pose = start;
  // From the rest pose the first frame is far off: first let all rays move nearly together
  // (stiff neighbour prior), then release them.
  const bool cold = prediction == nullptr;
  const int stages = cold ? 2 : 1;
  for (int stage = 0; stage < stages; ++stage) {
    // The ray features are many parallel lines: only near the answer do they pull each model ray
    // to its own image ray, so the cold first stage aligns silhouettes alone.
    const double nsig = cold && stage == 0 ? 0.1 * o_.neighbour_sigma : o_.neighbour_sigma;
    const bool rays = !(cold && stage == 0);
    auto L = linearise(views, pose, prediction, nsig, rays, keypoints);
    double lambda = 1e-2;
    int rejected = 0;
    for (int it = 0; it < max_iterations; ++it) {
      ++out.iterations;
      Eigen::MatrixXd A = L.ne.A();
      for (std::size_t i = 0; i < P; ++i) A(i, i) += lambda * A(i, i) + 1e-9;
      // A = J^T W J plus the damping is symmetric positive definite: Cholesky (blocked, several
      // times faster than LDLT at ~400 parameters; a sparse Cholesky, with its ordering redone
      // every step, measured no faster), LDLT only should it fail numerically.
      const Eigen::LLT<Eigen::MatrixXd> llt(A);
      Eigen::VectorXd delta = llt.info() == Eigen::Success ? Eigen::VectorXd(llt.solve(-L.ne.g())) : Eigen::VectorXd(A.ldlt().solve(-L.ne.g()));
      // Trust region in the infinity norm: the correspondences and the linearised projection
      // hold only for small changes (a tenth of a radian, a tenth of a chord).
      const double largest = delta.cwiseAbs().maxCoeff();
      if (largest > o_.max_step) delta *= o_.max_step / largest;
      const double largest_taken = std::min(largest, o_.max_step);
      Pose cand = pose;
      for (std::size_t i = 0; i < P; ++i) cand.p[i] += delta[i];
      auto Lc = linearise(views, cand, prediction, nsig, rays, keypoints);
      char line[128];
      std::snprintf(line, sizeof line, "LM stage %d step %d: lambda %.2e, cost %.6g -> %.6g, |step| %.3g", stage, it, lambda,
                    L.ne.cost(), Lc.ne.cost(), delta.norm());
      log::debug(line);
      if (Lc.ne.cost() < L.ne.cost()) {
        const double drop = (L.ne.cost() - Lc.ne.cost()) / std::max(L.ne.cost(), 1e-300);
        pose = std::move(cand);
        L = std::move(Lc);
        lambda = std::max(lambda / 3, 1e-4);
        rejected = 0;
        if (drop < o_.tolerance || largest_taken < o_.step_tolerance) break;
      } else {
        lambda *= 4;
        // Near the minimum the piecewise-linear correspondences reject step after step: each
        // further try costs a full linearisation for a change far below the tolerance.
        if (lambda > 1e8 || (o_.max_rejections > 0 && ++rejected >= o_.max_rejections)) break;
      }
    }
    out.cost = L.ne.cost();
  }
  out.pose = pose;
  out.points = skin(b_, forward_kinematics(s_, pose));
  const auto nvw = views.size();
  out.iou.assign(nvw, std::numeric_limits<double>::quiet_NaN());
  out.rms_px.assign(nvw, std::numeric_limits<double>::quiet_NaN());
  out.area_ratio.assign(nvw, std::numeric_limits<double>::quiet_NaN());
  out.valid.assign(nvw, 0);
  if (keypoints && !keypoints->image.empty()) {
    NormalEquations scratch(0);
    out.keypoint_rms_px = add_keypoint_residuals(views, *keypoints, ends_, out.points, nullptr, o_.keypoints, s_.chord, scratch);
  }
#pragma omp parallel for schedule(dynamic)
  for (std::ptrdiff_t v = 0; v < static_cast<std::ptrdiff_t>(nvw); ++v) {
    if (!views[v].valid) continue;
    const auto m = project_model(views[v].camera, out.points, tri_);
    NormalEquations scratch(0);
    // Outside the opaque body only, where the image tells fin from not-fin.
    const auto& body = views[v].body;
    out.iou[v] = mask_iou(m.mask, views[v].mask, body);
    const auto area = [&](const cv::Mat& a) { return body.empty() ? cv::countNonZero(a) : cv::countNonZero(a & (body == 0)); };
    out.area_ratio[v] = static_cast<double>(area(m.mask)) / std::max(1, area(views[v].mask));
    out.rms_px[v] = add_silhouette_residuals(views[v], m, tri_, nullptr, o_.silhouette, scratch).rms_px;
    out.valid[v] = 1;
  }
  return out;
}

}  // namespace finverse::vision
