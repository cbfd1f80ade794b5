// A record of synchronized frames on disk, fin-track's input: <dir>/<view>/NNNNNN.png (any format
// cv::imread reads), NNNNNN the frame index, one folder per calibrated view. The calibration
// defines the views: a folder of a view it does not know is an error; a view without a folder or
// frames, or a frame missing in some views, is warned about (the tracker fits the frames with the
// views that are there).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "vision/camera.hpp"

namespace finverse::vision {

struct FrameFiles {
  std::vector<long> frames;                                  // indices in any view, ascending
  std::vector<std::map<long, std::filesystem::path>> files;  // per camera: frame index -> file

  // The grey frame `frame` of view `view`, or an empty Mat where the view has none. Throws
  // finverse::Error naming the file when it cannot be read.
  cv::Mat load(std::size_t view, long frame) const;
};

// The frames of every camera's view under `dir`, but for the views in `ignore`. `calibration`
// names the cameras' file in messages. Throws finverse::Error when `dir` holds a view the cameras
// do not define or no frames at all.
FrameFiles list_frame_files(const std::filesystem::path& dir, const std::vector<Camera>& cameras,
                            const std::vector<std::string>& ignore, const std::string& calibration);

}  // namespace finverse::vision
