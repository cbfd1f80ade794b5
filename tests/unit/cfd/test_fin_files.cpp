// Tests of fin-cfd's file side (cfd/io): mesh.h5 + motion.h5 read through their contracts and
// cross-checked (every bad input a one-line finverse::Error naming the file and dataset), the
// loads.h5 round trip through the contract.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cfd/io/fin_input.hpp"
#include "cfd/io/loads_record.hpp"
#include "cfd/validation/thin_plate_case.hpp"
#include "core/error.hpp"
#include "core/stage_files.hpp"
#include "../scratch_dir.hpp"

namespace finverse::cfd::io {
namespace {

namespace fs = std::filesystem;

// The error message of f(), or "" when it does not throw.
template <class F> std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(FinFiles, PlateFilesPassTheContractsAndReadBack) {
  const auto f = make_thin_plate({});
  const finverse::test::ScratchDir scratch;
  const fs::path& d = scratch.path();
  Provenance prov{"test", {}, {}};
  auto mesh = f.mesh;
  auto motion = f.motion;
  stage::write(d / "mesh.h5", mesh, prov);
  stage::write(d / "motion.h5", motion, prov);
  const FinInput in = read_fin_input(d / "mesh.h5", d / "motion.h5");
  const ThinPlateSetup s;
  EXPECT_NEAR(in.reference_area, s.chord * s.span, 1e-15);
  EXPECT_EQ(in.rest.size(), f.mesh.points.dim(0));
  ASSERT_TRUE(in.layout.wrap);
  EXPECT_DOUBLE_EQ(*in.layout.wrap, s.period);
  EXPECT_LE(in.rest_mismatch, 1e-18);
  EXPECT_NE(error_of([&] { read_fin_input(d / "missing.h5", d / "motion.h5"); }).find("missing.h5"), std::string::npos);
  // The files swapped: the contract check names the schema.
  EXPECT_NE(error_of([&] { read_fin_input(d / "motion.h5", d / "mesh.h5"); }).find("motion.h5"), std::string::npos);
}

TEST(FinFiles, EachInconsistencyIsAOneLineErrorNamingTheDataset) {
  const auto f = make_thin_plate({});
  auto expect = [&](const stage::Mesh& m, const stage::Motion& q, const std::string& needle) {
    const std::string msg = error_of([&] { make_fin_input(m, q, "mesh.h5", "motion.h5"); });
    EXPECT_NE(msg.find(needle), std::string::npos) << "expected '" << needle << "' in: " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  };
  {  // node count
    auto q = f.motion;
    q.points = NdArray<double>({q.points.dim(0), q.points.dim(1) - 1, 3}, 0.0);
    expect(f.mesh, q, "motion.h5: /points");
  }
  {  // times
    auto q = f.motion;
    q.time(5) = q.time(4);
    expect(f.mesh, q, "motion.h5: /time is not strictly increasing at frame 5");
  }
  {  // one frame
    auto q = f.motion;
    q.time = NdArray<double>({1}, 0.0);
    q.points = NdArray<double>({1, f.mesh.points.dim(0), 3}, 0.0);
    expect(f.mesh, q, "motion.h5: /time has 1 frames");
  }
  {  // source node
    auto m = f.mesh;
    m.ibm_source_node(3) = static_cast<std::int32_t>(m.points.dim(0));
    expect(m, f.motion, "mesh.h5: /ibm/source_node[3]");
  }
  {  // offset sign
    auto m = f.mesh;
    m.ibm_offset_sign(2) = 2;
    expect(m, f.motion, "mesh.h5: /ibm/offset_sign[2]");
  }
  {  // not closed
    auto m = f.mesh;
    const std::size_t n = m.ibm_triangles.dim(0) - 1;
    m.ibm_triangles = NdArray<std::int32_t>({n, 3}, std::vector<std::int32_t>(m.ibm_triangles.data.begin(),
                                                                               m.ibm_triangles.data.begin() + 3 * n));
    expect(m, f.motion, "mesh.h5: /ibm/triangles: edge");
  }
  {  // inconsistent orientation
    auto m = f.mesh;
    std::swap(m.ibm_triangles(0, 1), m.ibm_triangles(0, 2));
    expect(m, f.motion, "mesh.h5: /ibm/triangles");
  }
  {  // surface not the offset mid-surface
    auto m = f.mesh;
    m.ibm_points(4, 1) += 0.1 * *m.ibm_thickness;
    expect(m, f.motion, "mesh.h5: /ibm/points[4]");
  }
  {  // mid-surface triangle index
    auto m = f.mesh;
    m.triangles(1, 2) = -1;
    expect(m, f.motion, "mesh.h5: /triangles[1]");
  }
  {  // periodic data whose last frame should repeat the first
    auto q = f.motion;
    const std::size_t nf = q.time.size(), nv = q.points.dim(1);
    NdArray<double> t({nf + 1}), p({nf + 1, nv, 3});
    for (std::size_t k = 0; k < nf; ++k) t(k) = q.time(k);
    t(nf) = *q.period;
    std::copy(q.points.data.begin(), q.points.data.end(), p.data.begin());
    for (std::size_t i = 0; i < 3 * nv; ++i) p.data[nf * 3 * nv + i] = q.points.data[3 * nv + i];  // frame 1, not 0
    q.time = t;
    q.points = p;
    q.velocity = {};
    expect(f.mesh, q, "motion.h5: /points: the last frame");
  }
}

TEST(FinFiles, LoadsRoundTripThroughTheContract) {
  const std::size_t nv = 5, ntri = 3;
  LoadsRecord rec(nv, ntri);
  for (int k = 0; k < 4; ++k) {
    std::vector<Vec3> nodal(nv);
    Vec3 total{};
    for (std::size_t i = 0; i < nv; ++i) {
      nodal[i] = {0.1 * k + static_cast<double>(i), -0.2 * static_cast<double>(i), 0.01 * k};
      for (int d = 0; d < 3; ++d) total[d] += nodal[i][d];
    }
    rec.add(0.01 * k, nodal, total, {1.0 * k, 2.0, -3.0});
  }
  EXPECT_THROW(rec.add(0.0, std::vector<Vec3>(nv), {}, {0, 0, 0}), Error);  // time must increase
  EXPECT_THROW(rec.add(1.0, std::vector<Vec3>(nv - 1), {}, {0, 0, 0}), Error);
  const double rho = 1000, U = 0.1, A = 1.5e-4;
  stage::Loads l = rec.to_stage(rho, U, A, 0.2);
  const double q = 0.5 * rho * U * U * A;
  EXPECT_DOUBLE_EQ(l.thrust(2), -l.force_total(2, 0) / q);
  EXPECT_DOUBLE_EQ(l.lateral(3), l.force_total(3, 1) / q);
  EXPECT_DOUBLE_EQ(l.vertical(1), l.force_total(1, 2) / q);
  const finverse::test::ScratchDir scratch;
  const fs::path& d = scratch.path();
  stage::write(d / "loads.h5", l, Provenance{"test", {}, {}});
  EXPECT_FALSE(fs::exists(d / "loads.h5.tmp"));
  const auto r = stage::read<stage::Loads>(d / "loads.h5");
  EXPECT_EQ(r.time, l.time);
  EXPECT_EQ(r.nodal_force, l.nodal_force);
  EXPECT_EQ(r.force_total, l.force_total);
  EXPECT_EQ(r.pressure_jump, l.pressure_jump);
  EXPECT_EQ(r.thrust, l.thrust);
  EXPECT_EQ(r.rho, l.rho);
  EXPECT_EQ(r.U, l.U);
  EXPECT_EQ(r.reference_area, l.reference_area);
  EXPECT_EQ(r.period, l.period);
  for (double e : nodal_sum_relative_error(r)) EXPECT_LE(e, 1e-15);
  // A non-finite force is refused before anything is written.
  l.nodal_force(1, 2, 0) = std::nan("");
  EXPECT_THROW(stage::write(d / "bad.h5", l, Provenance{"test", {}, {}}), Error);
  EXPECT_FALSE(fs::exists(d / "bad.h5"));
}

}  // namespace
}  // namespace finverse::cfd::io
