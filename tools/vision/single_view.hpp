// fin-track's 2-D single-view mode (issue 35, item 4): one camera's clip or image sequence ->
// per frame the fish's silhouette (segmentation.hpp: the whole fish, body and fin), midline and
// tail tip (midline.hpp), and over the record the tail-beat frequency, amplitude and body
// wavelength, in pixels and, given one scale factor, in millimetres. Written as CSV (per frame),
// HDF5 (everything) and an overlay video to check by eye.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "vision/midline.hpp"
#include "vision/segmentation.hpp"

namespace finverse::vision {

struct SingleViewOptions {
  SegmentationOptions segmentation;
  int stations = 25;                 // midline points, head to tail
  double fps = 500;                  // frame rate (1/s)
  std::optional<double> mm_per_px;   // one scale factor for the whole image
  cv::Rect region;                   // the user's rectangle that holds the fish (empty: the frame)
};

// A clip whose fish covers more of the image than this in its median frame fills the frame.
inline constexpr double kFillsTheFrame = 0.5;
// The tail beat needs this many measured frames.
inline constexpr std::size_t kMinBeatFrames = 8;

struct SingleViewResult {
  std::vector<long> frames;
  std::vector<MidlineFrame> midlines;            // each invalid one with its reason
  std::vector<std::uint8_t> segmentation_doubt;  // per frame: blob at the border, or lost
  TailBeat beat;                                 // NaN when fewer than kMinBeatFrames are valid
  std::size_t invalid = 0;                       // frames not measured
  std::string commonest_reason;                  // ... and why, most often
  // Most frames not measured: the record is written, flagged, and the run exits 1.
  bool mostly_invalid() const { return 2 * invalid > frames.size(); }
};

// Segments every frame (temporal median background as BackgroundModel says, the previous frame's
// fish chosen among the blobs) and measures the midlines and the tail beat. A frame is not
// measured when the fish is not whole in view (it touches the border), its segmentation is in
// doubt (no blob near the previous fish, the tail lost) or there is no fish; its reason is kept.
// Throws finverse::Error when no frame shows a fish or the fish fills the frame. `load(k)` gives
// frame index frames[k]'s grey image; `source` names the record in messages.
SingleViewResult track_single_view(const std::vector<long>& frames, const std::function<cv::Mat(long)>& load,
                                   const SingleViewOptions& options, const std::string& source);

// Per frame: frame, time, tip and tip lateral in px (and mm).
void write_single_view_csv(const std::filesystem::path& csv, const SingleViewResult& r, const SingleViewOptions& o);
// Everything in HDF5 with the run's configuration (provenance).
void write_single_view_h5(const std::filesystem::path& h5, const SingleViewResult& r, const SingleViewOptions& o,
                          const nlohmann::json& config, const std::vector<std::filesystem::path>& inputs);
// MJPG AVI: each frame with the midline, the tip and its track drawn over it; a frame not measured
// carries its reason.
void write_overlay_video(const std::filesystem::path& avi, const std::vector<long>& frames,
                         const std::function<cv::Mat(long)>& load, const SingleViewResult& r, double fps);

}  // namespace finverse::vision
