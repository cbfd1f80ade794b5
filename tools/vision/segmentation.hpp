// Segmentation of the fin in a camera frame (DESIGN.md section 5.5, fin-track; seed paper
// section 2.1 step 1: the fin outline in every view). The tank is backlit, so the background is
// bright and smooth and the translucent fin darkens it. The background is modelled per frame as
// a smooth radial surface (vignetting) fitted robustly to the pixels that are not fin; the fin is
// detected as every pixel darker than that model by more than a threshold set from the estimated
// noise (after a small Gaussian blur). Its rim is then decided per pixel by coverage: a rim pixel
// is fin when it darkens by at least half the full contrast of the fin at that spot, read at the
// nearest fully covered pixel (so the boundary sits where the coverage is one half, as for the
// pixel-centre silhouettes of the model). The mask is cleaned (one connected fin, holes filled)
// and turned into a signed distance field, which is what the silhouette residuals sample.
// Real footage (issue 35, item 3): the noise estimate has a floor (compressed or saturated video
// reads 0); static dark structure touching the image border (vignette strips, tank walls, dark
// bands) is taken into the background from the clip's temporal median (temporal_median); of the
// dark blobs the fish is the one connected to the previous frame's, else the largest not touching
// the border; the caudal fin is cut from the body (fin_separation.hpp) on request.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "vision/fin_separation.hpp"

namespace finverse::vision {

// The background a frame's darkening is measured against: the smooth radial model fitted to the
// frame; the clip's temporal median everywhere; or (automatic) the model, but the median where
// the median is darker than the model by more than the threshold in a region touching the border.
enum class BackgroundModel { model, median, automatic };
// automatic uses a temporal background only when the view has at least this many frames, and
// there the 90th percentile of the frames rather than their median: a pixel the fish leaves in
// one frame of ten or more is background there, while a vignette strip, a dark band or a body
// that never moves stays dark (measured: docs/studies/footage_inputs.md, run 4).
inline constexpr int kMedianMinFrames = 20;
inline constexpr double kStaticQuantile = 0.9;

struct SegmentationOptions {
  double blur_sigma_px = 0.7;      // pre-smoothing of the frame
  int contrast_radius_px = 3;      // reach of the rim test's reference (core pixel, else disc maximum)
  int core_depth_px = 2;           // pixels this deep in the detection mask count as fully covered
  double min_contrast = 6.0;       // 8-bit levels below the background, at least
  double noise_multiple = 4.0;     // ... and at least this many (blurred) noise sigmas
  int background_iterations = 4;   // robust refits of the background surface
  double coverage = 0.5;           // rim pixel: fin when it darkens by this fraction of the full contrast
  double noise_floor = 1.0;        // raw noise sigma (levels) never taken below this
  BackgroundModel background = BackgroundModel::automatic;
  bool reject_border = true;       // a blob touching the border is the fish only when no other is
  int track_radius_px = 0;         // a blob must reach this near the previous fish (0: 5 % of the image, >= 8)
  bool fin_cut = false;            // cut the caudal fin from the body at the peduncle
  FinCutOptions cut;
  // The body behind the fin (find_body): opaque (transmitting less than this fraction of the
  // background) and thicker than 2 body_radius_px + 1 px; grown by body_rim_px for its blurred rim.
  double opaque_transmission = 0.45;
  int body_radius_px = 3;
  int body_rim_px = 2;
};

// What the segmentation of one frame may know beyond the frame.
struct SegmentationContext {
  cv::Mat median;    // CV_32F temporal background of the view's clip (median or kStaticQuantile; empty: none)
  cv::Mat previous;  // CV_8U the fish's mask in the previous frame (empty: none)
  cv::Rect fin_region;  // the user's rectangle that holds the fin (empty: none)
  bool cut_at_line = false;  // keep only the fin's side of root_line (fin_separation.hpp)
  bool orient_by_line = false;  // the peduncle cut keeps the end on the fin's side of root_line
  cv::Vec3d root_line{0, 0, 0};
  bool find_body = false;    // mark the opaque body in the fish's blob (Segmentation::body)
  // With cut_at_line: the pixels up to this far (px) on the fin's side of root_line are marked
  // body too: the peduncle around the fin's root and the cut's own edge are not the fin's outline.
  double root_band_px = 0;
};

struct Segmentation {
  cv::Mat mask;              // CV_8U, 255 on the fin
  cv::Mat background;        // CV_32F, fitted background in 8-bit levels
  // CV_32F soft segmentation: the fraction of each pixel the fin covers, estimated as the raw
  // darkening over the local full contrast of the rim test (a core pixel over its own; a sliver
  // without a core over the largest raw darkening near it); 0 beyond two pixels of the mask.
  // Clipped to [-0.5, 1] (core: 1.5) only, so the sensor noise stays unbiased. Sub-pixel
  // evidence for the coverage residuals (coverage_residual.hpp).
  cv::Mat coverage;
  double noise_sigma = 0;    // estimated sensor noise (8-bit levels) of the raw frame, floor applied
  double threshold = 0;      // darkening (levels) that counts as fin
  bool touches_border = false;  // the chosen blob touches the image border (no other candidate)
  bool lost = false;            // no blob near the previous frame's fish: the mask is empty
  int rejected_blobs = 0;       // dark blobs left out (border, unconnected, specks)
  bool fin_cut = false;         // the body was cut off at the peduncle
  // With SegmentationContext::find_body, CV_8U: the body seen behind or beside the fin (empty:
  // none found). A backlit fin is translucent and its rays thin, the body opaque and thick: the
  // blob's pixels darker than opaque_transmission of the background, opened by a disc of
  // body_radius_px, grown by body_rim_px. Where it lies, fin and body cannot be told apart, so
  // the fit and the scores leave those pixels out (silhouette_residual.hpp, coverage_residual.hpp).
  cv::Mat body;
};

// `frame`: 8-bit grey (CV_8U). Throws finverse::Error if the frame is empty or not grey, or the
// context's median is not of the frame's size.
Segmentation segment_fin(const cv::Mat& frame, const SegmentationOptions& options = {},
                         const SegmentationContext& context = {});

// Per-pixel quantile (CV_32F; 0.5: the median) of 8-bit grey frames of one size.
cv::Mat temporal_median(const std::vector<cv::Mat>& frames, double quantile = 0.5);

// Signed distance (pixels, CV_32F) to the mask's boundary: positive outside, negative inside,
// zero half-way between an inside and an outside pixel centre.
cv::Mat signed_distance(const cv::Mat& mask);

// Pixels of `mask` with a 4-neighbour outside it (the inner contour), as (x, y).
std::vector<cv::Point> inner_contour(const cv::Mat& mask);

// Intersection over union of two masks of the same size; with `excluded` (same size, non-empty)
// over the pixels outside it only.
double mask_iou(const cv::Mat& a, const cv::Mat& b, const cv::Mat& excluded = {});

// The opaque, thick part of `mask` in `frame` against `background` (Segmentation::body).
cv::Mat opaque_body(const cv::Mat& frame, const cv::Mat& background, const cv::Mat& mask, const SegmentationOptions& options);

}  // namespace finverse::vision
