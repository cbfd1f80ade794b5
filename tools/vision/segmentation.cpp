// Background-model segmentation of the backlit fin (seed paper section 2.1, step 1).
#include "vision/segmentation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Dense>
#include <opencv2/imgproc.hpp>

#include "core/error.hpp"

namespace finverse::vision {
namespace {

// Background surface b(x, y) = c0 + c1 x + c2 y + c3 r^2 + c4 r^4 in normalised coordinates
// about the image centre: vignetting plus a tilt of the backlight.
constexpr int kTerms = 5;
void basis(double x, double y, double* f) {
  const double r2 = x * x + y * y;
  f[0] = 1;
  f[1] = x;
  f[2] = y;
  f[3] = r2;
  f[4] = r2 * r2;
}

}  // namespace

Segmentation segment_fin(const cv::Mat& frame, const SegmentationOptions& o, const SegmentationContext& ctx) {
  if (frame.empty() || frame.type() != CV_8UC1) throw Error("segmentation: expected a non-empty 8-bit grey frame");
  if (!ctx.median.empty() && (ctx.median.size() != frame.size() || ctx.median.type() != CV_32F))
    throw Error("segmentation: the temporal median background differs from the frame in size or type");
  const int W = frame.cols, H = frame.rows;
  const double cx = 0.5 * (W - 1), cy = 0.5 * (H - 1), scale = 1.0 / std::hypot(cx, cy);
  cv::Mat smooth;
  frame.convertTo(smooth, CV_32F);
  if (o.blur_sigma_px > 0) cv::GaussianBlur(smooth, smooth, cv::Size(0, 0), o.blur_sigma_px);

  // Noise from the raw frame: median absolute difference of horizontal neighbours, robust to
  // the fin's edges (sigma of a difference of two samples is sqrt(2) sigma).
  std::vector<float> diffs;
  diffs.reserve(static_cast<std::size_t>(W) * H / 4);
  for (int y = 0; y < H; y += 2) {
    const auto* row = frame.ptr<std::uint8_t>(y);
    for (int x = 0; x + 1 < W; x += 2) diffs.push_back(static_cast<float>(std::abs(row[x + 1] - row[x])));
  }
  std::nth_element(diffs.begin(), diffs.begin() + diffs.size() / 2, diffs.end());
  // Compressed or saturated video has most neighbour differences 0: the floor keeps the
  // threshold from falling to min_contrast on a frame whose noise is only hidden.
  const double raw_sigma = std::max(o.noise_floor, 1.4826 * diffs[diffs.size() / 2] / std::sqrt(2.0));
  // A Gaussian blur of sigma s reduces white noise by about 1 / (2 sqrt(pi) s).
  const double blurred_sigma = o.blur_sigma_px > 0 ? raw_sigma / (2 * std::sqrt(std::numbers::pi) * o.blur_sigma_px) : raw_sigma;

  // Robust least squares on a pixel lattice: start from every sample, drop the ones darker than
  // the current surface (fin) and refit.
  const int step = std::max(1, std::min(W, H) / 96);
  std::vector<std::array<double, kTerms>> F;
  std::vector<double> v;
  for (int y = 0; y < H; y += step)
    for (int x = 0; x < W; x += step) {
      std::array<double, kTerms> f;
      basis((x - cx) * scale, (y - cy) * scale, f.data());
      F.push_back(f);
      v.push_back(smooth.at<float>(y, x));
    }
  std::vector<char> use(v.size(), 1);
  // First pass: the fin covers well under half the view, so the brightest samples are background.
  {
    std::vector<double> sorted = v;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double median = sorted[sorted.size() / 2];
    for (std::size_t i = 0; i < v.size(); ++i) use[i] = v[i] >= median - 3 * std::max(1.0, raw_sigma) - 0.1 * median;
  }
  Eigen::Matrix<double, kTerms, 1> c = Eigen::Matrix<double, kTerms, 1>::Zero();
  for (int it = 0; it < std::max(1, o.background_iterations); ++it) {
    Eigen::Matrix<double, kTerms, kTerms> A = Eigen::Matrix<double, kTerms, kTerms>::Zero();
    Eigen::Matrix<double, kTerms, 1> b = Eigen::Matrix<double, kTerms, 1>::Zero();
    std::size_t n = 0;
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (!use[i]) continue;
      const Eigen::Map<const Eigen::Matrix<double, kTerms, 1>> f(F[i].data());
      A += f * f.transpose();
      b += f * v[i];
      ++n;
    }
    if (n < 4 * kTerms) throw Error("segmentation: too little background visible to model the backlight");
    c = A.ldlt().solve(b);
    for (std::size_t i = 0; i < v.size(); ++i) {
      const Eigen::Map<const Eigen::Matrix<double, kTerms, 1>> f(F[i].data());
      use[i] = v[i] > f.dot(c) - 3 * std::max(0.5, blurred_sigma);
    }
  }

  Segmentation s;
  s.noise_sigma = raw_sigma;
  s.threshold = std::max(o.min_contrast, o.noise_multiple * blurred_sigma);
  s.background = cv::Mat(H, W, CV_32F);
  s.mask = cv::Mat::zeros(H, W, CV_8U);
  s.coverage = cv::Mat::zeros(H, W, CV_32F);
  for (int y = 0; y < H; ++y) {
    auto* bg = s.background.ptr<float>(y);
    const auto* im = smooth.ptr<float>(y);
    auto* m = s.mask.ptr<std::uint8_t>(y);
    for (int x = 0; x < W; ++x) {
      double f[kTerms];
      basis((x - cx) * scale, (y - cy) * scale, f);
      double b = 0;
      for (int k = 0; k < kTerms; ++k) b += f[k] * c[k];
      bg[x] = static_cast<float>(b);
      m[x] = b - im[x] > s.threshold ? 255 : 0;
    }
  }
  if (!ctx.median.empty() && o.background != BackgroundModel::model) {
    cv::Mat median = ctx.median.clone();
    if (o.blur_sigma_px > 0) cv::GaussianBlur(median, median, cv::Size(0, 0), o.blur_sigma_px);
    if (o.background == BackgroundModel::median) {
      // The frame's spread about its median (compression, flicker) also sets the threshold.
      cv::Mat r = cv::abs(smooth - median);
      std::vector<float> rv(r.begin<float>(), r.end<float>());
      std::nth_element(rv.begin(), rv.begin() + rv.size() / 2, rv.end());
      s.threshold = std::max(s.threshold, o.noise_multiple * 1.4826 * rv[rv.size() / 2]);
      s.background = median;
    } else {
      // Static dark structure reaching the border: the median there, the model elsewhere (a fish
      // holding station stays out of the median's reach unless it touches the border). A static
      // structure that crosses the fin's root line is the fish's body holding still in the image
      // with the fin's root: the median only on the body's side of the line (the fin's root
      // barely moves either and would go into the background with the body).
      const cv::Mat dark_static = (s.background - median) > s.threshold;
      cv::Mat labels, stats, centroids;
      const int n = cv::connectedComponentsWithStats(dark_static, labels, stats, centroids, 8, CV_32S);
      cv::Mat body_side;
      if (ctx.cut_at_line || ctx.orient_by_line)
        body_side = fin_side_mask(cv::Mat(H, W, CV_8U, cv::Scalar(255)), ctx.root_line) == 0;
      for (int l = 1; l < n; ++l) {
        const int x0 = stats.at<int>(l, cv::CC_STAT_LEFT), y0 = stats.at<int>(l, cv::CC_STAT_TOP);
        const int w = stats.at<int>(l, cv::CC_STAT_WIDTH), h = stats.at<int>(l, cv::CC_STAT_HEIGHT);
        if (!(x0 == 0 || y0 == 0 || x0 + w == W || y0 + h == H)) continue;
        const cv::Mat component = labels == l;
        const int on_body_side = body_side.empty() ? 0 : cv::countNonZero(component & body_side);
        const bool crosses = on_body_side > 0 && on_body_side < stats.at<int>(l, cv::CC_STAT_AREA);
        median.copyTo(s.background, crosses ? cv::Mat(component & body_side) : component);
      }
    }
    s.mask = (s.background - smooth) > s.threshold;
  }
  // Rim pixels are part fin, part background (anti-aliasing, blur): a pixel is the fin's when the
  // fin covers at least half of it (the pixel-centre convention of project_model), i.e. when it
  // darkens the background by at least `coverage` times the full contrast of the fin at that
  // spot. That full contrast varies a lot (membrane about 30-90 levels, rays and stacked layers
  // of an edge-on fold up to 180), so it is read where the fin surely covers whole pixels: at the
  // nearest "core" pixel, at least core_depth_px inside the detection mask (the pre-blur and the
  // motion blur spread the detection about a pixel outwards, so the mask's first inner ring is
  // still rim). The test reads the unblurred frame (blurring would pull a dark rim's contrast into
  // the pixel outside it); the sensor noise there, about 2 levels, is small against half a
  // contrast of 15 levels or more. Where no core is near (a sliver only a few pixels thick), the
  // largest darkening within contrast_radius_px stands in for the full contrast. The full contrast
  // is also never less than that of the (pre-blurred) pixels touching the rim pixel: an outline
  // darker than the interior (the stacked layers of an edge-on fold, a ray along the edge) would
  // otherwise push the boundary a pixel outwards. Why not a maximum over a disc everywhere (it
  // takes a ray's contrast for the membrane beside it): docs/studies/vision_segmentation_rim.md.
  const int margin = o.contrast_radius_px + o.core_depth_px + 2;
  cv::Rect roi = cv::boundingRect(s.mask);
  if (roi.area() > 0) {
    roi = cv::Rect(roi.x - margin, roi.y - margin, roi.width + 2 * margin, roi.height + 2 * margin) & cv::Rect(0, 0, W, H);
    cv::Mat mask = s.mask(roi), bg = s.background(roi), cover = s.coverage(roi), raw, dark, dark_raw, core, dist, label, local;
    frame(roi).convertTo(raw, CV_32F);
    dark = bg - smooth(roi);
    dark_raw = bg - raw;
    const int cd = std::max(1, o.core_depth_px);
    cv::erode(mask, core, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * cd + 1, 2 * cd + 1)), cv::Point(-1, -1), 1,
              cv::BORDER_CONSTANT, cv::Scalar(0));
    // Voronoi labels: every pixel learns its nearest core pixel.
    cv::distanceTransform(core == 0, dist, label, cv::DIST_L2, cv::DIST_MASK_5, cv::DIST_LABEL_PIXEL);
    std::vector<float> full_at(static_cast<std::size_t>(cv::countNonZero(core)) + 1, 0.f);
    for (int y = 0; y < roi.height; ++y) {
      const auto* k = core.ptr<std::uint8_t>(y);
      const auto* l = label.ptr<int>(y);
      const auto* d = dark.ptr<float>(y);
      for (int x = 0; x < roi.width; ++x)
        if (k[x]) full_at[static_cast<std::size_t>(l[x])] = d[x];
    }
    const auto disk = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * o.contrast_radius_px + 1, 2 * o.contrast_radius_px + 1));
    cv::dilate(dark, local, disk);
    cv::Mat touching;  // largest darkening among the pixel and its 8 neighbours
    cv::dilate(dark, touching, cv::Mat());
    // Slivers without a core (an edge ray, a prong of the fork, one or two pixels wide): the
    // pre-blur spreads their darkening, so the soft segmentation reads their full contrast on
    // the raw frame, as the largest darkening a little further out (a sub-pixel prong is never
    // fully covered itself), less one noise sigma for picking the maximum of noisy samples.
    cv::Mat sliver_full;
    cv::dilate(dark_raw, sliver_full,
               cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * o.contrast_radius_px + 3, 2 * o.contrast_radius_px + 3)));
    sliver_full -= raw_sigma;
    for (int y = 0; y < roi.height; ++y) {
      const auto* d = dark_raw.ptr<float>(y);
      const auto* lm = local.ptr<float>(y);
      const auto* t = touching.ptr<float>(y);
      const auto* k = core.ptr<std::uint8_t>(y);
      const auto* l = label.ptr<int>(y);
      const auto* r = dist.ptr<float>(y);
      auto* m = mask.ptr<std::uint8_t>(y);
      auto* cov = cover.ptr<float>(y);
      const auto* sf = sliver_full.ptr<float>(y);
      for (int x = 0; x < roi.width; ++x) {
        const double full = std::max<double>(t[x], r[x] <= o.contrast_radius_px ? full_at[static_cast<std::size_t>(l[x])] : lm[x]);
        // Soft segmentation: the same ratio, kept (clipped to [-0.5, 1]: a darker ray beside a
        // rim pixel must not read as more than full cover) wherever a fin contrast is near.
        // The largest of nine noisy neighbours reads about 1.5 (blurred) sigmas high.
        const double t_cov = t[x] - 1.5 * blurred_sigma;
        const double full_cov = std::max(t_cov, r[x] <= o.contrast_radius_px ? full_at[static_cast<std::size_t>(l[x])]
                                                                             : std::max<double>(lm[x], sf[x]));
        if (k[x]) {
          // Also on the core, against its own (pre-blurred) contrast or its neighbours': the
          // pre-blur fills the gap between two prongs a pixel or two apart (the fork seen
          // edge-on), which the raw frame shows light, and dilutes the contrast of the pixels
          // beside the gap. Not clipped at 1, so the noise of a fully covered pixel stays unbiased.
          cov[x] = static_cast<float>(std::clamp(d[x] / full_cov, -0.5, 1.5));
          continue;
        }
        if (full_cov >= s.threshold) cov[x] = static_cast<float>(std::clamp(d[x] / full_cov, -0.5, 1.0));
        if (m[x] && d[x] < o.coverage * full) m[x] = 0;
      }
    }
  }
  if (ctx.fin_region.area() > 0) s.mask = fin_region_mask(s.mask, ctx.fin_region);
  if (ctx.cut_at_line) {
    s.mask = fin_side_mask(s.mask, ctx.root_line);
    s.fin_cut = true;
  }
  // One fish: of the dark blobs, the one that overlaps the previous frame's fish (grown by the
  // reach of a frame's motion) most; without a previous frame the largest that does not touch
  // the image border (a vignette strip, a tank wall), and only when every blob touches it the
  // largest of them. Then its holes are filled.
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(s.mask, labels, stats, centroids, 8, CV_32S);
  auto touches = [&](int l) {
    const int x0 = stats.at<int>(l, cv::CC_STAT_LEFT), y0 = stats.at<int>(l, cv::CC_STAT_TOP);
    return x0 == 0 || y0 == 0 || x0 + stats.at<int>(l, cv::CC_STAT_WIDTH) == W || y0 + stats.at<int>(l, cv::CC_STAT_HEIGHT) == H;
  };
  int best = 0;
  if (!ctx.previous.empty() && cv::countNonZero(ctx.previous) > 0) {
    const int reach = o.track_radius_px > 0 ? o.track_radius_px : std::max(8, static_cast<int>(0.05 * std::min(W, H)));
    cv::Mat near_previous;
    cv::dilate(ctx.previous, near_previous, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * reach + 1, 2 * reach + 1)));
    std::vector<int> overlap(static_cast<std::size_t>(n), 0);
    for (int y = 0; y < H; ++y) {
      const auto* l = labels.ptr<int>(y);
      const auto* p = near_previous.ptr<std::uint8_t>(y);
      for (int x = 0; x < W; ++x)
        if (l[x] > 0 && p[x]) ++overlap[static_cast<std::size_t>(l[x])];
    }
    for (int l = 1; l < n; ++l)
      if (overlap[static_cast<std::size_t>(l)] > (best ? overlap[static_cast<std::size_t>(best)] : 0)) best = l;
    s.lost = best == 0 && n > 1;
  } else {
    int area = 0;
    for (int pass = 0; pass < 2 && best == 0; ++pass)  // pass 0: blobs clear of the border
      for (int l = 1; l < n; ++l)
        if ((pass == 1 || !o.reject_border || !touches(l)) && stats.at<int>(l, cv::CC_STAT_AREA) > area)
          area = stats.at<int>(l, cv::CC_STAT_AREA), best = l;
  }
  s.rejected_blobs = std::max(0, n - 1 - (best > 0 ? 1 : 0));
  if (best == 0) {  // nothing darker than the background, or nothing near the fish: an empty view
    s.mask.setTo(0);
    s.coverage.setTo(0);
    return s;
  }
  s.touches_border = touches(best);
  s.mask = labels == best;
  cv::Mat outside = s.mask == 0;
  const int nb = cv::connectedComponentsWithStats(outside, labels, stats, centroids, 4, CV_32S);
  for (int l = 1; l < nb; ++l) {
    const int x0 = stats.at<int>(l, cv::CC_STAT_LEFT), y0 = stats.at<int>(l, cv::CC_STAT_TOP);
    const int w = stats.at<int>(l, cv::CC_STAT_WIDTH), h = stats.at<int>(l, cv::CC_STAT_HEIGHT);
    const bool touches_border = x0 == 0 || y0 == 0 || x0 + w == W || y0 + h == H;
    if (!touches_border) s.mask.setTo(255, labels == l);
  }
  if (o.fin_cut) {
    auto cut = separate_caudal_fin(s.mask, o.cut, ctx.orient_by_line ? &ctx.root_line : nullptr);
    s.fin_cut = s.fin_cut || cut.cut;
    s.mask = cut.fin;
  }
  if (ctx.find_body) s.body = opaque_body(frame, s.background, s.mask, o);
  if (ctx.cut_at_line && ctx.root_band_px > 0) {
    const cv::Vec3d beyond(ctx.root_line[0], ctx.root_line[1], ctx.root_line[2] - ctx.root_band_px);
    const cv::Mat band = fin_side_mask(cv::Mat(H, W, CV_8U, cv::Scalar(255)), beyond) == 0;
    s.body = s.body.empty() ? band : cv::Mat(s.body | band);
  }
  // The soft segmentation keeps the fin's rim: nothing beyond two pixels of the cleaned mask.
  cv::Mat near;
  cv::dilate(s.mask, near, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(5, 5)));
  s.coverage.setTo(0, near == 0);
  return s;
}

cv::Mat signed_distance(const cv::Mat& mask) {
  cv::Mat inside = mask != 0, outside = mask == 0;
  cv::Mat d_out, d_in;
  // distanceTransform measures to the nearest zero pixel: d_out is the distance of an outside
  // pixel to the fin, d_in of a fin pixel to the background.
  cv::distanceTransform(outside, d_out, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  cv::distanceTransform(inside, d_in, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  cv::Mat sdf(mask.size(), CV_32F);
  for (int y = 0; y < mask.rows; ++y) {
    const auto* m = mask.ptr<std::uint8_t>(y);
    const auto* a = d_out.ptr<float>(y);
    const auto* b = d_in.ptr<float>(y);
    auto* s = sdf.ptr<float>(y);
    for (int x = 0; x < mask.cols; ++x) s[x] = m[x] ? 0.5f - b[x] : a[x] - 0.5f;
  }
  return sdf;
}

std::vector<cv::Point> inner_contour(const cv::Mat& mask) {
  std::vector<cv::Point> out;
  for (int y = 0; y < mask.rows; ++y) {
    const auto* m = mask.ptr<std::uint8_t>(y);
    const auto* up = y > 0 ? mask.ptr<std::uint8_t>(y - 1) : nullptr;
    const auto* dn = y + 1 < mask.rows ? mask.ptr<std::uint8_t>(y + 1) : nullptr;
    for (int x = 0; x < mask.cols; ++x) {
      if (!m[x]) continue;
      const bool edge = x == 0 || x + 1 == mask.cols || !m[x - 1] || !m[x + 1] || !up || !dn || !up[x] || !dn[x];
      if (edge) out.emplace_back(x, y);
    }
  }
  return out;
}

double mask_iou(const cv::Mat& a, const cv::Mat& b, const cv::Mat& excluded) {
  if (a.size() != b.size() || (!excluded.empty() && excluded.size() != a.size())) throw Error("mask_iou: masks differ in size");
  cv::Mat inter = (a != 0) & (b != 0), uni = (a != 0) | (b != 0);
  if (!excluded.empty()) inter.setTo(0, excluded), uni.setTo(0, excluded);
  const double i = cv::countNonZero(inter), u = cv::countNonZero(uni);
  return u > 0 ? i / u : 1.0;
}

cv::Mat opaque_body(const cv::Mat& frame, const cv::Mat& background, const cv::Mat& mask, const SegmentationOptions& o) {
  cv::Mat grey, opaque;
  frame.convertTo(grey, CV_32F);
  if (o.blur_sigma_px > 0) cv::GaussianBlur(grey, grey, cv::Size(0, 0), o.blur_sigma_px);
  opaque = (grey < o.opaque_transmission * background) & (mask != 0);
  // Opening removes what is thinner than the disc: a ray, an edge-on fin, a speck.
  const int r = std::max(1, o.body_radius_px);
  cv::morphologyEx(opaque, opaque, cv::MORPH_OPEN, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * r + 1, 2 * r + 1)));
  if (cv::countNonZero(opaque) == 0) return {};
  if (o.body_rim_px > 0)
    cv::dilate(opaque, opaque,
               cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * o.body_rim_px + 1, 2 * o.body_rim_px + 1)));
  return opaque;
}

cv::Mat temporal_median(const std::vector<cv::Mat>& frames, double quantile) {
  if (frames.empty()) throw Error("temporal median: no frames");
  const cv::Size size = frames[0].size();
  for (const auto& f : frames)
    if (f.size() != size || f.type() != CV_8UC1) throw Error("temporal median: frames differ in size or are not 8-bit grey");
  cv::Mat out(size, CV_32F);
  std::vector<std::uint8_t> v(frames.size());
  const bool median = quantile == 0.5;
  const std::size_t mid = median ? frames.size() / 2
                                 : static_cast<std::size_t>(std::clamp(quantile, 0.0, 1.0) * static_cast<double>(frames.size() - 1) + 0.5);
  for (int y = 0; y < size.height; ++y) {
    auto* o = out.ptr<float>(y);
    for (int x = 0; x < size.width; ++x) {
      for (std::size_t k = 0; k < frames.size(); ++k) v[k] = frames[k].ptr<std::uint8_t>(y)[x];
      std::nth_element(v.begin(), v.begin() + mid, v.end());
      float m = v[mid];
      if (median && frames.size() % 2 == 0) m = 0.5f * (m + *std::max_element(v.begin(), v.begin() + mid));
      o[x] = m;
    }
  }
  return out;
}

}  // namespace finverse::vision
