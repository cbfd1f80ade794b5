// The layout of loop.h5 (schema finverse/loop, tools/core/CONTRACTS.md): fin-loop trace writes it
// (loop_files.hpp), fin-report reads it for its "Closing the loop" section. Header-only, on the
// stage-file machinery of tools/core alone, so a reader need not link the FEM behind the tracing.
// errors/* hold three model states in a fixed order: kInitial (the fit's values), kBase (the
// base refitted, before any effect) and kFinal (after the last accepted effect).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "core/stage_files.hpp"

namespace finverse::loop::io {

struct LoopFile {
  static constexpr const char* kSchema = "finverse/loop";
  static constexpr std::size_t kInitial = 0, kBase = 1, kFinal = 2;
  stage::Strings candidates, tried, parameter_names, names;
  NdArray<std::int32_t> accepted, held_out;
  NdArray<double> score, p_value, projected, magnitude, lower95, upper95;
  NdArray<double> bic_before, bic_after, held_before, held_after, te_before, te_after, values;
  // Optional (files from before the report section have none): per-node RMS residual maps and
  // the three states' errors.
  NdArray<double> node_rms_before, node_rms_after, step_node_rms_after;
  NdArray<double> state_trailing_edge, state_held_out, state_bic;
  std::optional<std::string> stop_reason, held_out_kind;
  std::optional<double> excursion;
  template <class V> void fields(V&& v) {
    v("candidates", candidates);
    v("steps/tried", tried);
    v("steps/accepted", accepted);
    v("steps/score", score);
    v("steps/p_value", p_value);
    v("steps/projected_fraction", projected);
    v("steps/parameter_names", parameter_names);
    v("steps/magnitude", magnitude);
    v("steps/lower95", lower95);
    v("steps/upper95", upper95);
    v("steps/bic_before", bic_before);
    v("steps/bic_after", bic_after);
    v("steps/held_out_before", held_before);
    v("steps/held_out_after", held_after);
    v("steps/trailing_edge_before", te_before);
    v("steps/trailing_edge_after", te_after);
    v("steps/node_rms_after", step_node_rms_after);
    v("parameters/names", names);
    v("parameters/values", values);
    v("held_out_frames", held_out);
    v("nodes/rms_before", node_rms_before);
    v("nodes/rms_after", node_rms_after);
    v("errors/trailing_edge", state_trailing_edge);
    v("errors/held_out", state_held_out);
    v("errors/bic", state_bic);
  }
  template <class A> void attributes(A&& a) {
    a("stop_reason", stop_reason);
    a("held_out_kind", held_out_kind);
    a("trailing_edge_excursion", excursion);
  }
};

}  // namespace finverse::loop::io
