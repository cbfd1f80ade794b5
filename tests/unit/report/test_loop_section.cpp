// The report's "Closing the loop" section (report/loop_section.hpp, issue 34) on a hand-made trail
// written by fin-loop's own writer (loop/io/loop_files.hpp): two steps, the first added (residual
// cut 6x), the second rejected. Checked: the section's numbers and rows, fin-report --loop and
// report_figures.py writing the maps, the table and the errors into index.html, the report
// unchanged without --loop, and a loop.h5 of another mesh refused with one line, exit 2.
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "../scratch_dir.hpp"
#include "core/stage_files.hpp"
#include "loop/io/loop_files.hpp"
#include "report/fin_report.hpp"
#include "report/loop_section.hpp"

namespace finverse::report {
namespace {

constexpr std::size_t kNx = 7, kNz = 9;  // nodes along the chord (x) and the span (z)

stage::Mesh grid_mesh(double scale = 1.0) {
  stage::Mesh m;
  m.points = NdArray<double>({kNx * kNz, 3});
  std::vector<std::int32_t> tri, root;
  for (std::size_t i = 0; i < kNx; ++i)
    for (std::size_t j = 0; j < kNz; ++j) {
      m.points(i * kNz + j, 0) = scale * 0.01 * double(i) / (kNx - 1);
      m.points(i * kNz + j, 2) = scale * 0.015 * double(j) / (kNz - 1);
      if (i == 0) root.push_back(std::int32_t(j));
    }
  for (std::size_t i = 0; i + 1 < kNx; ++i)
    for (std::size_t j = 0; j + 1 < kNz; ++j) {
      const auto a = std::int32_t(i * kNz + j), b = std::int32_t((i + 1) * kNz + j);
      for (std::int32_t v : {a, b, b + 1, a, b + 1, a + 1}) tri.push_back(v);
    }
  const std::size_t ntri = tri.size() / 3, nv = kNx * kNz;
  m.triangles = NdArray<std::int32_t>({ntri, 3}, tri);
  m.shell_thickness = NdArray<double>({ntri}, 2e-5);
  m.shell_region = NdArray<std::int32_t>({ntri}, 0);
  // One ray along the chord at z = 0; the closed surface is the mid-surface itself (not used).
  std::vector<std::int32_t> beams;
  std::vector<double> s;
  for (std::size_t i = 0; i + 1 < kNx; ++i) {
    beams.insert(beams.end(), {std::int32_t(i * kNz), std::int32_t((i + 1) * kNz)});
    s.insert(s.end(), {double(i) / (kNx - 1), double(i + 1) / (kNx - 1)});
  }
  m.beam_elements = NdArray<std::int32_t>({kNx - 1, 2}, beams);
  m.beam_ray = NdArray<std::int32_t>({kNx - 1}, 1);
  m.beam_s = NdArray<double>({kNx - 1, 2}, s);
  m.beam_thickness = NdArray<double>({kNx - 1, 2}, 1e-4);
  m.beam_width = NdArray<double>({kNx - 1, 2}, 2e-4);
  m.root_nodes = NdArray<std::int32_t>({root.size()}, root);
  m.ibm_points = m.points;
  m.ibm_triangles = m.triangles;
  std::vector<std::int32_t> source(nv);
  for (std::size_t n = 0; n < nv; ++n) source[n] = std::int32_t(n);
  m.ibm_source_node = NdArray<std::int32_t>({nv}, source);
  m.ibm_offset_sign = NdArray<std::int32_t>({nv}, 0);
  m.ibm_thickness = 1e-4;
  m.chord = 0.01;
  return m;
}

// Per-node RMS growing along the chord, NaN on the root (not compared).
Eigen::VectorXd node_map(const stage::Mesh& m, double peak) {
  Eigen::VectorXd v(m.points.dim(0));
  for (Eigen::Index n = 0; n < v.size(); ++n)
    v(n) = n < Eigen::Index(kNz) ? NAN : peak * m.points(std::size_t(n), 0) / 0.01;
  return v;
}

loop::ModelState state(double te, double held, double bic, const Eigen::VectorXd& map) {
  loop::ModelState s;
  s.trailing_edge_rms = te;
  s.held_out_rms = held;
  s.bic = bic;
  s.node_rms = map;
  return s;
}

loop::CandidateScore candidate(const std::string& name, double statistic, double p) {
  loop::CandidateScore c;
  c.name = name, c.score.statistic = statistic, c.score.p_value = p, c.score.degrees_of_freedom = 2;
  return c;
}

loop::io::TraceRecord trail(const stage::Mesh& m) {
  loop::io::TraceRecord rec;
  rec.candidates = {"active_stiffening", "rayleigh_damping", "root_curvature"};
  rec.split.held_out = {6, 7};
  rec.split.kind = "last_cycle";
  rec.excursion = 0.01;
  auto& r = rec.result;
  const auto before = node_map(m, 1.2e-3), after = node_map(m, 2e-4), worse = node_map(m, 2.5e-4);
  r.base_initial = state(1.5e-3, 1.6e-3, 300, node_map(m, 1.5e-3));
  r.base = state(1.2e-3, 1.3e-3, 100, before);
  r.final_state = state(2e-4, 2.5e-4, -200, after);
  loop::TraceStep s1;
  s1.scores = {candidate("active_stiffening", 250, 1e-12), candidate("root_curvature", 30, 1e-6),
               candidate("rayleigh_damping", 2, 0.4)};
  s1.tried = "active_stiffening", s1.accepted = true;
  s1.effect_parameter_names = {"stiffening_amplitude", "stiffening_phase"};
  s1.magnitude = Eigen::Vector2d(0.29, 1.5);
  s1.lower95 = Eigen::Vector2d(0.27, 1.4);
  s1.upper95 = Eigen::Vector2d(0.31, 1.6);
  s1.before = r.base;
  s1.after = r.final_state;
  loop::TraceStep s2;
  s2.scores = {candidate("root_curvature", 12, 2e-3), candidate("rayleigh_damping", 1, 0.6)};
  s2.tried = "root_curvature", s2.accepted = false;
  s2.effect_parameter_names = {"curvature_amplitude", "curvature_phase"};
  s2.magnitude = Eigen::Vector2d(0.01, 0.2);
  s2.lower95 = Eigen::Vector2d(-0.02, -1);
  s2.upper95 = Eigen::Vector2d(0.04, 1.4);
  s2.before = r.final_state;
  s2.after = state(1.9e-4, 2.7e-4, -195, worse);
  r.steps = {s1, s2};
  r.added = {"active_stiffening"};
  fit::Parameter p{"E_rays", "Pa", 1e8, 1e11, fit::Scale::log10, std::nullopt};
  r.space = fit::ParameterSpace({p});
  r.parameters = Eigen::VectorXd::Constant(1, 3e9);
  r.stop_reason = "BIC or held-out error did not improve";
  return rec;
}

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(LoopSection, TrailRowsMapsAndErrorsFromLoopH5) {
  test::ScratchDir dir;
  auto mesh = grid_mesh();
  stage::write(dir / "mesh.h5", mesh, Provenance{"test", {}, {}});
  loop::io::write_loop(dir / "loop.h5", trail(mesh), Provenance{"fin-loop", {}, {dir / "mesh.h5"}});
  const auto loop = stage::read<loop::io::LoopFile>(dir / "loop.h5");
  ASSERT_EQ(loop.node_rms_before.data.size(), kNx * kNz);
  EXPECT_TRUE(std::isnan(loop.node_rms_before.data[0]));  // the root: not compared
  EXPECT_NEAR(loop.node_rms_after.data.back(), 2e-4, 1e-15);
  EXPECT_NEAR(loop.step_node_rms_after.data.back(), 2.5e-4, 1e-15);  // step 2's refit

  const auto s = loop_section(loop, mesh, "loop.h5");
  const auto& f = s.figure;
  ASSERT_EQ(f["trail"].size(), 2u);
  EXPECT_EQ(f["trail"][0]["ranking"][0]["candidate"], "active_stiffening");
  EXPECT_EQ(f["trail"][0]["verdict"], "added");
  EXPECT_EQ(f["trail"][1]["ranking"].size(), 2u);  // the added one is no longer ranked
  EXPECT_EQ(f["trail"][1]["verdict"], "rejected: BIC did not improve, held-out error did not fall");
  EXPECT_NEAR(f["trail"][0]["magnitude"][0]["upper95"].get<double>(), 0.31, 1e-15);
  EXPECT_NEAR(f["errors"]["trailing_edge"][2].get<double>(), 6.0, 1e-12);  // 1.2e-3 / 2e-4
  EXPECT_NEAR(f["errors"]["bic"][2].get<double>(), -300, 1e-9);
  EXPECT_NEAR(f["vmax"].get<double>(), 1.2e-3, 1e-15);  // one scale: the larger of both maps
  ASSERT_EQ(f["maps"].size(), 2u);
  EXPECT_TRUE(f["maps"][0]["rms"][0].is_null());
  bool factor = false;
  for (const auto& sc : s.scores)
    if (sc.name == "closing the loop: trailing-edge residual RMS, factor before / after")
      factor = std::abs(*sc.value - 6.0) < 1e-12;
  EXPECT_TRUE(factor);

  // Maps on another mesh: refused, naming the file.
  auto small = grid_mesh();
  small.points = NdArray<double>({kNz, 3});
  try {
    loop_section(loop, small, "x/loop.h5");
    ADD_FAILURE() << "a loop.h5 of another mesh was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("x/loop.h5"), std::string::npos);
  }
  // Without the loop: no section, no input.
  ReportInputs in;
  in.case_name = "x";
  in.mesh = mesh;
  const auto plain = build_report(in);
  EXPECT_FALSE(plain.figures.contains("loop"));
  EXPECT_FALSE(summary_json(in, plain)["inputs"].contains("loop"));
}

TEST(LoopSection, FinReportWritesTheSectionAndRefusesAnotherMesh) {
  test::ScratchDir dir;
  auto mesh = grid_mesh();
  stage::write(dir / "mesh.h5", mesh, Provenance{"test", {}, {}});
  loop::io::write_loop(dir / "loop.h5", trail(mesh), Provenance{"fin-loop", {}, {dir / "mesh.h5"}});
  const std::string exe = FIN_REPORT_EXE, out = (dir / "report").string();
  const std::string report = exe + " --case x --mesh " + (dir / "mesh.h5").string() + " --loop " +
                             (dir / "loop.h5").string() + " --out-dir " + out + " 2> " + (dir / "log").string();
  ASSERT_EQ(std::system(report.c_str()), 0) << slurp(dir / "log");
  ASSERT_EQ(std::system(("/usr/bin/python3 " REPORT_FIGURES_PY " " + out).c_str()), 0);
  const auto page = slurp(dir / "report" / "index.html");
  EXPECT_NE(page.find("<h2>Closing the loop</h2>"), std::string::npos);
  EXPECT_EQ(count(page, "<tr class='loop-step'"), 2u);
  EXPECT_EQ(count(page, "<tr class='loop-error'>"), 3u);
  EXPECT_NE(page.find("src='loop_residual_maps.png'"), std::string::npos);
  EXPECT_GT(std::filesystem::file_size(dir / "report" / "loop_residual_maps.png"), 1000u);
  EXPECT_NE(slurp(dir / "report" / "summary.json").find("closing the loop: BIC change"), std::string::npos);

  auto other = grid_mesh(1.01);
  stage::write(dir / "other_mesh.h5", other, Provenance{"test", {}, {}});
  const std::string refused = exe + " --case x --mesh " + (dir / "other_mesh.h5").string() + " --loop " +
                              (dir / "loop.h5").string() + " --out-dir " + out + " 2> " + (dir / "refused").string();
  const int rc = std::system(refused.c_str());
  EXPECT_EQ(WEXITSTATUS(rc), 2);
  const auto line = slurp(dir / "refused");
  EXPECT_NE(line.find("was made from another"), std::string::npos) << line;
  EXPECT_EQ(count(line, "error:"), 1u) << line;
}

}  // namespace
}  // namespace finverse::report
