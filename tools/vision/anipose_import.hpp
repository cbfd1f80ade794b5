// Cameras from Anipose's calibration.toml (aniposelib CameraGroup.dump): one [cam_N] table per
// camera with name, size = [width, height], matrix (3x3), distortions (k1 k2 p1 p2 k3), rotation
// (Rodrigues vector) and translation, both world -> camera in OpenCV's convention, lengths in the
// unit of the board's square (millimetres in Anipose's examples). Read by a small reader of the
// TOML subset that file uses (tables, strings, numbers, booleans, nested arrays of numbers): a
// full TOML library is not a Debian package the project already builds with, and the layout is
// fixed. Fisheye cameras (Anipose's `fisheye = true`) are refused: cameras.yml has no such model.
#pragma once

#include <filesystem>
#include <vector>

#include "vision/camera.hpp"

namespace finverse::vision {

// Throws finverse::Error naming the file and the table or key at fault.
std::vector<Camera> read_anipose_calibration(const std::filesystem::path& toml, double metres_per_unit);
void write_anipose_calibration(const std::filesystem::path& toml, const std::vector<Camera>& cameras, double metres_per_unit);

}  // namespace finverse::vision
