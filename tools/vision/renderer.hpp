// Synthetic high-speed camera images of the fin (DESIGN.md section 5.5: "fin-synth renders the
// truth surface into each calibrated camera: z-buffer, translucent membrane, darker rays,
// texture, blur, sensor noise"), modelled on the paper's backlit flow-tank videos (section 4.1,
// Fig. 7: 500 fps, three views).
//
// Per pixel the renderer keeps the nearest few fragments (a small depth-sorted k-buffer, so
// overlapping folds of the translucent fin composite in the right order whatever the triangle
// order), then composites them back to front over the backlit background. Coverage uses exact
// fixed-point edge functions with the top-left rule, so no pixel is drawn twice or missed along a
// shared edge. Rays are drawn per pixel from the interpolated distance to the nearest ray, so
// they stay crisp on a coarse surface. Triangles are rasterised straight in the distorted image
// (vertices are projected with distortion); with the mild lens model and small triangles the
// curvature error is far below a pixel.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "core/nd_array.hpp"
#include "vision/camera.hpp"
#include "vision/fin_surface.hpp"
#include "vision/fish_body.hpp"

namespace finverse::vision {

struct RenderOptions {
  int supersample = 2;           // samples per pixel along each axis (anti-aliasing)
  double background = 0.85;      // backlit tank, fraction of full scale at the image centre
  double vignetting = 0.15;      // background falls by this fraction towards the corners
  double vignetting_power = 2;   // ... as (r / r_corner)^power (2: gentle; 4 and more: a dark rim)
  double background_gradient = 0;  // background falls by this fraction from the right to the left edge
  double membrane_alpha = 0.45;  // opacity of the membrane
  double ray_alpha = 0.9;        // opacity of a ray
  double membrane_level = 0.55;  // grey level of lit membrane
  double ray_level = 0.15;       // grey level of lit ray
  double noise_sigma = 2.0;      // sensor noise, standard deviation in 8-bit levels (0: none)
  double gain = 1.0;             // sensor gain; above 1 the bright background clips at 255
};

class Renderer {
 public:
  // `body` (optional, not owned): the fish's opaque body drawn with the fin (fish_body.hpp).
  Renderer(const FinSurface& surface, const RenderOptions& options, const FishBody* body = nullptr);

  // Noise-free image in [0, 1] (CV_32F) of the surface at `positions` [nv,3] at `time` (s:
  // the body's pectoral fins move on their own clock).
  cv::Mat render_clean(const Camera& camera, const NdArray<double>& positions, double time = 0) const;

  // The 8-bit frame: the average of the sub-frame images (motion blur over the exposure; one
  // entry means none) plus sensor noise drawn from a generator seeded with `noise_key`, so a
  // frame is a pure function of its inputs.
  cv::Mat render_frame(const Camera& camera, const std::vector<NdArray<double>>& subframes, std::uint64_t noise_key) const;
  // render_frame in two steps, so scene effects (footage_effects.hpp) can come between: the
  // average of the sub-frame images (CV_32F, [0, 1]) at `times` (one per sub-frame; empty: all
  // at 0), then the sensor (gain, noise, 8 bits).
  cv::Mat render_exposure(const Camera& camera, const std::vector<NdArray<double>>& subframes,
                          const std::vector<double>& times = {}) const;
  cv::Mat sensor(const cv::Mat& exposure, std::uint64_t noise_key) const;

 private:
  const FinSurface& surface_;
  RenderOptions o_;
  const FishBody* body_;
};

// Mixes a seed, a view index and a frame index into the noise key of one frame.
std::uint64_t noise_key(std::uint64_t seed, std::uint64_t view, std::uint64_t frame);

}  // namespace finverse::vision
