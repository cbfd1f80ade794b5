// fin-track's validation and benchmark summaries (issue 5 criteria; core/summary.hpp format): a
// tracked record scored against the virtual experiment's truth (vertex errors, silhouette IoU of
// the fitted against the true surface in every view, trailing-edge amplitude), and its speed.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/nd_array.hpp"
#include "core/stage_files.hpp"
#include "core/summary.hpp"
#include "vision/tracker.hpp"

namespace finverse::vision {

// Another reconstruction of the same frames, scored beside the tracked one (reported only).
struct OtherReconstruction {
  std::string label, file;  // metric prefix; the file it came from (messages)
  NdArray<double> points;   // [nf,nv,3]
};

// The validation summary of `result` (tracked with `model`, TrackResult's truth scores filled)
// against truth.h5 (`truth_name` in messages); logs the vertex errors. Throws finverse::Error when
// the truth does not hold the tracked frames on this template or another reconstruction's shape differs.
Summary tracking_validation_summary(const TrackResult& result, const TrackingModel& model, const stage::Truth& truth,
                                    const std::string& truth_name, const std::vector<OtherReconstruction>& others = {});

// The benchmark summary: seconds per frame set after the first against the goal, and the
// fin-mesh wall time (`mesh_wall_time`, s) against its own when given.
Summary tracking_bench_summary(const TrackResult& result, int image_width, std::optional<double> mesh_wall_time);

}  // namespace finverse::vision
