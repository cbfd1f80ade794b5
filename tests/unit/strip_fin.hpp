// A small fin-like strip as stage files (mesh.h5, loads.h5), shared by the file-driven tests of
// fin-fem run (tests/unit/fem/test_file_run.cpp) and fin-fit run (tests/unit/fit): rays along x
// (one per grid row), membrane shells between them, root (leading edge) at x = 0.
#pragma once

#include <cstdint>
#include <vector>

#include "core/stage_files.hpp"

namespace finverse::test::strip {

inline constexpr int nx = 4, nz = 2;
inline constexpr double chord = 0.08, span = 0.04;

inline int node(int i, int j) { return j * (nx + 1) + i; }

inline stage::Mesh strip_mesh() {
  stage::Mesh m;
  const size_t nv = (nx + 1) * (nz + 1);
  m.points = NdArray<double>({nv, 3});
  for (int j = 0; j <= nz; ++j)
    for (int i = 0; i <= nx; ++i) {
      m.points(node(i, j), 0) = chord * i / nx;
      m.points(node(i, j), 2) = span * j / nz;
    }
  std::vector<std::int32_t> tri;
  for (int j = 0; j < nz; ++j)
    for (int i = 0; i < nx; ++i) {
      tri.insert(tri.end(), {node(i, j), node(i + 1, j), node(i + 1, j + 1)});
      tri.insert(tri.end(), {node(i, j), node(i + 1, j + 1), node(i, j + 1)});
    }
  const size_t nt = tri.size() / 3;
  m.triangles = NdArray<std::int32_t>({nt, 3}, tri);
  m.shell_thickness = NdArray<double>({nt}, 2e-4);
  m.shell_region = NdArray<std::int32_t>({nt}, 0);
  std::vector<std::int32_t> be, ray;
  std::vector<double> s;
  for (int j = 0; j <= nz; ++j)
    for (int i = 0; i < nx; ++i) {
      be.insert(be.end(), {node(i, j), node(i + 1, j)});
      ray.push_back(j + 1);
      s.insert(s.end(), {double(i) / nx, double(i + 1) / nx});
    }
  const size_t nb = ray.size();
  m.beam_elements = NdArray<std::int32_t>({nb, 2}, be);
  m.beam_ray = NdArray<std::int32_t>({nb}, ray);
  m.beam_s = NdArray<double>({nb, 2}, s);
  m.beam_thickness = NdArray<double>({nb, 2}, 1e-3);
  m.beam_width = NdArray<double>({nb, 2}, 2e-3);
  std::vector<std::int32_t> root;
  for (int j = 0; j <= nz; ++j) root.push_back(node(0, j));
  m.root_nodes = NdArray<std::int32_t>({root.size()}, root);
  m.ibm_points = m.points;
  m.ibm_triangles = m.triangles;
  m.ibm_source_node = NdArray<std::int32_t>({nv});
  for (size_t i = 0; i < nv; ++i) m.ibm_source_node.data[i] = static_cast<std::int32_t>(i);
  m.ibm_offset_sign = NdArray<std::int32_t>({nv}, 0);
  return m;
}

// Lateral (y) force on every node growing linearly: F(t) = f0 t / t_end.
inline stage::Loads ramp_loads(double f0, int frames, double t_end) {
  stage::Loads l;
  const size_t nv = (nx + 1) * (nz + 1), nt = frames;
  l.time = NdArray<double>({nt});
  l.nodal_force = NdArray<double>({nt, nv, 3});
  l.force_total = NdArray<double>({nt, 3});
  l.thrust = l.lateral = l.vertical = NdArray<double>({nt});
  l.pressure_jump = NdArray<double>({nt, size_t(2 * nx * nz)});
  for (size_t k = 0; k < nt; ++k) {
    l.time.data[k] = t_end * k / (nt - 1);
    for (size_t i = 0; i < nv; ++i) l.nodal_force(k, i, 1) = f0 * l.time.data[k] / t_end;
  }
  l.rho = 1000;
  l.U = 0.1;
  l.reference_area = chord * span;
  return l;
}

}  // namespace finverse::test::strip
