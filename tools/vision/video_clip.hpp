// One camera's video file (AVI, MP4, MOV, ... whatever OpenCV's videoio decodes) as a source of
// grey frames for fin-track (issue 35, item 1: inputs as labs have them). Frames are numbered
// 0, 1, ... in decoding order; the count is found by decoding the clip once (a container's own
// count is not always right), the frame rate is the container's. Reading is sequential: a frame
// before the last one read reopens the clip, so the tracker's in-order reads cost one decode each.
#pragma once

#include <filesystem>
#include <mutex>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>

namespace finverse::vision {

// True for the file name endings of the video containers fin-track accepts.
bool is_video_file(const std::filesystem::path& file);

class VideoClip {
 public:
  // Throws finverse::Error naming the file when it cannot be opened or holds no decodable frame.
  explicit VideoClip(const std::filesystem::path& file);

  long frames() const { return frames_; }
  double fps() const { return fps_; }  // the container's frame rate; 0 when it gives none
  int width() const { return width_; }
  int height() const { return height_; }
  const std::filesystem::path& path() const { return file_; }

  // Frame k (0-based) as 8-bit grey. Thread-safe. Throws finverse::Error naming the file and frame
  // when it cannot be decoded.
  cv::Mat grey(long k) const;

 private:
  void reopen() const;
  std::filesystem::path file_;
  long frames_ = 0;
  double fps_ = 0;
  int width_ = 0, height_ = 0;
  mutable std::mutex mutex_;
  mutable cv::VideoCapture capture_;
  mutable long next_ = 0;  // index of the frame the next read returns
};

}  // namespace finverse::vision
