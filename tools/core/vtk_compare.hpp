// Comparison of VTK XML files (.vtp .vtu .vtr .vti .vts) read with VTK's own readers: point
// coordinates, grid coordinates, connectivity and cell types, and every point/cell data array by
// name, under the same tolerances as HDF5 datasets (objects are named "Points",
// "PointData/<name>", "CellData/<name>", "Cells").
#pragma once

#include <filesystem>
#include <vector>

#include "core/array_compare.hpp"
#include "core/tolerances.hpp"

namespace finverse {

std::vector<Comparison> compare_vtk(const std::filesystem::path& reference, const std::filesystem::path& candidate,
                                    const Tolerances& tolerances, const std::string& prefix = "");

bool is_vtk_xml(const std::filesystem::path& p);

}  // namespace finverse
