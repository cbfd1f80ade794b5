// fin-loop's stage files (tools/core/CONTRACTS.md): residual.h5 (finverse/residual: the residual
// and its decomposition) and loop.h5 (finverse/loop: the effect tracing's trail), each checked
// against its contract and written atomically, and the readers that turn motion.h5 / fsi.h5
// into the sampled motions the analysis compares.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/provenance.hpp"
#include "core/stage_files.hpp"
#include "loop/effect_tracing.hpp"
#include "loop/residual_analysis.hpp"

namespace finverse::loop::io {

SampledMotion sampled_motion(const NdArray<double>& time, const NdArray<double>& points, const std::string& source);
Eigen::MatrixXd rest_positions(const stage::Mesh& mesh);
// Each ray's tip (the node at its largest arc-length fraction, mesh.h5 /beams/s); empty without rays.
std::vector<int> ray_tip_nodes(const stage::Mesh& mesh);

void write_residual(const std::filesystem::path& path, const ResidualAnalysis& analysis,
                    std::optional<double> period, const std::string& prediction_kind, const Provenance& provenance);

struct TraceRecord {
  TraceResult result;
  std::vector<std::string> candidates;
  HeldOutSplit split;
  double excursion = 0;  // m
};
void write_loop(const std::filesystem::path& path, const TraceRecord& record, const Provenance& provenance);
// The digest: per step the ranking, the effect tried, magnitude and interval, before/after.
nlohmann::json trace_summary_json(const TraceRecord& record);

}  // namespace finverse::loop::io
