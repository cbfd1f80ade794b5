// fin-track's subcommand midline, the 2-D single-view mode (issue 35, item 4; single_view.hpp):
// its flags and its run, from the clip to midline.h5, the tip CSV and the overlay video.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "vision/single_view.hpp"

namespace finverse::vision {

struct MidlineCommand {
  SingleViewOptions options;
  std::string frames, region, background = "auto";
  std::filesystem::path out, csv, overlay;
  std::optional<double> fps, mm_per_px;
};

// Adds the subcommand "midline" to `app`, its flags bound to `command`.
CLI::App* add_midline_command(CLI::App& app, MidlineCommand& command);

// Runs it: reads the frames, tracks the midlines and writes the files. Returns kExitOk, or
// kExitDifferent when most frames could not be measured (the files written, flagged, and one
// error line with the count and the commonest reason). Throws finverse::Error naming the flag or
// file for bad input, a clip without a fish and a fish that fills the frame.
int run_midline_command(MidlineCommand& command, const CLI::App& app);

}  // namespace finverse::vision
