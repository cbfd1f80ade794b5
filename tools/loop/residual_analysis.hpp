// Residual analysis (issue 34, DESIGN.md section 5.6), the whole of `fin-loop residual`: the
// residual field (residual_field.hpp), its cycle mean and harmonics k = 1..3 of the beat
// frequency (harmonic_analysis.hpp), its POD modes (residual_modes.hpp) with where each sits
// (fin_regions.hpp) and its phase against the root motion (phase_character.hpp), and the
// trailing-edge error (trailing_edge_error.hpp). What cannot be trusted (no period, frames over
// less than one period, an ill-conditioned harmonic fit) is listed in `flags`, never hidden.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "loop/fin_regions.hpp"
#include "loop/harmonic_analysis.hpp"
#include "loop/phase_character.hpp"
#include "loop/residual_field.hpp"
#include "loop/residual_modes.hpp"
#include "loop/trailing_edge_error.hpp"

namespace finverse::loop {

struct ResidualAnalysisOptions {
  std::optional<double> period;  // beat period T [s]; none: no harmonics
  int harmonics = 3;
  int modes = 5;
  Eigen::VectorXd node_weights;  // empty: all 1
  std::vector<int> trailing_edge_nodes;  // empty: nodes with xi >= 0.95
  double max_condition = 1e6;  // harmonic fits worse conditioned than this are flagged
};

struct ResidualAnalysis {
  ResidualField field;
  FinRegions regions;
  std::optional<Harmonics> harmonics;
  ResidualModes modes;
  std::vector<std::array<double, kRegionCount>> mode_regions;  // [mode]
  std::vector<PhaseCharacter> mode_phase;                      // [mode]
  RootSignal root;
  TrailingEdgeError trailing_edge;
  std::vector<int> trailing_edge_nodes;
  double rms = 0;  // RMS of |r| over nodes with weight > 0 (all nodes without weights) and frames
  std::vector<std::string> flags;
};

// rest: [nv, 3] mesh rest positions. Throws InvalidInput (residual_field.hpp's refusals among them).
ResidualAnalysis analyse_residual(const SampledMotion& prediction, const SampledMotion& reconstruction,
                                  const Eigen::MatrixXd& rest, const std::vector<int>& root_nodes,
                                  const ResidualAnalysisOptions& options);

// The digest for --summary: RMS, trailing-edge error, per mode energy, dominant region, character.
nlohmann::json residual_summary_json(const ResidualAnalysis& a);

}  // namespace finverse::loop
