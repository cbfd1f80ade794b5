// Frame files of a record (see frame_files.hpp).
#include "vision/frame_files.hpp"

#include <algorithm>
#include <cctype>
#include <opencv2/imgcodecs.hpp>
#include <set>

#include "core/error.hpp"
#include "core/log.hpp"

namespace fs = std::filesystem;

namespace finverse::vision {
namespace {

// frame index -> file, in one view's folder.
std::map<long, fs::path> list_frames(const fs::path& dir) {
  std::map<long, fs::path> out;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    const auto stem = e.path().stem().string();
    if (stem.empty() ||
        !std::all_of(stem.begin(), stem.end(), [](char ch) { return std::isdigit(static_cast<unsigned char>(ch)); }))
      continue;
    out[std::stol(stem)] = e.path();
  }
  return out;
}

}  // namespace

cv::Mat FrameFiles::load(std::size_t view, long frame) const {
  const auto it = files[view].find(frame);
  if (it == files[view].end()) return {};
  cv::Mat img = cv::imread(it->second.string(), cv::IMREAD_GRAYSCALE);
  if (img.empty()) throw Error(it->second.string() + ": unreadable image");
  return img;
}

FrameFiles list_frame_files(const fs::path& dir, const std::vector<Camera>& cameras,
                            const std::vector<std::string>& ignore, const std::string& calibration) {
  std::set<std::string> known;
  for (const auto& c : cameras) known.insert(c.name);
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_directory() && !known.count(e.path().filename().string()))
      throw Error(calibration + ": calibration inconsistent with the frames: " + dir.string() + " has view '" +
                  e.path().filename().string() + "' but the camera file defines " + std::to_string(cameras.size()) +
                  " view(s)");
  const std::size_t nview = cameras.size();
  FrameFiles out;
  out.files.resize(nview);
  std::set<long> indices;
  for (std::size_t v = 0; v < nview; ++v) {
    const auto& name = cameras[v].name;
    const auto sub = dir / name;
    if (std::find(ignore.begin(), ignore.end(), name) != ignore.end()) {
      log::info("view '" + name + "' left out (--ignore-view)");
      continue;
    }
    if (!fs::is_directory(sub)) {
      log::warn("view '" + name + "': no frames directory " + sub.string() + "; fitting without this view");
      continue;
    }
    out.files[v] = list_frames(sub);
    if (out.files[v].empty())
      log::warn("view '" + name + "': no frames in " + sub.string() + "; fitting without this view");
    for (const auto& [k, p] : out.files[v]) indices.insert(k);
  }
  if (indices.empty())
    throw Error(dir.string() + ": no frames (expected <view>/NNNNNN.png for the views in " + calibration + ")");
  out.frames.assign(indices.begin(), indices.end());
  const auto& frames = out.frames;
  for (std::size_t i = 1; i < frames.size(); ++i)
    if (frames[i] != frames[i - 1] + 1)
      log::warn("frames " + std::to_string(frames[i - 1] + 1) + ".." + std::to_string(frames[i] - 1) +
                " are missing in every view (dropped); fitting the frames that are there");
  for (std::size_t v = 0; v < nview; ++v)
    if (!out.files[v].empty() && out.files[v].size() < frames.size())
      log::warn("view '" + cameras[v].name + "': " + std::to_string(frames.size() - out.files[v].size()) +
                " frame(s) missing; those frames are fitted from the other views");
  return out;
}

}  // namespace finverse::vision
