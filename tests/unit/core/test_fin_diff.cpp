// fin-diff, run as the executable users run: exit 0 for equal or within tolerance, 1 for
// beyond tolerance, a missing dataset or a shape mismatch, 2 for an unreadable file; VTK and
// .pvd comparison; provenance ignored; --update.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include "core/hdf5_file.hpp"
#include "core/stage_files.hpp"
#include "core/vtk_output.hpp"
#include "test_util.hpp"

using namespace finverse;

namespace {

int fin_diff(const std::string& args) {
  const std::string cmd = std::string(FIN_DIFF_EXE) + " " + args + " > /dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

class FinDiff : public ::testing::Test {
 protected:
  void SetUp() override {
    auto m = test::sample_motion();
    stage::write(dir / "ref.h5", m, test::test_provenance());
  }
  std::string path(const std::string& n) { return (dir / n).string(); }
  // A copy of the reference motion with one change applied, written by another "producer".
  void variant(const std::string& name, const std::function<void(stage::Motion&)>& change) {
    auto m = test::sample_motion();
    change(m);
    stage::write(dir / name, m, Provenance{"other-tool", {{"x", 1}}, {}});
  }
  void raw(const std::string& name, const std::function<void(h5::File&)>& body) {
    auto f = h5::File::create(dir / name);
    write_provenance(f, "finverse/motion", 1, test::test_provenance());
    body(f);
    f.commit();
  }
  test::ScratchDir dir;
};

}  // namespace

TEST_F(FinDiff, EqualFilesDespiteDifferentProvenance) {
  variant("same.h5", [](stage::Motion&) {});
  EXPECT_EQ(fin_diff(path("ref.h5") + " " + path("same.h5")), 0);
}

TEST_F(FinDiff, WithinAndBeyondTolerance) {
  variant("near.h5", [](stage::Motion& m) { m.points(3, 4, 1) += 1e-9; });
  EXPECT_EQ(fin_diff(path("ref.h5") + " " + path("near.h5")), 1);  // exact by default
  EXPECT_EQ(fin_diff(path("ref.h5") + " " + path("near.h5") + " --atol 1e-8"), 0);
  std::ofstream(dir / "tol.json") << R"({"default": {"atol": 0}, "datasets": {"/points": {"atol": 1e-8}}})";
  EXPECT_EQ(fin_diff(path("ref.h5") + " " + path("near.h5") + " --tolerances " + path("tol.json")), 0);
  variant("far.h5", [](stage::Motion& m) { m.points(3, 4, 1) += 1e-3; });
  EXPECT_EQ(fin_diff(path("ref.h5") + " " + path("far.h5") + " --tolerances " + path("tol.json")), 1);
  variant("late.h5", [](stage::Motion& m) { m.time.data[2] += 1e-9; });
  EXPECT_EQ(fin_diff(path("ref.h5") + " " + path("late.h5") + " --tolerances " + path("tol.json")), 1);
}

TEST_F(FinDiff, MissingDataset) {
  variant("novel.h5", [](stage::Motion& m) { m.velocity = {}; });
  EXPECT_EQ(fin_diff(path("ref.h5") + " " + path("novel.h5") + " --atol 1"), 1);
  EXPECT_EQ(fin_diff(path("novel.h5") + " " + path("ref.h5") + " --atol 1"), 1);  // extra in candidate
}

TEST_F(FinDiff, ShapeMismatch) {
  auto m = test::sample_motion(8, 31);
  stage::write(dir / "bigger.h5", m, test::test_provenance());
  EXPECT_EQ(fin_diff(path("ref.h5") + " " + path("bigger.h5") + " --atol 1e9"), 1);
}

TEST_F(FinDiff, NaNAndAttributes) {
  raw("a.h5", [](h5::File& f) { f.write("x", NdArray<double>({3}, {1, std::nan(""), 3}), {"m"}); });
  raw("b.h5", [](h5::File& f) { f.write("x", NdArray<double>({3}, {1, std::nan(""), 3}), {"m"}); });
  raw("c.h5", [](h5::File& f) { f.write("x", NdArray<double>({3}, {1, 2, 3}), {"m"}); });
  raw("d.h5", [](h5::File& f) { f.write("x", NdArray<double>({3}, {1, std::nan(""), 3}), {"mm"}); });
  EXPECT_EQ(fin_diff(path("a.h5") + " " + path("b.h5")), 0);
  EXPECT_EQ(fin_diff(path("a.h5") + " " + path("c.h5") + " --atol 1e9"), 1);
  EXPECT_EQ(fin_diff(path("a.h5") + " " + path("d.h5")), 1);  // units attribute differs
}

TEST_F(FinDiff, UnreadableFileIsAnError) {
  std::ofstream(dir / "junk.h5") << "junk";
  EXPECT_EQ(fin_diff(path("ref.h5") + " " + path("junk.h5")), 2);
  EXPECT_EQ(fin_diff(path("ref.h5") + " " + path("absent.h5")), 2);
  EXPECT_EQ(fin_diff(path("ref.h5")), 2);  // missing argument
  std::ofstream(dir / "bad_tol.json") << "{";
  EXPECT_EQ(fin_diff(path("ref.h5") + " " + path("ref.h5") + " --tolerances " + path("bad_tol.json")), 2);
}

TEST_F(FinDiff, UpdateRewritesReference) {
  variant("new.h5", [](stage::Motion& m) { m.points(0, 0, 0) = 42; });
  EXPECT_EQ(fin_diff(path("ref.h5") + " " + path("new.h5")), 1);
  EXPECT_EQ(fin_diff(path("ref.h5") + " " + path("new.h5") + " --update"), 0);
  EXPECT_EQ(fin_diff(path("ref.h5") + " " + path("new.h5")), 0);
}

TEST_F(FinDiff, VtkSeriesAndDirectories) {
  const NdArray<std::int32_t> tris({2, 3}, {0, 1, 2, 0, 2, 3});
  auto frames = [&](double bump) {
    std::vector<vtkio::SurfaceFrame> f(2);
    for (std::size_t i = 0; i < 2; ++i) {
      f[i].points = NdArray<double>({4, 3}, {0, 0, 0, 1, 0, 0, 1, 1, double(i), 0, 1, 0});
      f[i].point_data.push_back({"displacement", NdArray<double>({4, 3}, 0.1 * double(i))});
      f[i].cell_data.push_back({"pressure", NdArray<double>({2}, {1.0, 2.0 + bump})});
    }
    return f;
  };
  for (const auto& [sub, bump] : {std::pair{"ref", 0.0}, std::pair{"same", 0.0}, std::pair{"moved", 1e-4}}) {
    vtkio::write_surface_series(dir / sub / "surface.pvd", {0.0, 0.5}, tris, frames(bump));
    auto m = test::sample_motion();
    stage::write(dir / sub / "motion.h5", m, test::test_provenance());
  }
  EXPECT_EQ(fin_diff(path("ref/surface.pvd") + " " + path("same/surface.pvd")), 0);
  EXPECT_EQ(fin_diff(path("ref/surface.pvd") + " " + path("moved/surface.pvd")), 1);
  EXPECT_EQ(fin_diff(path("ref/surface.pvd") + " " + path("moved/surface.pvd") + " --rtol 1e-3"), 0);
  EXPECT_EQ(fin_diff(path("ref/surface/surface_000001.vtp") + " " + path("moved/surface/surface_000001.vtp")), 1);
  EXPECT_EQ(fin_diff(path("ref") + " " + path("same")), 0);
  EXPECT_EQ(fin_diff(path("ref") + " " + path("moved")), 1);
  std::ofstream(dir / "ref/tolerances.json") << R"({"datasets": {"*CellData/pressure": {"rtol": 1e-3}}})";
  EXPECT_EQ(fin_diff(path("ref") + " " + path("moved")), 0);  // directory picks up its tolerances.json
  std::filesystem::remove(dir / "same/motion.h5");
  EXPECT_EQ(fin_diff(path("ref") + " " + path("same")), 1);
}
