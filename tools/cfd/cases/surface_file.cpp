// Surface files to triangulated bodies; see surface_file.hpp.
#include "cfd/cases/surface_file.hpp"

#include <vtkCellArray.h>
#include <vtkCleanPolyData.h>
#include <vtkErrorCode.h>
#include <vtkOBJReader.h>
#include <vtkObject.h>
#include <vtkPolyData.h>
#include <vtkSTLReader.h>
#include <vtkSmartPointer.h>
#include <vtkTriangleFilter.h>
#include <vtkXMLPolyDataReader.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include "core/error.hpp"
#include "core/stage_files.hpp"

namespace finverse::cfd::cases {

namespace {

template <class Reader>
vtkSmartPointer<vtkPolyData> read_with(const std::filesystem::path& file) {
  // VTK's own error and warning text would come before ours, several lines of it (issue 46):
  // the reader's error code becomes our one line instead.
  vtkObject::GlobalWarningDisplayOff();
  auto reader = vtkSmartPointer<Reader>::New();
  reader->SetFileName(file.string().c_str());
  // Triangles only, and one vertex where the file repeats it (STL stores each triangle's corners).
  auto triangles = vtkSmartPointer<vtkTriangleFilter>::New();
  triangles->SetInputConnection(reader->GetOutputPort());
  auto clean = vtkSmartPointer<vtkCleanPolyData>::New();
  clean->SetInputConnection(triangles->GetOutputPort());
  clean->PointMergingOn();
  clean->SetTolerance(0.0);
  clean->Update();
  if (const unsigned long code = reader->GetErrorCode(); code != vtkErrorCode::NoError)
    throw Error(file.string() + ": cannot read it as a " + file.extension().string() + " surface (" +
                vtkErrorCode::GetStringFromErrorCode(code) + ")");
  return clean->GetOutput();
}

TriangulatedSurface from_mesh_h5(const std::filesystem::path& file) {
  const auto mesh = stage::read<stage::Mesh>(file);
  if (mesh.ibm_points.size() == 0 || mesh.ibm_triangles.size() == 0)
    throw Error(file.string() + ": /ibm/points: missing, expected the closed thin body (a structural mesh has none)");
  TriangulatedSurface s;
  for (std::size_t v = 0; v < mesh.ibm_points.dim(0); ++v)
    s.points.push_back({mesh.ibm_points(v, 0), mesh.ibm_points(v, 1), mesh.ibm_points(v, 2)});
  for (std::size_t t = 0; t < mesh.ibm_triangles.dim(0); ++t)
    s.triangles.push_back({mesh.ibm_triangles(t, 0), mesh.ibm_triangles(t, 1), mesh.ibm_triangles(t, 2)});
  return s;
}

}  // namespace

double signed_volume(const TriangulatedSurface& s) {
  double v = 0;
  for (const auto& t : s.triangles) {
    const auto& a = s.points[t[0]];
    const auto& b = s.points[t[1]];
    const auto& c = s.points[t[2]];
    v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  return v / 6;
}

void transform(TriangulatedSurface& s, double scale, const std::array<double, 3>& translate) {
  for (auto& p : s.points)
    for (int c = 0; c < 3; ++c) p[c] = scale * p[c] + translate[c];
}

TriangulatedSurface read_surface_file(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file)) throw Error(file.string() + ": no such surface file");
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".h5") return from_mesh_h5(file);
  vtkSmartPointer<vtkPolyData> poly;
  if (ext == ".stl")
    poly = read_with<vtkSTLReader>(file);
  else if (ext == ".obj")
    poly = read_with<vtkOBJReader>(file);
  else if (ext == ".vtp")
    poly = read_with<vtkXMLPolyDataReader>(file);
  else
    throw Error(file.string() + ": unknown surface format '" + ext + "', expected .stl, .obj, .vtp or mesh .h5");
  TriangulatedSurface s;
  for (vtkIdType i = 0; i < poly->GetNumberOfPoints(); ++i) {
    double x[3];
    poly->GetPoint(i, x);
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
      throw Error(file.string() + ": vertex " + std::to_string(i) + " has a coordinate that is not a finite number");
    s.points.push_back({x[0], x[1], x[2]});
  }
  vtkCellArray* polys = poly->GetPolys();
  const vtkIdType* ids = nullptr;
  vtkIdType n = 0;
  for (polys->InitTraversal(); polys->GetNextCell(n, ids);)
    if (n == 3) s.triangles.push_back({static_cast<int>(ids[0]), static_cast<int>(ids[1]), static_cast<int>(ids[2])});
  if (s.triangles.empty()) throw Error(file.string() + ": no triangles");
  // Outward orientation: a body given inside out would otherwise put the fluid inside it.
  if (signed_volume(s) < 0)
    for (auto& t : s.triangles) std::swap(t[1], t[2]);
  return s;
}

}  // namespace finverse::cfd::cases
