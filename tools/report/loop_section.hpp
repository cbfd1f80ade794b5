// The report's "Closing the loop" section (issue 34 "Deliver": a report section): from loop.h5
// (fin-loop trace) and the mesh it ran on, the per-node RMS residual before any effect (the
// refitted base) and after the last accepted one, for planform maps on one colour scale; the
// decision trail, one row per step (every candidate's score and p value, the one tried, its
// fitted magnitude with 95 % interval, trailing-edge RMS, BIC and held-out error before and
// after, the verdict); and the before/after error with its factor as info scores. The report
// draws and grades nothing of its own here: the numbers are the tracer's.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/stage_files.hpp"
#include "loop/io/loop_file.hpp"
#include "report/score.hpp"

namespace finverse::report {

struct LoopSection {
  std::vector<Score> scores;
  nlohmann::json figure;  // figures.json "loop": points, triangles, maps, trail, errors
};

// Throws finverse::Error (naming `source`) when the loop's per-node maps are not on the mesh's
// nodes or its step arrays disagree in length.
LoopSection loop_section(const loop::io::LoopFile& loop, const stage::Mesh& mesh, const std::string& source);

}  // namespace finverse::report
