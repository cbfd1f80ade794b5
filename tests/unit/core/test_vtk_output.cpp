// What core writes for ParaView is read back by VTK's own XML readers (the readers ParaView
// 5.11 uses): a moving triangle surface (.pvd + .vtp), an unstructured shell+beam mesh (.vtu)
// and cell fields on a stretched grid (.pvd + .vtr).
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkRectilinearGrid.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLRectilinearGridReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include "core/error.hpp"
#include "core/vtk_output.hpp"
#include "test_util.hpp"

using namespace finverse;

TEST(VtkOutput, SurfaceSeriesReadsBack) {
  test::ScratchDir dir;
  const NdArray<std::int32_t> tris({2, 3}, {0, 1, 2, 0, 2, 3});
  std::vector<vtkio::SurfaceFrame> frames(3);
  for (std::size_t f = 0; f < 3; ++f) {
    frames[f].points = NdArray<double>({4, 3}, {0, 0, 0, 1, 0, 0, 1, 1, 0.1 * double(f), 0, 1, 0});
    frames[f].point_data.push_back({"velocity", test::wave({4, 3}, double(f))});
    frames[f].cell_data.push_back({"pressure_jump", NdArray<double>({2}, {double(f), -double(f)})});
  }
  vtkio::write_surface_series(dir / "fin.pvd", {0, 0.002, 0.004}, tris, frames);
  const auto pvd = test::slurp(dir / "fin.pvd");
  EXPECT_NE(pvd.find("file=\"fin/fin_000002.vtp\""), std::string::npos);
  EXPECT_NE(pvd.find("timestep=\"0.004"), std::string::npos);

  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName((dir / "fin/fin_000002.vtp").c_str());
  reader->Update();
  auto* poly = reader->GetOutput();
  ASSERT_EQ(poly->GetNumberOfPoints(), 4);
  ASSERT_EQ(poly->GetNumberOfPolys(), 2);
  EXPECT_DOUBLE_EQ(poly->GetPoint(2)[2], 0.2);
  auto* v = poly->GetPointData()->GetArray("velocity");
  ASSERT_NE(v, nullptr);
  EXPECT_EQ(v->GetNumberOfComponents(), 3);
  EXPECT_DOUBLE_EQ(v->GetComponent(3, 2), test::wave({4, 3}, 2.0)(3, 2));
  EXPECT_DOUBLE_EQ(poly->GetCellData()->GetArray("pressure_jump")->GetComponent(1, 0), -2.0);
}

TEST(VtkOutput, UnstructuredShellAndBeamsReadBack) {
  test::ScratchDir dir;
  const NdArray<double> pts({4, 3}, {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0});
  vtkio::write_unstructured(dir / "mesh.vtu", pts, NdArray<std::int32_t>({2, 3}, {0, 1, 2, 0, 2, 3}),
                            NdArray<std::int32_t>({1, 2}, {0, 2}), {{"root", NdArray<double>({4}, {1, 0, 0, 1})}},
                            {{"E", NdArray<double>({3}, {1e7, 1e7, 3e8})}});
  vtkNew<vtkXMLUnstructuredGridReader> reader;
  reader->SetFileName((dir / "mesh.vtu").c_str());
  reader->Update();
  auto* g = reader->GetOutput();
  ASSERT_EQ(g->GetNumberOfCells(), 3);
  EXPECT_EQ(g->GetCellType(0), VTK_TRIANGLE);
  EXPECT_EQ(g->GetCellType(2), VTK_LINE);
  EXPECT_DOUBLE_EQ(g->GetCellData()->GetArray("E")->GetComponent(2, 0), 3e8);
  EXPECT_DOUBLE_EQ(g->GetPointData()->GetArray("root")->GetComponent(3, 0), 1);
}

TEST(VtkOutput, StretchedGridFieldsReadBack) {
  test::ScratchDir dir;
  const std::vector<double> x{0, 0.1, 0.2, 0.35, 0.6}, y{-1, 0, 1}, z{0, 0.5};
  const std::size_t ncells = 4 * 2 * 1;
  std::vector<vtkio::GridFrame> frames(2);
  for (std::size_t f = 0; f < 2; ++f) {
    frames[f].cell_data.push_back({"p", test::wave({ncells}, double(f))});
    frames[f].cell_data.push_back({"u", test::wave({ncells, 3}, double(f))});
  }
  vtkio::write_grid_series(dir / "flow.pvd", {0.0, 0.1}, x, y, z, frames);
  vtkNew<vtkXMLRectilinearGridReader> reader;
  reader->SetFileName((dir / "flow/flow_000001.vtr").c_str());
  reader->Update();
  auto* g = reader->GetOutput();
  int dims[3];
  g->GetDimensions(dims);
  EXPECT_EQ(dims[0], 5);
  EXPECT_EQ(dims[1], 3);
  EXPECT_EQ(dims[2], 2);
  EXPECT_DOUBLE_EQ(g->GetXCoordinates()->GetComponent(3, 0), 0.35);
  ASSERT_EQ(g->GetNumberOfCells(), 8);
  // Cell (i=3, j=1): x fastest, so flat index 1*4+3 = 7.
  EXPECT_DOUBLE_EQ(g->GetCellData()->GetArray("u")->GetComponent(7, 1), test::wave({ncells, 3}, 1.0)(7, 1));
  double c[3];
  g->GetCell(7)->GetBounds();
  g->GetPoint(0, c);
  EXPECT_DOUBLE_EQ(c[1], -1.0);
}

TEST(VtkOutput, GridSeriesWritesFrameByFrameAndResumesAfterARestart) {
  test::ScratchDir dir;
  const std::vector<double> x{0, 0.5, 1}, y{0, 1}, z{0};
  const auto frame = [](double v) {
    vtkio::GridFrame f;
    f.cell_data.push_back({"p", NdArray<double>({2}, {v, -v})});
    return f;
  };
  const auto pvd_text = [&] {
    std::ifstream in(dir / "flow.pvd");
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  {
    vtkio::GridSeries s(dir / "flow.pvd", x, y, z);
    for (int f = 0; f < 3; ++f) {
      s.add(0.1 * f, frame(f));
      // The collection names every frame written so far, and only those.
      EXPECT_NE(pvd_text().find("flow_00000" + std::to_string(f) + ".vtr"), std::string::npos);
      EXPECT_EQ(pvd_text().find("flow_00000" + std::to_string(f + 1) + ".vtr"), std::string::npos);
    }
  }
  // A run restarted from t = 0.1 keeps frames 0 and 1 and writes its next one as frame 2.
  vtkio::GridSeries s(dir / "flow.pvd", x, y, z);
  s.resume(0.1 + 1e-12);
  EXPECT_EQ(s.size(), 2u);
  s.add(0.15, frame(7));
  const std::string text = pvd_text();
  EXPECT_NE(text.find("timestep=\"0.14999999999999999\""), std::string::npos) << text;
  EXPECT_EQ(text.find("timestep=\"0.20000000000000001\""), std::string::npos) << text;
  vtkNew<vtkXMLRectilinearGridReader> reader;
  reader->SetFileName((dir / "flow/flow_000002.vtr").c_str());
  reader->Update();
  EXPECT_DOUBLE_EQ(reader->GetOutput()->GetCellData()->GetArray("p")->GetComponent(0, 0), 7.0);
  // No earlier file: resume starts an empty series.
  vtkio::GridSeries fresh(dir / "other.pvd", x, y, z);
  fresh.resume(1.0);
  EXPECT_EQ(fresh.size(), 0u);
}

TEST(VtkOutput, BadInputNamesTheFile) {
  test::ScratchDir dir;
  const NdArray<double> pts({3, 3}, 0.0);
  EXPECT_THROW(vtkio::write_unstructured(dir / "m.vtu", pts, NdArray<std::int32_t>({1, 3}, {0, 1, 5}), {}, {}, {}), Error);
  EXPECT_FALSE(std::filesystem::exists(dir / "m.vtu"));
  EXPECT_THROW(vtkio::write_grid_series(dir / "g.pvd", {0}, {0, 1, 0.5}, {0, 1}, {0}, {vtkio::GridFrame{}}), Error);
}
