// fin-track's flags of the 3-D tracker (DESIGN.md section 5.5): the fit (LM, priors, ray and
// coverage terms), the segmentation (contrast, noise floor, background), the cut of the caudal fin
// from the body, the user's fin rectangles and the fit checks, and their translation into
// TrackerOptions once the calibration is read. The defaults are TrackerOptions' own
// (tracker.hpp; docs/studies/tracking_fit_defaults.md).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "vision/camera.hpp"
#include "vision/tracker.hpp"

namespace finverse::vision {

struct TrackerFlags {
  TrackerOptions options;
  std::string fin_cut = "none";     // none, peduncle, root-plane
  std::string background = "auto";  // model, median, auto
  std::vector<std::string> fin_regions;  // view=x0,y0,x1,y1
};

void add_tracker_flags(CLI::App& app, TrackerFlags& flags);

// The flags' strings into `flags.options`. Throws finverse::Error naming the flag for a
// malformed --fin-region or one whose view is not in `cameras` (read from `cameras_file`).
void apply_tracker_flags(TrackerFlags& flags, const std::vector<Camera>& cameras, const std::string& cameras_file);

// "model", "median" or "auto" (the flags' check) as the segmentation's background.
BackgroundModel background_model(const std::string& name);

}  // namespace finverse::vision
