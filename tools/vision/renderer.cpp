// k-buffer rasteriser for the translucent fin (DESIGN.md section 5.5; seed paper section 4.1).
#include "vision/renderer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>

#include <opencv2/imgproc.hpp>

#include "core/error.hpp"

namespace finverse::vision {
namespace {

constexpr int kFragments = 4;      // nearest fragments kept per sample
constexpr std::int64_t kSub = 256; // fixed-point subpixel steps

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// Smooth value noise in [0, 1] on a unit lattice, from a hash: the fin's pigment pattern, tied to
// material points so the texture moves with the fin (what a tracker can lock on to).
double lattice(std::int64_t i, std::int64_t j) {
  return static_cast<double>(splitmix64(static_cast<std::uint64_t>(i) * 0x100000001b3ULL ^ static_cast<std::uint64_t>(j)) >> 11) *
         0x1.0p-53;
}
double value_noise(double x, double y) {
  const double fx = std::floor(x), fy = std::floor(y);
  const auto i = static_cast<std::int64_t>(fx), j = static_cast<std::int64_t>(fy);
  double u = x - fx, v = y - fy;
  u = u * u * (3 - 2 * u);
  v = v * v * (3 - 2 * v);
  return (1 - v) * ((1 - u) * lattice(i, j) + u * lattice(i + 1, j)) + v * ((1 - u) * lattice(i, j + 1) + u * lattice(i + 1, j + 1));
}

struct Fragment {
  float depth, level, alpha;
};

}  // namespace

std::uint64_t noise_key(std::uint64_t seed, std::uint64_t view, std::uint64_t frame) {
  return splitmix64(splitmix64(splitmix64(seed) ^ view) ^ frame);
}

Renderer::Renderer(const FinSurface& surface, const RenderOptions& options, const FishBody* body)
    : surface_(surface), o_(options), body_(body) {
  if (o_.supersample < 1 || o_.supersample > 8) throw Error("--supersample: expected 1..8");
  if (!(o_.noise_sigma >= 0)) throw Error("--noise-sigma: expected >= 0");
  if (!(o_.background > 0 && o_.background <= 1)) throw Error("--background-level: expected a grey level in (0, 1]");
  if (!(o_.vignetting >= 0 && o_.vignetting < 1)) throw Error("--vignetting: expected a fraction in [0, 1)");
  if (!(o_.vignetting_power > 0)) throw Error("--vignetting-power: expected > 0");
  if (!(o_.background_gradient >= 0 && o_.background_gradient < 1)) throw Error("--background-gradient: expected a fraction in [0, 1)");
  if (!(o_.gain > 0)) throw Error("--gain: expected > 0");
}

cv::Mat Renderer::render_clean(const Camera& cam, const NdArray<double>& pos, double time) const {
  const int S = o_.supersample;
  const int W = cam.width * S, H = cam.height * S;
  const std::size_t nv = surface_.size();
  if (pos.rank() != 2 || pos.dim(0) != nv || pos.dim(1) != 3) throw Error("renderer: positions do not match the surface");

  // Vertex normals (area-weighted), projection and per-vertex lighting: a light at the camera,
  // diffuse and two-sided, since the backlit fin is seen from both sides.
  std::vector<cv::Vec3d> normal(nv, cv::Vec3d(0, 0, 0));
  const auto& tri = surface_.triangles;
  const std::size_t nt = tri.dim(0);
  auto P = [&](std::int32_t i) { return cv::Vec3d(pos(i, 0), pos(i, 1), pos(i, 2)); };
  for (std::size_t t = 0; t < nt; ++t) {
    const cv::Vec3d n = (P(tri(t, 1)) - P(tri(t, 0))).cross(P(tri(t, 2)) - P(tri(t, 0)));
    for (int k = 0; k < 3; ++k) normal[tri(t, k)] += n;
  }
  const cv::Vec3d eye = cam.center();
  std::vector<std::array<std::int64_t, 2>> xy(nv);
  std::vector<double> depth(nv), shade(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    const auto p = cam.project(P(static_cast<std::int32_t>(i)), &depth[i]);
    xy[i] = {std::llround(((p.x + 0.5) * S - 0.5) * kSub), std::llround(((p.y + 0.5) * S - 0.5) * kSub)};
    const double nn = cv::norm(normal[i]);
    const cv::Vec3d l = cv::normalize(eye - P(static_cast<std::int32_t>(i)));
    shade[i] = 0.45 + 0.55 * (nn > 0 ? std::abs(normal[i].dot(l)) / nn : 1.0);
  }

  // Reused per thread: only the counts need clearing, and a fresh 50 MB buffer per image would
  // cost more in page faults than the rasterisation itself.
  thread_local std::vector<Fragment> frags;
  thread_local std::vector<std::uint8_t> count;
  frags.resize(static_cast<std::size_t>(W) * H * kFragments);
  count.assign(static_cast<std::size_t>(W) * H, 0);
  const double tex_scale = 1.0 / (0.03 * surface_.chord);  // pigment spots about 0.03 c apart

  for (std::size_t t = 0; t < nt; ++t) {
    std::array<std::int32_t, 3> v{tri(t, 0), tri(t, 1), tri(t, 2)};
    if (depth[v[0]] <= 0 || depth[v[1]] <= 0 || depth[v[2]] <= 0) continue;  // behind the camera
    auto edge = [&](int a, int b, std::int64_t px, std::int64_t py) {
      return (xy[v[b]][0] - xy[v[a]][0]) * (py - xy[v[a]][1]) - (xy[v[b]][1] - xy[v[a]][1]) * (px - xy[v[a]][0]);
    };
    std::int64_t area = edge(0, 1, xy[v[2]][0], xy[v[2]][1]);
    if (area == 0) continue;
    if (area < 0) {  // two-sided: make every triangle positively oriented in the image
      std::swap(v[1], v[2]);
      area = -area;
    }
    const std::int64_t x0 = std::max<std::int64_t>(0, (std::min({xy[v[0]][0], xy[v[1]][0], xy[v[2]][0]}) + kSub - 1) / kSub);
    const std::int64_t x1 = std::min<std::int64_t>(W - 1, std::max({xy[v[0]][0], xy[v[1]][0], xy[v[2]][0]}) / kSub);
    const std::int64_t y0 = std::max<std::int64_t>(0, (std::min({xy[v[0]][1], xy[v[1]][1], xy[v[2]][1]}) + kSub - 1) / kSub);
    const std::int64_t y1 = std::min<std::int64_t>(H - 1, std::max({xy[v[0]][1], xy[v[1]][1], xy[v[2]][1]}) / kSub);
    if (x0 > x1 || y0 > y1) continue;
    // Tie rule for samples exactly on an edge: a shared edge runs a->b in one triangle and b->a
    // in the other (both positively oriented), and exactly one of the two directions owns it.
    auto owns = [&](int a, int b) {
      const std::int64_t dx = xy[v[b]][0] - xy[v[a]][0], dy = xy[v[b]][1] - xy[v[a]][1];
      return dy < 0 || (dy == 0 && dx > 0);
    };
    const bool own[3] = {owns(1, 2), owns(2, 0), owns(0, 1)};
    const double inv_area = 1.0 / static_cast<double>(area);
    const double iz[3] = {1 / depth[v[0]], 1 / depth[v[1]], 1 / depth[v[2]]};
    for (std::int64_t py = y0; py <= y1; ++py) {
      for (std::int64_t px = x0; px <= x1; ++px) {
        const std::int64_t sx = px * kSub, sy = py * kSub;
        const std::int64_t e[3] = {edge(1, 2, sx, sy), edge(2, 0, sx, sy), edge(0, 1, sx, sy)};
        bool inside = true;
        for (int k = 0; k < 3 && inside; ++k) inside = e[k] > 0 || (e[k] == 0 && own[k]);
        if (!inside) continue;
        // Perspective-correct interpolation.
        double q[3], qs = 0;
        for (int k = 0; k < 3; ++k) {
          q[k] = static_cast<double>(e[k]) * inv_area * iz[k];
          qs += q[k];
        }
        for (auto& qk : q) qk /= qs;
        auto lerp = [&](const auto& attr) { return q[0] * attr(v[0]) + q[1] * attr(v[1]) + q[2] * attr(v[2]); };
        const double z = 1 / qs;
        const double d = lerp([&](int i) { return surface_.ray_distance[i]; });
        const double hw = lerp([&](int i) { return surface_.ray_half_width[i]; });
        const double rx = lerp([&](int i) { return surface_.rest(i, 0); }) * tex_scale;
        const double rz = lerp([&](int i) { return surface_.rest(i, 2); }) * tex_scale;
        const double sh = lerp([&](int i) { return shade[i]; });
        const double ray = std::clamp((1.25 * hw - d) / (0.5 * hw), 0.0, 1.0);  // soft ray edge
        const double spots = std::clamp((value_noise(rx, rz) - 0.55) / 0.3, 0.0, 1.0);
        const double grain = 0.9 + 0.2 * value_noise(4 * rx + 17.3, 4 * rz - 5.1);
        const double membrane = o_.membrane_level * grain * (1 - 0.6 * spots);
        const Fragment f{static_cast<float>(z),
                         static_cast<float>(sh * ((1 - ray) * membrane + ray * o_.ray_level)),
                         static_cast<float>((1 - ray) * o_.membrane_alpha + ray * o_.ray_alpha)};
        // Insert into the depth-sorted k-buffer (nearest first); the farthest falls off when full.
        const std::size_t pix = static_cast<std::size_t>(py) * W + static_cast<std::size_t>(px);
        Fragment* fb = &frags[pix * kFragments];
        int n = count[pix];
        int at = n;
        while (at > 0 && fb[at - 1].depth > f.depth) --at;
        if (at >= kFragments) continue;
        for (int k = std::min(n, kFragments - 1); k > at; --k) fb[k] = fb[k - 1];
        fb[at] = f;
        count[pix] = static_cast<std::uint8_t>(std::min(n + 1, kFragments));
      }
    }
  }

  cv::Mat img(H, W, CV_32F);
  const double cx = 0.5 * (W - 1), cy = 0.5 * (H - 1), r2max = cx * cx + cy * cy;
  // The opaque body hides the background and every fin fragment behind it.
  const OpaqueLayer body = body_ ? body_->rasterize(cam, pos, S, time) : OpaqueLayer{};
  for (int y = 0; y < H; ++y) {
    float* row = img.ptr<float>(y);
    const float* body_depth = body_ ? body.depth.ptr<float>(y) : nullptr;
    const float* body_level = body_ ? body.level.ptr<float>(y) : nullptr;
    for (int x = 0; x < W; ++x) {
      const double r2 = ((x - cx) * (x - cx) + (y - cy) * (y - cy)) / r2max;
      const double falloff = o_.vignetting_power == 2 ? r2 : std::pow(r2, 0.5 * o_.vignetting_power);
      double c = o_.background * (1 - o_.vignetting * falloff);
      if (o_.background_gradient > 0) c *= 1 - o_.background_gradient * (1 - x / (W - 1.0));
      const std::size_t pix = static_cast<std::size_t>(y) * W + x;
      int front = count[pix];
      if (body_depth && std::isfinite(body_depth[x])) {
        c = body_level[x];
        while (front > 0 && frags[pix * kFragments + front - 1].depth > body_depth[x]) --front;
      }
      for (int k = front - 1; k >= 0; --k) {  // back to front
        const Fragment& f = frags[pix * kFragments + k];
        c = c * (1 - f.alpha) + f.level * f.alpha;
      }
      row[x] = static_cast<float>(c);
    }
  }
  if (S == 1) return img;
  cv::Mat out;
  cv::resize(img, out, cv::Size(cam.width, cam.height), 0, 0, cv::INTER_AREA);
  return out;
}

cv::Mat Renderer::render_frame(const Camera& cam, const std::vector<NdArray<double>>& subframes, std::uint64_t key) const {
  return sensor(render_exposure(cam, subframes), key);
}

cv::Mat Renderer::render_exposure(const Camera& cam, const std::vector<NdArray<double>>& subframes,
                                  const std::vector<double>& times) const {
  if (subframes.empty()) throw Error("renderer: no sub-frames to render");
  if (!times.empty() && times.size() != subframes.size()) throw Error("renderer: expected one time per sub-frame");
  cv::Mat acc = cv::Mat::zeros(cam.height, cam.width, CV_32F);
  for (std::size_t j = 0; j < subframes.size(); ++j)
    acc += render_clean(cam, subframes[j], times.empty() ? 0.0 : times[j]);
  acc /= static_cast<double>(subframes.size());
  return acc;
}

cv::Mat Renderer::sensor(const cv::Mat& acc, std::uint64_t key) const {
  cv::Mat levels;
  acc.convertTo(levels, CV_64F, 255.0 * o_.gain);
  if (o_.noise_sigma > 0) {
    // Box-Muller on our own uniform draws: std::normal_distribution is not specified bit for bit.
    std::mt19937_64 rng(key);
    auto uniform = [&] { return (static_cast<double>(rng() >> 11) + 0.5) * 0x1.0p-53; };
    for (int y = 0; y < levels.rows; ++y) {
      double* row = levels.ptr<double>(y);
      for (int x = 0; x < levels.cols; ++x)
        row[x] += o_.noise_sigma * std::sqrt(-2 * std::log(uniform())) * std::cos(2 * std::numbers::pi * uniform());
    }
  }
  cv::Mat out;
  levels.convertTo(out, CV_8U);  // rounds and saturates
  return out;
}

}  // namespace finverse::vision
