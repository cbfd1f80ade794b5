// Video files as frame sources (see video_clip.hpp).
#include "vision/video_clip.hpp"

#include <algorithm>
#include <array>
#include <cctype>

#include <opencv2/core/utils/logger.hpp>
#include <opencv2/imgproc.hpp>

#include "core/error.hpp"

namespace fs = std::filesystem;

namespace finverse::vision {

bool is_video_file(const fs::path& file) {
  auto ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  static const std::array<const char*, 7> known{".avi", ".mp4", ".mov", ".mkv", ".m4v", ".mpg", ".wmv"};
  return std::any_of(known.begin(), known.end(), [&](const char* e) { return ext == e; });
}

namespace {
cv::Mat to_grey(const cv::Mat& frame) {
  if (frame.channels() == 1) return frame.depth() == CV_8U ? frame.clone() : cv::Mat();
  cv::Mat grey;
  cv::cvtColor(frame, grey, frame.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return grey;
}
}  // namespace

void VideoClip::reopen() const {
  capture_.release();
  // File backends only: FFmpeg first (GStreamer logs several lines on a file it cannot play),
  // then GStreamer. CAP_ANY would also probe camera backends, which enumerate USB devices and
  // leak what they allocate (LeakSanitizer); OpenCV's log is silenced while probing.
  const auto level = cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  bool ok = false;
  for (const int api : {cv::CAP_FFMPEG, cv::CAP_GSTREAMER}) {
    try {
      ok = capture_.open(file_.string(), api) && capture_.isOpened();
    } catch (const cv::Exception&) {
      ok = false;
    }
    if (ok) break;
  }
  cv::utils::logging::setLogLevel(level);
  if (!ok || !capture_.isOpened())
    throw Error(file_.string() + ": cannot decode the video (expected a clip OpenCV's videoio reads: AVI, MP4, MOV)");
  next_ = 0;
}

VideoClip::VideoClip(const fs::path& file) : file_(file) {
  if (!fs::is_regular_file(file)) throw Error(file.string() + ": no such video file");
  reopen();
  fps_ = capture_.get(cv::CAP_PROP_FPS);
  if (!(fps_ > 0 && fps_ < 1e7)) fps_ = 0;
  cv::Mat frame;
  if (!capture_.read(frame) || frame.empty())
    throw Error(file_.string() + ": cannot decode the video (no frame could be read; expected AVI, MP4 or MOV)");
  width_ = frame.cols, height_ = frame.rows;
  frames_ = 1;
  while (capture_.grab()) ++frames_;
  reopen();
}

cv::Mat VideoClip::grey(long k) const {
  const std::lock_guard lock(mutex_);
  if (k < 0 || k >= frames_)
    throw Error(file_.string() + ": no frame " + std::to_string(k) + " (the clip has " + std::to_string(frames_) + ")");
  if (k < next_) reopen();
  for (; next_ < k; ++next_)
    if (!capture_.grab()) throw Error(file_.string() + ": frame " + std::to_string(next_) + " cannot be decoded");
  cv::Mat frame;
  const bool ok = capture_.read(frame);
  ++next_;
  cv::Mat grey = ok && !frame.empty() ? to_grey(frame) : cv::Mat();
  if (grey.empty()) throw Error(file_.string() + ": frame " + std::to_string(k) + " cannot be decoded");
  return grey;
}

}  // namespace finverse::vision
