// Cameras from DLTdv's 11-coefficient DLT calibration (Hedrick 2008, Bioinsp. Biomim. 3:034001;
// Abdel-Aziz & Karara's DLT): u = (L1 X + L2 Y + L3 Z + L4) / (L9 X + L10 Y + L11 Z + 1), v the same
// with L5..L8. The 3x4 matrix is split into K [R | t] by an RQ decomposition (Hartley & Zisserman
// section 6.2.4). DLTdv measures v from the image's bottom edge (origin lower left), OpenCV from
// the top: v_opencv = height - v_dlt. A DLT has no lens distortion: the cameras get none.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "vision/camera.hpp"

namespace finverse::vision {

using DltCoefficients = std::array<double, 11>;

enum class DltOrigin { bottom_left, top_left };

// One camera from its 11 coefficients (world units as in the file, scaled by `metres_per_unit`).
// Throws finverse::Error naming `where` when the matrix is degenerate.
Camera camera_from_dlt(const DltCoefficients& L, const std::string& name, int width, int height, DltOrigin origin,
                       double metres_per_unit, const std::string& where);

// The 11 coefficients of a camera without distortion (the inverse of camera_from_dlt).
DltCoefficients dlt_from_camera(const Camera& cam, DltOrigin origin, double metres_per_unit);

// DLTdv's coefficient file (*_DLTcoefs.csv): 11 rows, one column per camera, comma separated.
std::vector<DltCoefficients> read_dlt_file(const std::filesystem::path& csv);
void write_dlt_file(const std::filesystem::path& csv, const std::vector<DltCoefficients>& cameras);

}  // namespace finverse::vision
