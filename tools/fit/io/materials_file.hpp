// materials.h5 (schema finverse/materials, tools/core/CONTRACTS.md): the fit result as the stage
// file fin-fit writes and fin-fsi / fin-report read. Runs of different lengths are padded with
// NaN after their last generation. Wall times stay out (byte-identical files for the same seed
// and threads); fit_summary_json carries them.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

#include "core/provenance.hpp"
#include "core/stage_files.hpp"
#include "fit/fit_result.hpp"

namespace finverse::fit::io {

stage::Materials to_stage(const FitResult& result);
// Checks against the contract, then writes atomically (nothing is left on failure).
void write_materials(const std::filesystem::path& path, const FitResult& result, const Provenance& provenance);

// The human-facing digest: per parameter best, interval, verdict, truth error when known; per
// run objective, generations, evaluations and wall time; totals.
nlohmann::json fit_summary_json(const FitResult& result);

}  // namespace finverse::fit::io
