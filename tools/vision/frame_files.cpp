// Frames of a record from image folders or video files (see frame_files.hpp).
#include "vision/frame_files.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <set>

#include "core/error.hpp"
#include "core/log.hpp"
#include "vision/image_file.hpp"

namespace fs = std::filesystem;

namespace finverse::vision {
namespace {

bool is_image_file(const fs::path& file) {
  auto ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  static const std::array<const char*, 10> known{".png", ".jpg", ".jpeg", ".tif", ".tiff", ".bmp", ".pgm", ".ppm", ".pbm", ".webp"};
  return std::any_of(known.begin(), known.end(), [&](const char* e) { return ext == e; });
}

// frame index -> file, in one view's folder.
std::map<long, fs::path> list_images(const fs::path& dir) {
  std::map<long, fs::path> out;
  std::size_t unnumbered = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (!e.is_regular_file() || !is_image_file(e.path())) continue;
    const auto k = frame_number(e.path());
    if (!k) {
      ++unnumbered;
      continue;
    }
    const auto [it, fresh] = out.emplace(*k, e.path());
    if (!fresh)
      throw Error(dir.string() + ": images " + it->second.filename().string() + " and " + e.path().filename().string() +
                  " both have frame number " + std::to_string(*k) + " (expected one image per number)");
  }
  if (unnumbered > 0)
    log::warn(dir.string() + ": " + std::to_string(unnumbered) + " image(s) without a frame number in the name skipped");
  return out;
}

struct ViewSource {
  fs::path path;  // folder of images or video file; empty: none given
};

}  // namespace

std::optional<long> frame_number(const fs::path& file) {
  const auto stem = file.stem().string();
  auto end = stem.size();
  while (end > 0 && !std::isdigit(static_cast<unsigned char>(stem[end - 1]))) --end;
  if (end == 0) return std::nullopt;
  auto begin = end;
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(stem[begin - 1]))) --begin;
  const auto digits = stem.substr(begin, end - begin);
  if (digits.size() > 15) return std::nullopt;
  return std::stol(digits);
}

cv::Mat FrameFiles::load(std::size_t view, long frame) const {
  if (clips[view]) return frame >= 0 && frame < clips[view]->frames() ? clips[view]->grey(frame) : cv::Mat();
  const auto it = files[view].find(frame);
  if (it == files[view].end()) return {};
  return read_image(it->second, cv::IMREAD_GRAYSCALE);
}

std::size_t FrameFiles::count(std::size_t view) const {
  return clips[view] ? static_cast<std::size_t>(clips[view]->frames()) : files[view].size();
}

FrameFiles list_frame_files(const std::vector<std::string>& spec, const std::vector<Camera>& cameras,
                            const std::vector<std::string>& ignore, const std::string& calibration) {
  const std::size_t nview = cameras.size();
  auto view_index = [&](const std::string& name) {
    for (std::size_t v = 0; v < nview; ++v)
      if (cameras[v].name == name) return v;
    return nview;
  };
  auto defined = [&] {
    std::string s;
    for (const auto& c : cameras) s += (s.empty() ? "" : ", ") + c.name;
    return s;
  };
  if (spec.empty()) throw Error("--frames: expected a folder or view=path items");
  std::vector<ViewSource> src(nview);
  const bool per_view = std::any_of(spec.begin(), spec.end(), [](const auto& s) { return s.find('=') != std::string::npos; });
  std::string where;  // names the record in messages
  if (per_view) {
    for (const auto& item : spec) {
      const auto eq = item.find('=');
      if (eq == std::string::npos || eq == 0 || eq + 1 == item.size())
        throw Error("--frames: expected view=path items (a video file or a folder of images), got '" + item + "'");
      const auto name = item.substr(0, eq);
      const auto v = view_index(name);
      if (v == nview)
        throw Error("--frames: view '" + name + "' is not in " + calibration + " (it defines " + defined() + ")");
      if (!src[v].path.empty()) throw Error("--frames: view '" + name + "' given twice");
      src[v].path = item.substr(eq + 1);
      if (!fs::exists(src[v].path)) throw Error("--frames: " + src[v].path.string() + ": no such file or folder");
    }
    where = "--frames";
  } else {
    if (spec.size() != 1) throw Error("--frames: expected one folder, or view=path items");
    const fs::path dir = spec[0];
    if (!fs::is_directory(dir)) {
      if (fs::is_regular_file(dir)) {
        const auto stem = dir.stem().string();
        throw Error("--frames: " + dir.string() + " is a file; name its view: --frames " +
                    (view_index(stem) < nview ? stem : cameras[0].name) + "=" + dir.string() + ",... (views: " + defined() + ")");
      }
      throw Error("--frames: " + dir.string() + ": no such folder");
    }
    for (const auto& e : fs::directory_iterator(dir)) {
      const auto& p = e.path();
      const bool view_dir = e.is_directory(), video = e.is_regular_file() && is_video_file(p);
      if (!view_dir && !video) continue;
      const auto name = view_dir ? p.filename().string() : p.stem().string();
      const auto v = view_index(name);
      if (v == nview)
        throw Error(calibration + ": calibration inconsistent with the frames: " + dir.string() + " has view '" + name +
                    "' but the camera file defines " + std::to_string(nview) + " view(s) (" + defined() + ")");
      if (!src[v].path.empty()) throw Error(dir.string() + ": view '" + name + "' has both a folder and a video");
      src[v].path = p;
    }
    where = dir.string();
  }

  FrameFiles out;
  out.files.resize(nview);
  out.clips.resize(nview);
  std::set<long> indices;
  const VideoClip* first_clip = nullptr;
  for (std::size_t v = 0; v < nview; ++v) {
    const auto& name = cameras[v].name;
    if (std::find(ignore.begin(), ignore.end(), name) != ignore.end()) {
      log::info("view '" + name + "' left out (--ignore-view)");
      continue;
    }
    const auto& path = src[v].path;
    if (path.empty()) {
      log::warn("view '" + name + "': no frames in " + where + "; fitting without this view");
      continue;
    }
    if (fs::is_directory(path)) {
      out.files[v] = list_images(path);
      if (out.files[v].empty()) log::warn("view '" + name + "': no numbered images in " + path.string() + "; fitting without this view");
      for (const auto& [k, p] : out.files[v]) indices.insert(k);
      continue;
    }
    auto clip = std::make_shared<const VideoClip>(path);
    if (first_clip) {
      if (clip->frames() != first_clip->frames())
        throw Error(path.string() + ": " + std::to_string(clip->frames()) + " frames, but " + first_clip->path().string() +
                    " has " + std::to_string(first_clip->frames()) + " (expected synchronized clips of equal length)");
      if (std::abs(clip->fps() - first_clip->fps()) > 1e-3 * std::max(clip->fps(), first_clip->fps()))
        throw Error(path.string() + ": " + std::to_string(clip->fps()) + " fps, but " + first_clip->path().string() + " has " +
                    std::to_string(first_clip->fps()) + " (expected synchronized clips of one frame rate)");
    }
    if (!first_clip) {
      first_clip = clip.get();
      if (clip->fps() > 0) out.container_fps = clip->fps();
    }
    for (long k = 0; k < clip->frames(); ++k) indices.insert(k);
    out.clips[v] = std::move(clip);
  }
  if (indices.empty())
    throw Error(where + ": no frames (expected <view>/ folders of numbered images or <view>.avi|.mp4|.mov for the views in " +
                calibration + ")");
  out.frames.assign(indices.begin(), indices.end());
  const auto& frames = out.frames;
  for (std::size_t i = 1; i < frames.size(); ++i)
    if (frames[i] != frames[i - 1] + 1)
      log::warn("frames " + std::to_string(frames[i - 1] + 1) + ".." + std::to_string(frames[i] - 1) +
                " are missing in every view (dropped); fitting the frames that are there");
  for (std::size_t v = 0; v < nview; ++v) {
    const auto n = out.count(v);
    if (n > 0 && n < frames.size())
      log::warn("view '" + cameras[v].name + "': " + std::to_string(frames.size() - n) +
                " frame(s) missing; those frames are fitted from the other views");
  }
  return out;
}

FrameFiles list_frame_files(const fs::path& dir, const std::vector<Camera>& cameras, const std::vector<std::string>& ignore,
                            const std::string& calibration) {
  return list_frame_files(std::vector<std::string>{dir.string()}, cameras, ignore, calibration);
}

}  // namespace finverse::vision
