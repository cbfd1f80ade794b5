// ParaView-readable output (DESIGN.md section 3, "Viewing") written through VTK's own XML
// writers, so ParaView 5.11 reads it by construction (a test reads every kind back with VTK's
// readers):
//   - triangle surfaces over time:            <stem>.pvd + <stem>/<stem>_NNNNNN.vtp
//   - unstructured meshes (shells + beams):   .vtu
//   - fields on a stretched Cartesian grid:   <stem>.pvd + <stem>/<stem>_NNNNNN.vtr (cell data)
// Every file is written to a temporary and renamed; the .pvd is written last, so it never names
// a frame that is not complete.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "core/nd_array.hpp"

namespace finverse::vtkio {

// Named data on points or cells: shape [n] (scalar) or [n, k] (k components, e.g. 3 = vector).
struct NamedArray {
  std::string name;
  NdArray<double> values;
};

struct SurfaceFrame {
  NdArray<double> points;  // [nv,3]
  std::vector<NamedArray> point_data;
  std::vector<NamedArray> cell_data;
};

// Triangle surface with fixed connectivity moving over time.
void write_surface_series(const std::filesystem::path& pvd, const std::vector<double>& times,
                          const NdArray<std::int32_t>& triangles, const std::vector<SurfaceFrame>& frames);

// One unstructured mesh with triangles and two-node lines (beams) and per-cell/per-point data.
// Cell data arrays are ordered triangles first, then lines.
void write_unstructured(const std::filesystem::path& vtu, const NdArray<double>& points,
                        const NdArray<std::int32_t>& triangles, const NdArray<std::int32_t>& lines,
                        const std::vector<NamedArray>& point_data, const std::vector<NamedArray>& cell_data);

// A stretched Cartesian grid given by its face coordinates (nx+1, ny+1, nz+1; nz+1 = 1 in 2-D)
// with cell-centred data per frame ([ncells] or [ncells, k], x fastest).
struct GridFrame {
  std::vector<NamedArray> cell_data;
};
void write_grid_series(const std::filesystem::path& pvd, const std::vector<double>& times,
                       const std::vector<double>& x_faces, const std::vector<double>& y_faces,
                       const std::vector<double>& z_faces, const std::vector<GridFrame>& frames);

// The same series written one frame at a time during a run (each add() writes its .vtr, then
// rewrites the .pvd), so a long run's snapshots never have to sit in memory together.
class GridSeries {
 public:
  GridSeries(std::filesystem::path pvd, std::vector<double> x_faces, std::vector<double> y_faces,
             std::vector<double> z_faces);
  // Continue an existing collection after a restart: keep its frames up to time t_max (later ones
  // belong to the interrupted run and are overwritten). No file: start empty.
  void resume(double t_max);
  void add(double t, const GridFrame& frame);
  std::size_t size() const { return entries_.size(); }

 private:
  std::filesystem::path pvd_;
  std::vector<double> x_, y_, z_;
  std::vector<std::pair<double, std::string>> entries_;
};

// The .pvd collection itself: (time, file relative to the .pvd) pairs.
void write_pvd(const std::filesystem::path& pvd, const std::vector<std::pair<double, std::string>>& entries);

}  // namespace finverse::vtkio
