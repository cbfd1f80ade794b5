// A record of synchronized frames, fin-track's input (issue 35, item 1: inputs as labs have
// them). Per calibrated view either a video file (video_clip.hpp; frames 0, 1, ...) or a folder
// of numbered images (any format cv::imread reads, any name with a number: frame_0001.png,
// img12.jpg, 000003.png; the frame index is the last number in the name, so the natural order).
// Given as one folder holding <view>/ (images) or <view>.avi|.mp4|.mov per view (the layout
// fin-synth writes), or view by view: "side=clip_side.avi", "back=frames/back". The calibration
// defines the views: a folder or name of a view it does not know is an error; a view without
// frames, or an image missing in some views, is warned about (the tracker fits the frames with
// the views that are there). Videos of different frame counts or frame rates are an error.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "vision/camera.hpp"
#include "vision/video_clip.hpp"

namespace finverse::vision {

struct FrameFiles {
  std::vector<long> frames;                                  // indices in any view, ascending
  std::vector<std::map<long, std::filesystem::path>> files;  // per camera: frame index -> image file
  std::vector<std::shared_ptr<const VideoClip>> clips;       // per camera: its video (null: images)
  std::optional<double> container_fps;                       // the videos' common frame rate

  // The grey frame `frame` of view `view`, or an empty Mat where the view has none. Throws
  // finverse::Error naming the file when it cannot be read.
  cv::Mat load(std::size_t view, long frame) const;
  // The number of frames view `view` has.
  std::size_t count(std::size_t view) const;
};

// The frame index of an image file name: its last number; none when the name has no digit.
std::optional<long> frame_number(const std::filesystem::path& file);

// The frames of every camera's view as `spec` gives them (one folder, or view=path items), but
// for the views in `ignore`. `calibration` names the cameras' file in messages. Throws
// finverse::Error (one line, naming the file or flag) on a view the cameras do not define, no
// frames at all, two images with the same number, a video that cannot be decoded, or videos
// of different frame counts or frame rates.
FrameFiles list_frame_files(const std::vector<std::string>& spec, const std::vector<Camera>& cameras,
                            const std::vector<std::string>& ignore, const std::string& calibration);
FrameFiles list_frame_files(const std::filesystem::path& dir, const std::vector<Camera>& cameras,
                            const std::vector<std::string>& ignore, const std::string& calibration);

}  // namespace finverse::vision
