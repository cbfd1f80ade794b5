// Checkpoint encoding of the fit (DESIGN.md section 5.4: "a checkpoint every generation, and a
// restart that gives the uninterrupted result"). States are JSON documents written as CBOR, with
// every double stored as its 8 bytes (a JSON binary value), so that a restart continues from
// bitwise the same numbers, infinities included. Files are written to name.tmp and renamed, so
// an interrupted write never leaves a half checkpoint looking complete.
#pragma once

#include <filesystem>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "fit/fit_result.hpp"

namespace finverse::fit {

nlohmann::json pack_doubles(const double* data, std::size_t count);
nlohmann::json pack_vector(const Eigen::VectorXd& v);
std::vector<double> unpack_doubles(const nlohmann::json& j);
Eigen::VectorXd unpack_vector(const nlohmann::json& j);

nlohmann::json run_result_to_json(const RunResult& run);
RunResult run_result_from_json(const nlohmann::json& j);
nlohmann::json uncertainty_to_json(const Uncertainty& u);
Uncertainty uncertainty_from_json(const nlohmann::json& j);

// Atomic write (name.tmp, then rename). Throws InvalidInput naming the path on failure.
void write_checkpoint(const std::filesystem::path& path, const nlohmann::json& state);
// nullopt when the file does not exist; InvalidInput naming the path when it is unreadable.
std::optional<nlohmann::json> read_checkpoint(const std::filesystem::path& path);

}  // namespace finverse::fit
