// fin-track midline: flags and run (see midline_command.hpp).
#include "vision/midline_command.hpp"

#include <cstdio>
#include <vector>

#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "vision/camera.hpp"
#include "vision/frame_files.hpp"
#include "vision/tracker_flags.hpp"

namespace fs = std::filesystem;

namespace finverse::vision {

CLI::App* add_midline_command(CLI::App& app, MidlineCommand& c) {
  auto& so = c.options;
  auto* mid = app.add_subcommand("midline", "2-D single-view mode: midline, tail tip and tail-beat frequency, amplitude and "
                                            "body wavelength of the fish seen by one camera (no calibration)");
  mid->add_option("--frames", c.frames, "the camera's video file (AVI, MP4, MOV) or folder of numbered images")->required();
  mid->add_option("--out", c.out, "midline.h5: midlines, tips, tail beat (px and mm)")->required();
  mid->add_option("--csv", c.csv, "per-frame tail tip and its lateral excursion as CSV");
  mid->add_option("--overlay", c.overlay, "MJPG AVI of the frames with the midline and the tip's track drawn over them");
  mid->add_option("--fps", c.fps, "frame rate (1/s); default: the video's own, else " + std::to_string(int(so.fps)))
      ->check(finverse::cli::positive());
  mid->add_option("--mm-per-px", c.mm_per_px, "image scale (mm per px): results also in mm")
      ->check(finverse::cli::positive());
  mid->add_option("--stations", so.stations, "midline points, head to tail")->capture_default_str()->check(CLI::Range(3, 1000));
  mid->add_option("--region", c.region, "x0,y0,x1,y1: the rectangle (px) that holds the fish");
  mid->add_option("--min-contrast", so.segmentation.min_contrast, "segmentation: smallest darkening that counts as fish (levels)")
      ->capture_default_str();
  mid->add_option("--noise-floor", so.segmentation.noise_floor, "segmentation: the sensor noise is never taken below this (levels)")
      ->capture_default_str();
  mid->add_option("--background", c.background, "segmentation background: model, median or auto (as fin-track's)")
      ->check(CLI::IsMember({"model", "median", "auto"}))
      ->capture_default_str();
  return mid;
}

int run_midline_command(MidlineCommand& c, const CLI::App& app) {
  auto& so = c.options;
  so.segmentation.background = background_model(c.background);
  so.mm_per_px = c.mm_per_px;
  if (!c.region.empty()) {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    char tail = 0;
    if (std::sscanf(c.region.c_str(), "%d,%d,%d,%d%c", &x0, &y0, &x1, &y1, &tail) != 4 || x1 <= x0 || y1 <= y0)
      throw Error("--region: expected x0,y0,x1,y1 with x1 > x0 and y1 > y0 (px), got '" + c.region + "'");
    so.region = cv::Rect(x0, y0, x1 - x0, y1 - y0);
  }
  Camera one;
  one.name = "view";
  const auto files = list_frame_files(std::vector<std::string>{"view=" + c.frames}, {one}, {}, "--frames");
  if (c.fps) so.fps = *c.fps;
  else if (files.container_fps) so.fps = *files.container_fps;
  const auto load = [&](long k) {
    cv::Mat img = files.load(0, k);
    if (img.empty()) throw Error(c.frames + ": no frame " + std::to_string(k));
    return img;
  };
  const auto r = track_single_view(files.frames, load, so, c.frames);
  auto config = cli::effective_config(app);
  config["midline"]["fps"] = std::to_string(so.fps);
  std::vector<fs::path> inputs;
  if (fs::is_regular_file(c.frames)) inputs.push_back(c.frames);
  write_single_view_h5(c.out, r, so, config, inputs);
  if (!c.csv.empty()) write_single_view_csv(c.csv, r, so);
  if (!c.overlay.empty()) write_overlay_video(c.overlay, files.frames, load, r, so.fps);
  if (r.mostly_invalid()) {
    log::error(c.frames + ": " + std::to_string(r.invalid) + " of " + std::to_string(r.frames.size()) +
               " frames could not be measured, most often because " + r.commonest_reason +
               " (written, flagged: " + c.out.string() + ")");
    return kExitDifferent;
  }
  char line[256];
  std::snprintf(line, sizeof line, "tail beat %.4g Hz, amplitude %.4g px, body wavelength %.4g px over %d beats",
                r.beat.frequency_hz, r.beat.amplitude_px, r.beat.wavelength_px, r.beat.beats);
  log::info(line);
  if (c.mm_per_px) {
    std::snprintf(line, sizeof line, "amplitude %.4g mm, body wavelength %.4g mm", r.beat.amplitude_px * *c.mm_per_px,
                  r.beat.wavelength_px * *c.mm_per_px);
    log::info(line);
  }
  log::info("wrote " + c.out.string());
  return kExitOk;
}

}  // namespace finverse::vision
