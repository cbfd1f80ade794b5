// Linear blend skinning of the fin template on the ray chains (seed paper section 2.1, step 1).
#include "vision/skinning.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"

namespace finverse::vision {
namespace {

struct Foot {
  double distance, s;  // signed in-plane distance to the ray line (+: dorsal, +z side), arc fraction of the foot
};

// Foot of (x, z) on ray polyline `pts`, its first and last segments extended beyond the root and
// the tip: a point of the membrane past a ray's tip (the forked trailing edge runs beyond the
// tips of the shorter middle rays) is measured across the ray's line, not to its tip point.
Foot nearest_on_ray(const std::vector<mesh::Point2>& pts, const std::vector<double>& frac, double x, double z) {
  Foot best{std::numeric_limits<double>::max(), 0};
  double best_abs = std::numeric_limits<double>::max();
  const std::size_t n = pts.size();
  for (std::size_t i = 0; i + 1 < n; ++i) {
    const double ax = pts[i][0], az = pts[i][1], ux = pts[i + 1][0] - ax, uz = pts[i + 1][1] - az;
    const double L2 = ux * ux + uz * uz;
    if (!(L2 > 0)) continue;
    const double lo = i == 0 ? -std::numeric_limits<double>::infinity() : 0.0;
    const double hi = i + 2 == n ? std::numeric_limits<double>::infinity() : 1.0;
    const double u = std::clamp(((x - ax) * ux + (z - az) * uz) / L2, lo, hi);
    const double d = std::hypot(x - ax - u * ux, z - az - u * uz);
    if (d < best_abs) {
      best_abs = d;
      const double side = ux * (z - az) - uz * (x - ax);  // > 0: left of root->tip (+x), i.e. dorsal
      const double uc = std::clamp(u, 0.0, 1.0);
      best = {side >= 0 ? d : -d, frac[i] + uc * (frac[i + 1] - frac[i])};
    }
  }
  return best;
}

}  // namespace

SkinBinding bind_skin(const mesh::FinTemplate& t, const Skeleton& s, const NdArray<double>& rest) {
  if (rest.rank() != 2 || rest.dim(1) != 3) throw Error("skinning: rest positions must be [nv,3]");
  if (t.ray_count() != s.rays) throw Error("skinning: skeleton and template differ in ray count");
  const std::size_t nv = rest.dim(0), nr = s.rays, S = s.segments;
  std::vector<std::vector<double>> frac(nr);
  for (std::size_t r = 0; r < nr; ++r) frac[r] = t.arc_fractions(r);
  SkinBinding b;
  b.rest = rest;
  b.joint.resize(nv);
  b.weight.resize(nv);
  b.depends.resize(nv);
  std::vector<Foot> feet(nr);
  for (std::size_t v = 0; v < nv; ++v) {
    const double x = rest(v, 0), z = rest(v, 2);
    for (std::size_t r = 0; r < nr; ++r) feet[r] = nearest_on_ray(t.rays[r].points, frac[r], x, z);
    // The two rays that bracket the point: ray r dorsal of it and ray r + 1 ventral of it (rays
    // run dorsal to ventral). Choosing the nearest ray and its nearer neighbour instead fails near
    // the forked trailing edge, where a point beyond a short ray's tip is nearer to the ray after
    // next than to its own neighbour, and binds the membrane to the wrong pair of rays.
    std::size_t r1 = 0, r2 = 1;
    double w1 = 1.0;
    if (feet[0].distance >= 0) {  // dorsal of the first ray (on its edge): follows it alone
      r1 = 0, r2 = 1, w1 = 1.0;
    } else if (feet[nr - 1].distance <= 0) {  // ventral of the last ray
      r1 = nr - 1, r2 = nr - 2, w1 = 1.0;
    } else {
      double best = std::numeric_limits<double>::max();
      for (std::size_t r = 0; r + 1 < nr; ++r) {
        const double a = -feet[r].distance, c = feet[r + 1].distance;  // both >= 0 when bracketing
        if (a < 0 || c < 0 || a + c >= best) continue;
        best = a + c;
        r1 = r, r2 = r + 1;
        w1 = a + c > 0 ? c / (a + c) : 1.0;
      }
      if (best == std::numeric_limits<double>::max()) {  // crossing ray lines: nearest ray alone
        for (std::size_t r = 0; r < nr; ++r)
          if (std::abs(feet[r].distance) < std::abs(feet[r1].distance)) r1 = r;
        r2 = r1 + 1 < nr ? r1 + 1 : r1 - 1;
        w1 = 1.0;
      }
    }
    const std::size_t rr[2] = {r1, r2};
    const double wr[2] = {w1, 1 - w1};
    for (int k = 0; k < 2; ++k) {
      // Segment k covers s in [k/S, (k+1)/S]; blend linearly between neighbouring segment centres.
      const double u = std::clamp(feet[rr[k]].s * S - 0.5, 0.0, S - 1.0);
      const auto lo = static_cast<std::size_t>(std::min(std::floor(u), S - 1.0));
      const std::size_t hi = std::min(lo + 1, S - 1);
      const double a = u - lo;
      b.joint[v][2 * k] = static_cast<int>(s.joint(rr[k], lo));
      b.weight[v][2 * k] = wr[k] * (1 - a);
      b.joint[v][2 * k + 1] = static_cast<int>(s.joint(rr[k], hi));
      b.weight[v][2 * k + 1] = wr[k] * a;
    }
    auto& dep = b.depends[v];
    for (int k = 0; k < SkinBinding::kInfluences; ++k)
      for (int j = b.joint[v][k]; j >= 0; j = s.parent[static_cast<std::size_t>(j)])
        if (std::find(dep.begin(), dep.end(), j) == dep.end()) dep.push_back(j);
    std::sort(dep.begin(), dep.end());
  }
  return b;
}

namespace {
cv::Vec3d skin_vertex(const SkinBinding& b, const JointFrames& f, std::size_t v) {
  const cv::Vec3d x(b.rest(v, 0), b.rest(v, 1), b.rest(v, 2));
  cv::Vec3d X(0, 0, 0);
  for (int k = 0; k < SkinBinding::kInfluences; ++k) {
    const double w = b.weight[v][k];
    if (w == 0) continue;
    const auto j = static_cast<std::size_t>(b.joint[v][k]);
    X += w * (f.R[j] * x + f.t[j]);
  }
  return X;
}
}  // namespace

NdArray<double> skin(const SkinBinding& b, const JointFrames& f) {
  NdArray<double> out({b.size(), 3});
  for (std::size_t v = 0; v < b.size(); ++v) {
    const auto X = skin_vertex(b, f, v);
    for (int d = 0; d < 3; ++d) out(v, d) = X[d];
  }
  return out;
}

SkinJacobian skin_jacobian(const SkinBinding& b, const Skeleton& s, const Pose& pose, double h) {
  const std::size_t nv = b.size(), nj = s.joint_count();
  SkinJacobian J;
  J.cols.resize(nv);
  J.vals.resize(nv);
  // Which vertices each joint moves, and where its columns go in their lists.
  std::vector<std::vector<std::size_t>> moved(nj);
  for (std::size_t v = 0; v < nv; ++v) {
    J.cols[v] = {0, 1, 2};
    J.vals[v] = {{s.chord, 0, 0}, {0, s.chord, 0}, {0, 0, s.chord}};
    for (int j : b.depends[v]) {
      moved[static_cast<std::size_t>(j)].push_back(v);
      for (int c = 0; c < 3; ++c) J.cols[v].push_back(3 + 3 * j + c);
    }
  }
  // Perturbing joint j changes the frames of j and its descendants only (joints are stored
  // parents first): recompute those with forward_kinematics' own step from the unperturbed frames,
  // instead of the whole skeleton twice per parameter. The values are the same.
  const JointFrames base = forward_kinematics(s, pose);
  const cv::Vec3d translation(pose.p[0] * s.chord, pose.p[1] * s.chord, pose.p[2] * s.chord);
  JointFrames fp = base, fm = base;
  std::vector<char> changed(nj, 0);
  auto perturbed = [&](std::size_t j, const cv::Vec3d& rv, JointFrames& f) {
    for (std::size_t k = j; k < nj; ++k) {
      changed[k] = k == j || (s.parent[k] >= 0 && changed[static_cast<std::size_t>(s.parent[k])]);
      if (changed[k])
        compose_joint_frame(s, k, k == j ? rv : cv::Vec3d(pose.p[3 + 3 * k], pose.p[4 + 3 * k], pose.p[5 + 3 * k]),
                            translation, f);
    }
  };
  auto restore = [&](std::size_t j) {
    for (std::size_t k = j; k < nj; ++k)
      if (changed[k]) fp.R[k] = fm.R[k] = base.R[k], fp.t[k] = fm.t[k] = base.t[k], changed[k] = 0;
  };
  for (std::size_t j = 0; j < nj; ++j) {
    if (moved[j].empty()) continue;
    for (int c = 0; c < 3; ++c) {
      const std::size_t i = 3 + 3 * j + c;
      cv::Vec3d rv(pose.p[3 + 3 * j], pose.p[4 + 3 * j], pose.p[5 + 3 * j]);
      rv[c] = pose.p[i] + h;
      perturbed(j, rv, fp);
      rv[c] = pose.p[i] - h;
      perturbed(j, rv, fm);
      for (std::size_t v : moved[j]) J.vals[v].push_back((skin_vertex(b, fp, v) - skin_vertex(b, fm, v)) / (2 * h));
      restore(j);
    }
  }
  return J;
}

}  // namespace finverse::vision
