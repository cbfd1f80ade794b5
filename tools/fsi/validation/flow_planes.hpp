// The flow's velocity on planes z = const (the Hessenthaler flap's report, issue 49 deliverable 5:
// the outlet pipe's cross-sections 10 and 30 mm above the clamp, where the MRI measured the flow).
// Sampled at the grid's cell centres in x and y, linearly between the two cell layers around z;
// NaN where either layer's cell is not fluid (the walls, the solid outside the pipes).
// File: flow_planes.h5 with one group per plane, /z_<mm>mm/{x, y, u, v, w} (x [nx], y [ny] [m];
// u, v, w [ny, nx] [m/s]) and the plane's z as an attribute.
#pragma once

#include <filesystem>
#include <vector>

#include "cfd/flow/flow_solver.hpp"

namespace finverse::fsi::validation {

struct FlowPlane {
  double z = 0;                 // [m]
  std::vector<double> x, y;     // cell centres [m]
  std::vector<double> u, v, w;  // [ny * nx], row j holds y[j] [m/s]
};

// Throws finverse::Error when z lies outside the grid's first and last cell centres.
FlowPlane sample_flow_plane(const cfd::FlowSolver& flow, double z);

// Writes the planes (atomically: a temporary renamed at the end).
void write_flow_planes(const std::filesystem::path& path, const std::vector<FlowPlane>& planes);

}  // namespace finverse::fsi::validation
