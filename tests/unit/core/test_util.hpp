// Helpers shared by the core unit tests: a scratch directory per test (scratch_dir.hpp) and sample stage data
// with consistent dimensions.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <limits>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/nd_array.hpp"
#include "core/stage_files.hpp"
#include "../scratch_dir.hpp"

namespace finverse::test {

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Smooth, non-trivial values so that comparisons are meaningful.
inline NdArray<double> wave(std::vector<std::size_t> shape, double phase = 0) {
  NdArray<double> a(std::move(shape));
  for (std::size_t i = 0; i < a.size(); ++i) a.data[i] = std::sin(0.37 * double(i) + phase) * (1 + 1e-3 * double(i));
  return a;
}
inline NdArray<std::int32_t> counting(std::vector<std::size_t> shape, std::int32_t modulo) {
  NdArray<std::int32_t> a(std::move(shape));
  for (std::size_t i = 0; i < a.size(); ++i) a.data[i] = static_cast<std::int32_t>(i % modulo);
  return a;
}

inline stage::Motion sample_motion(std::size_t nf = 8, std::size_t nv = 30) {
  stage::Motion m;
  m.time = NdArray<double>({nf});
  for (std::size_t i = 0; i < nf; ++i) m.time.data[i] = 0.002 * double(i);
  m.points = wave({nf, nv, 3});
  m.velocity = wave({nf, nv, 3}, 1.0);
  m.period = 0.016;
  return m;
}

inline stage::Mesh sample_mesh(std::size_t nv = 30) {
  stage::Mesh m;
  const std::size_t ntri = 40, nb = 12, nvi = 64, ntri_i = 124;
  m.points = wave({nv, 3});
  m.triangles = counting({ntri, 3}, std::int32_t(nv));
  m.shell_thickness = NdArray<double>({ntri}, 2e-5);
  m.shell_region = NdArray<std::int32_t>({ntri}, 0);
  m.beam_elements = counting({nb, 2}, std::int32_t(nv));
  m.beam_ray = counting({nb}, 20);
  m.beam_s = wave({nb, 2});
  m.beam_thickness = NdArray<double>({nb, 2}, 1e-4);
  m.beam_width = NdArray<double>({nb, 2}, 2e-4);
  m.root_nodes = counting({5}, std::int32_t(nv));
  m.ibm_points = wave({nvi, 3});
  m.ibm_triangles = counting({ntri_i, 3}, std::int32_t(nvi));
  m.ibm_source_node = counting({nvi}, std::int32_t(nv));
  m.ibm_offset_sign = counting({nvi}, 2);
  m.ibm_thickness = 1e-4;
  m.chord = 0.01;
  return m;
}

inline void fill_forces(stage::Forces& f, std::size_t nt, std::size_t nv) {
  f.nodal_force = wave({nt, nv, 3});
  f.force_total = wave({nt, 3});
  f.thrust = wave({nt});
  f.lateral = wave({nt}, 0.5);
  f.vertical = wave({nt}, 0.7);
  f.rho = 1000.0;
  f.U = 0.1;
  f.reference_area = 1.5e-4;
}

inline stage::Loads sample_loads(std::size_t nt = 6, std::size_t nv = 30, std::size_t ntri = 40) {
  stage::Loads l;
  l.time = wave({nt});
  fill_forces(l, nt, nv);
  l.pressure_jump = wave({nt, ntri});
  return l;
}

inline stage::Fsi sample_fsi(std::size_t nt = 6, std::size_t nv = 30) {
  stage::Fsi f;
  f.time = wave({nt});
  f.points = wave({nt, nv, 3});
  fill_forces(f, nt, nv);
  f.coupling_iterations = counting({nt}, 7);
  f.coupling_residual = wave({nt});
  return f;
}

inline stage::Kinematics sample_kinematics(std::size_t nf = 5, std::size_t nv = 30) {
  stage::Kinematics k;
  k.template_points = wave({nv, 3});
  k.template_triangles = counting({40, 3}, std::int32_t(nv));
  k.ray_offsets = NdArray<std::int32_t>({4}, {0, 3, 6, 9});
  k.ray_vertices = counting({9}, std::int32_t(nv));
  k.time = wave({nf});
  k.points = wave({nf, nv, 3});
  k.joint_parent = NdArray<std::int32_t>({4}, {-1, 0, 1, 2});
  k.joint_rest = wave({4, 3});
  k.joint_angles = wave({nf, 4, 3});
  k.views = {"side", "back", "ventral"};
  k.silhouette_iou = wave({nf, 3});
  k.silhouette_iou(1, 2) = std::nan("");  // a missing view is allowed to be NaN
  k.reprojection_rms = wave({nf, 3});
  k.view_valid = NdArray<std::uint8_t>({nf, 3}, 1);
  k.fps = 500.0;
  return k;
}

inline stage::Materials sample_materials() {
  stage::Materials m;
  m.names = {"E_membrane", "E_ray1", "nu"};
  m.units = {"Pa", "Pa", "1"};
  m.scale = {"log10", "log10", "linear"};
  m.lower = NdArray<double>({3}, {1e6, 5e7, 0.15});
  m.upper = NdArray<double>({3}, {1e9, 5e10, 0.45});
  m.best = NdArray<double>({3}, {1.2e7, 3e8, 0.4});
  m.objective = NdArray<double>({}, {0.0123});
  m.sum_of_squares = NdArray<double>({}, {0.0004});
  m.evaluations = NdArray<std::int64_t>({}, {2345});
  m.run_method = {"ga", "cmaes"};
  m.run_seed = NdArray<std::int64_t>({2}, {1, 2});
  m.run_evaluations = NdArray<std::int64_t>({2}, {1200, 1100});
  m.run_best = wave({2, 3});
  m.run_objective = wave({2});
  m.run_generations = NdArray<std::int32_t>({2}, {30, 41});
  m.run_converged = NdArray<std::int32_t>({2}, {1, 0});
  m.run_history = wave({2, 41});
  m.run_history_evaluations = wave({2, 41});
  m.run_history_best = wave({2, 41, 3});
  for (std::size_t g = 30; g < 41; ++g) m.run_history(0, g) = std::nan("");
  m.standard_error = wave({3});
  m.standard_error(2) = std::numeric_limits<double>::infinity();  // a direction the data cannot fix
  m.ci95 = wave({3, 2});
  m.correlation = wave({3, 3});
  m.identified = NdArray<std::int32_t>({3}, {1, 1, 0});
  m.verdict = {"identified", "identified", "not identified: Jacobian rank deficient"};
  m.objective_kind = "quasi_static";
  return m;
}

inline stage::Truth sample_truth(std::size_t nf = 4, std::size_t nv = 30) {
  stage::Truth t;
  t.template_points = wave({nv, 3});
  t.template_triangles = counting({40, 3}, std::int32_t(nv));
  t.time = wave({nf});
  t.points = wave({nf, nv, 3});
  t.material_names = {"E_membrane", "nu"};
  t.material_units = {"Pa", "1"};
  t.material_values = NdArray<double>({2}, {1.2e7, 0.4});
  t.period = 0.02;
  t.effects = R"({"damping": 0.02})";
  return t;
}

inline Provenance test_provenance() { return Provenance{"core_tests", {{"case", "unit"}}, {}}; }

}  // namespace finverse::test
