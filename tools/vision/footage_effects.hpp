// What a lab's camera adds to the scene that the renderer does not (issue 35, item 8: realistic
// virtual footage): debris specks in the tank, and the lossy compression of the recording (JPEG
// frames, as an MJPG AVI stores them). The renderer itself gives the body (fish_body.hpp),
// vignetting, the background gradient, sensor gain with saturation and noise (renderer.hpp).
//
// Debris: `count` dark, soft-edged specks per view, drawn from a generator seeded with (seed,
// view), so a frame is a pure function of its inputs. A third of them sit still (dirt on the tank
// window); the others drift across the frame at a constant velocity (particles in the flow),
// wrapping around the image. Radii are drawn between 0.5 and max_radius_px.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include <opencv2/core.hpp>

namespace finverse::vision {

struct DebrisOptions {
  int count = 0;                 // specks per view (0: none)
  double max_radius_px = 3.0;    // largest speck radius
  double drift_px_per_s = 400;   // largest drift speed of a moving speck
};

class Debris {
 public:
  // Throws finverse::Error naming the flag when an option is out of range.
  Debris(const DebrisOptions& options, std::uint64_t seed, std::size_t view, int width, int height);
  // Darkens `exposure` (CV_32F in [0, 1], the scene before the sensor) with the specks at time t (s).
  void draw(cv::Mat& exposure, double t) const;

 private:
  struct Speck {
    double x, y, vx, vy, radius, level, opacity;
  };
  std::vector<Speck> specks_;
  int width_, height_;
};

// The frame after a JPEG round trip at `quality` (1..100), as an MJPG recording stores it.
cv::Mat jpeg_round_trip(const cv::Mat& frame, int quality);

// `frames` (8-bit grey, one size) as an MJPG AVI at `fps` and JPEG `quality`, written by OpenCV's
// own MJPEG encoder (no external backend, so the file is the same wherever it runs) into a
// temporary renamed into place.
void write_mjpg_avi(const std::filesystem::path& avi, const std::vector<cv::Mat>& frames, double fps, int quality);

}  // namespace finverse::vision
