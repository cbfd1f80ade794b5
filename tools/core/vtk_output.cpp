// VTK XML writers (see vtk_output.hpp). Appended raw binary with zlib compression: compact,
// fast for ParaView, and deterministic (no timestamps in the XML formats).
#include "core/vtk_output.hpp"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkRectilinearGrid.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLRectilinearGridWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>
#include <vtkZLibDataCompressor.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace finverse::vtkio {
namespace {

vtkNew<vtkDoubleArray> to_vtk(const NamedArray& a, std::size_t expected_tuples, const std::string& where) {
  const std::size_t n = a.values.shape.empty() ? 0 : a.values.shape[0];
  const std::size_t k = a.values.rank() == 2 ? a.values.shape[1] : 1;
  if (a.values.rank() < 1 || a.values.rank() > 2 || n != expected_tuples)
    throw Error(where + ": array '" + a.name + "' has shape " + shape_string(a.values.shape) + ", expected [" +
                std::to_string(expected_tuples) + "] or [" + std::to_string(expected_tuples) + ",k]");
  vtkNew<vtkDoubleArray> v;
  v->SetName(a.name.c_str());
  v->SetNumberOfComponents(static_cast<int>(k));
  v->SetNumberOfTuples(static_cast<vtkIdType>(n));
  std::copy(a.values.data.begin(), a.values.data.end(), v->GetPointer(0));
  return v;
}

vtkNew<vtkPoints> to_points(const NdArray<double>& p, const std::string& where) {
  if (p.rank() != 2 || p.shape[1] != 3) throw Error(where + ": points have shape " + shape_string(p.shape) + ", expected [n,3]");
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->SetNumberOfPoints(static_cast<vtkIdType>(p.shape[0]));
  for (std::size_t i = 0; i < p.shape[0]; ++i) pts->SetPoint(static_cast<vtkIdType>(i), p(i, 0), p(i, 1), p(i, 2));
  return pts;
}

// Connectivity must be [n, per_cell] with indices inside the point range.
void check_cells(const NdArray<std::int32_t>& c, std::size_t per_cell, std::size_t npoints, const std::string& where) {
  if (c.size() == 0) return;
  if (c.rank() != 2 || c.shape[1] != per_cell)
    throw Error(where + ": connectivity has shape " + shape_string(c.shape) + ", expected [n," + std::to_string(per_cell) + "]");
  for (std::size_t i = 0; i < c.size(); ++i)
    if (c.data[i] < 0 || static_cast<std::size_t>(c.data[i]) >= npoints)
      throw Error(where + ": cell " + std::to_string(i / per_cell) + " refers to point " + std::to_string(c.data[i]) +
                  " of " + std::to_string(npoints));
}

// Inserts the cells of `c` (already checked) into any VTK dataset with InsertNextCell.
template <class Grid>
void insert_cells(Grid* grid, const NdArray<std::int32_t>& c, std::size_t per_cell, int vtk_type) {
  if (c.size() == 0) return;
  std::vector<vtkIdType> ids(per_cell);
  for (std::size_t e = 0; e < c.shape[0]; ++e) {
    for (std::size_t j = 0; j < per_cell; ++j) ids[j] = c(e, j);
    grid->InsertNextCell(vtk_type, static_cast<vtkIdType>(per_cell), ids.data());
  }
}

template <class Writer, class Data>
void write_xml(Data* data, const std::filesystem::path& path) {
  std::error_code ec;
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
  const auto tmp = temporary_for(path);
  vtkNew<Writer> w;
  vtkNew<vtkZLibDataCompressor> zlib;
  w->SetInputData(data);
  w->SetFileName(tmp.c_str());
  w->SetDataModeToAppended();
  w->EncodeAppendedDataOff();
  w->SetCompressor(zlib);
  if (w->Write() != 1) {
    std::filesystem::remove(tmp, ec);
    throw Error(path.string() + ": VTK writer failed");
  }
  commit_temporary(tmp, path);
}

std::string frame_name(const std::filesystem::path& pvd, std::size_t i, const char* ext) {
  char num[16];
  std::snprintf(num, sizeof num, "_%06zu", i);
  const auto stem = pvd.stem().string();
  return stem + "/" + stem + num + ext;
}

}  // namespace

void write_pvd(const std::filesystem::path& pvd, const std::vector<std::pair<double, std::string>>& entries) {
  std::ostringstream o;
  o.precision(17);
  o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n";
  for (const auto& [t, file] : entries) o << "    <DataSet timestep=\"" << t << "\" part=\"0\" file=\"" << file << "\"/>\n";
  o << "  </Collection>\n</VTKFile>\n";
  write_text_atomic(pvd, o.str());
}

void write_surface_series(const std::filesystem::path& pvd, const std::vector<double>& times,
                          const NdArray<std::int32_t>& triangles, const std::vector<SurfaceFrame>& frames) {
  const std::string where = pvd.string();
  if (times.size() != frames.size())
    throw Error(where + ": " + std::to_string(times.size()) + " times for " + std::to_string(frames.size()) + " frames");
  std::vector<std::pair<double, std::string>> entries;
  for (std::size_t f = 0; f < frames.size(); ++f) {
    const auto& fr = frames[f];
    vtkNew<vtkPolyData> poly;
    auto pts = to_points(fr.points, where);
    const std::size_t nv = fr.points.shape[0];
    poly->SetPoints(pts);
    check_cells(triangles, 3, nv, where);
    poly->AllocateExact(static_cast<vtkIdType>(triangles.size() / 3), static_cast<vtkIdType>(triangles.size()));
    insert_cells(poly.Get(), triangles, 3, VTK_TRIANGLE);
    for (const auto& a : fr.point_data) poly->GetPointData()->AddArray(to_vtk(a, nv, where));
    for (const auto& a : fr.cell_data) poly->GetCellData()->AddArray(to_vtk(a, triangles.shape.empty() ? 0 : triangles.shape[0], where));
    const auto name = frame_name(pvd, f, ".vtp");
    write_xml<vtkXMLPolyDataWriter>(poly.Get(), pvd.parent_path() / name);
    entries.emplace_back(times[f], name);
  }
  write_pvd(pvd, entries);
}

void write_unstructured(const std::filesystem::path& vtu, const NdArray<double>& points,
                        const NdArray<std::int32_t>& triangles, const NdArray<std::int32_t>& lines,
                        const std::vector<NamedArray>& point_data, const std::vector<NamedArray>& cell_data) {
  const std::string where = vtu.string();
  vtkNew<vtkUnstructuredGrid> grid;
  auto pts = to_points(points, where);
  const std::size_t nv = points.shape[0];
  grid->SetPoints(pts);
  const std::size_t ntri = triangles.size() ? triangles.shape[0] : 0, nline = lines.size() ? lines.shape[0] : 0;
  grid->Allocate(static_cast<vtkIdType>(ntri + nline));
  check_cells(triangles, 3, nv, where);
  check_cells(lines, 2, nv, where);
  insert_cells(grid.Get(), triangles, 3, VTK_TRIANGLE);  // triangles first, then lines:
  insert_cells(grid.Get(), lines, 2, VTK_LINE);          // the order cell_data follows
  for (const auto& a : point_data) grid->GetPointData()->AddArray(to_vtk(a, nv, where));
  for (const auto& a : cell_data) grid->GetCellData()->AddArray(to_vtk(a, ntri + nline, where));
  write_xml<vtkXMLUnstructuredGridWriter>(grid.Get(), vtu);
}

GridSeries::GridSeries(std::filesystem::path pvd, std::vector<double> x_faces, std::vector<double> y_faces,
                       std::vector<double> z_faces)
    : pvd_(std::move(pvd)), x_(std::move(x_faces)), y_(std::move(y_faces)), z_(std::move(z_faces)) {
  const std::string where = pvd_.string();
  if (x_.size() < 2 || y_.size() < 2 || z_.empty())
    throw Error(where + ": a grid needs at least 2 x and y faces and 1 z face");
  for (const auto* f : {&x_, &y_, &z_})
    for (std::size_t i = 1; i < f->size(); ++i)
      if (!((*f)[i] > (*f)[i - 1]))
        throw Error(where + ": " + (f == &x_ ? "x" : f == &y_ ? "y" : "z") + " face coordinates must increase strictly");
}

void GridSeries::resume(double t_max) {
  std::ifstream in(pvd_);
  if (!in) return;  // nothing written before: start a new series
  std::string line;
  entries_.clear();
  // The collections this class writes: one <DataSet timestep="t" part="0" file="..."/> per line.
  while (std::getline(in, line)) {
    const auto ts = line.find("timestep=\""), fs = line.find("file=\"");
    if (ts == std::string::npos || fs == std::string::npos) continue;
    const double t = std::stod(line.substr(ts + 10));
    const auto fe = line.find('"', fs + 6);
    if (t <= t_max) entries_.emplace_back(t, line.substr(fs + 6, fe - fs - 6));
  }
}

void GridSeries::add(double t, const GridFrame& frame) {
  const std::string where = pvd_.string();
  const std::size_t ncells = (x_.size() - 1) * (y_.size() - 1) * std::max<std::size_t>(z_.size() - 1, 1);
  // Named, so that the file does not carry VTK's default name, the array's memory address, and the
  // same frame gives the same bytes.
  auto coords = [](const std::vector<double>& f, const char* name) {
    vtkNew<vtkDoubleArray> c;
    c->SetName(name);
    c->SetNumberOfTuples(static_cast<vtkIdType>(f.size()));
    std::copy(f.begin(), f.end(), c->GetPointer(0));
    return c;
  };
  auto xc = coords(x_, "x");
  auto yc = coords(y_, "y");
  auto zc = coords(z_, "z");
  vtkNew<vtkRectilinearGrid> grid;
  grid->SetDimensions(static_cast<int>(x_.size()), static_cast<int>(y_.size()), static_cast<int>(z_.size()));
  grid->SetXCoordinates(xc);
  grid->SetYCoordinates(yc);
  grid->SetZCoordinates(zc);
  for (const auto& a : frame.cell_data) grid->GetCellData()->AddArray(to_vtk(a, ncells, where));
  const auto name = frame_name(pvd_, entries_.size(), ".vtr");
  write_xml<vtkXMLRectilinearGridWriter>(grid.Get(), pvd_.parent_path() / name);
  entries_.emplace_back(t, name);
  write_pvd(pvd_, entries_);  // after the frame: the collection never names an unfinished file
}

void write_grid_series(const std::filesystem::path& pvd, const std::vector<double>& times,
                       const std::vector<double>& x_faces, const std::vector<double>& y_faces,
                       const std::vector<double>& z_faces, const std::vector<GridFrame>& frames) {
  if (times.size() != frames.size())
    throw Error(pvd.string() + ": " + std::to_string(times.size()) + " times for " + std::to_string(frames.size()) +
                " frames");
  GridSeries series(pvd, x_faces, y_faces, z_faces);
  for (std::size_t f = 0; f < frames.size(); ++f) series.add(times[f], frames[f]);
}

}  // namespace finverse::vtkio
