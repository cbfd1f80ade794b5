// The footage_calibration validation's scores (issue 35, Validation): a rig calibrated from a
// simulated checkerboard recording against the rig that recorded it (reprojection RMS <= 0.2 px,
// camera centre within 0.5 mm, orientation within 0.1 deg), and the same rig written as DLTdv
// coefficients and as an Anipose calibration.toml and read back through the importers (the DLT
// without lens distortion, which it cannot represent).
#pragma once

#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/summary.hpp"
#include "vision/camera.hpp"

namespace finverse::vision {

// `report`: fin-calibrate checkerboard's report.json. `work_dir` receives the DLT and TOML files.
Summary calibration_validation_summary(const std::vector<Camera>& truth, const std::vector<Camera>& calibrated,
                                       const nlohmann::json& report, const std::filesystem::path& work_dir);

}  // namespace finverse::vision
