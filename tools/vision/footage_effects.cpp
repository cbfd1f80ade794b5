// Debris specks and lossy compression of realistic virtual footage (issue 35, item 8).
#include "vision/footage_effects.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace finverse::vision {

Debris::Debris(const DebrisOptions& o, std::uint64_t seed, std::size_t view, int width, int height)
    : width_(width), height_(height) {
  if (o.count < 0) throw Error("--debris: expected a count >= 0");
  if (!(o.max_radius_px >= 0.5)) throw Error("--debris-radius: expected >= 0.5 px");
  if (!(o.drift_px_per_s >= 0)) throw Error("--debris-drift: expected >= 0 px/s");
  // Own uniform draws (as the renderer's noise): std distributions are not specified bit for bit.
  std::mt19937_64 rng(seed * 0x9e3779b97f4a7c15ULL ^ (0xd1b54a32d192ed03ULL + view));
  auto uniform = [&] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  for (int i = 0; i < o.count; ++i) {
    Speck s{};
    s.x = uniform() * width, s.y = uniform() * height;
    if (i % 3 != 0) {
      const double a = 2 * std::numbers::pi * uniform(), v = o.drift_px_per_s * (0.3 + 0.7 * uniform());
      s.vx = v * std::cos(a), s.vy = v * std::sin(a);
    }
    s.radius = 0.5 + (o.max_radius_px - 0.5) * uniform();
    s.level = 0.05 + 0.3 * uniform();
    s.opacity = 0.5 + 0.5 * uniform();
    specks_.push_back(s);
  }
}

void Debris::draw(cv::Mat& img, double t) const {
  if (img.type() != CV_32F || img.cols != width_ || img.rows != height_) throw Error("debris: frame does not match the view");
  for (const auto& s : specks_) {
    // Position at t, wrapped into the frame (a speck leaving one side comes back on the other).
    const double x = s.x + std::fmod(s.vx * t, width_) + width_, y = s.y + std::fmod(s.vy * t, height_) + height_;
    const double cx = std::fmod(x, width_), cy = std::fmod(y, height_);
    const int r = static_cast<int>(std::ceil(s.radius + 1));
    for (int py = static_cast<int>(cy) - r; py <= static_cast<int>(cy) + r; ++py) {
      if (py < 0 || py >= height_) continue;
      float* row = img.ptr<float>(py);
      for (int px = static_cast<int>(cx) - r; px <= static_cast<int>(cx) + r; ++px) {
        if (px < 0 || px >= width_) continue;
        // Pixel centres at integer + 0.5 from the speck's centre; a one-pixel soft edge.
        const double d = std::hypot(px + 0.5 - cx, py + 0.5 - cy);
        const double a = s.opacity * std::clamp(s.radius + 0.5 - d, 0.0, 1.0);
        if (a > 0) row[px] = static_cast<float>(row[px] * (1 - a) + s.level * a);
      }
    }
  }
}

cv::Mat jpeg_round_trip(const cv::Mat& frame, int quality) {
  if (quality < 1 || quality > 100) throw Error("--jpeg-quality: expected 1..100 (0: no compression)");
  std::vector<unsigned char> buf;
  if (!cv::imencode(".jpg", frame, buf, {cv::IMWRITE_JPEG_QUALITY, quality})) throw Error("cannot encode JPEG");
  cv::Mat out = cv::imdecode(buf, cv::IMREAD_UNCHANGED);
  if (out.empty()) throw Error("cannot decode JPEG");
  return out;
}

void write_mjpg_avi(const std::filesystem::path& avi, const std::vector<cv::Mat>& frames, double fps, int quality) {
  if (quality < 1 || quality > 100) throw Error("--jpeg-quality: expected 1..100 for the MJPG video");
  if (frames.empty()) throw Error(avi.string() + ": no frames to write");
  const auto tmp = temporary_for(avi).replace_extension(".avi");
  cv::VideoWriter out(tmp.string(), cv::CAP_OPENCV_MJPEG, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), fps, frames[0].size(),
                      true);
  if (!out.isOpened()) throw Error(avi.string() + ": cannot write an MJPG AVI here");
  out.set(cv::VIDEOWRITER_PROP_QUALITY, quality);
  for (const auto& f : frames) {
    if (f.size() != frames[0].size() || f.type() != CV_8U) throw Error(avi.string() + ": frames of one size, 8-bit grey, expected");
    cv::Mat bgr;  // three equal channels: FFmpeg's decoder misreads OpenCV's single-channel MJPEG
    cv::cvtColor(f, bgr, cv::COLOR_GRAY2BGR);
    out.write(bgr);
  }
  out.release();
  std::filesystem::rename(tmp, avi);
}

}  // namespace finverse::vision
