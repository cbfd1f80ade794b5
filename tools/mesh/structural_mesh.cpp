// Assembly of mesh.h5's structural model from the template and the planform mesh (seed paper
// section 4.1; DESIGN.md section 4, the mesh.h5 contract in tools/core/CONTRACTS.md).
#include "mesh/structural_mesh.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace finverse::mesh {

std::vector<int> root_nodes(const FinTemplate& t, const PlanformMesh& m, double root_band) {
  if (!(std::isfinite(root_band) && root_band >= 0)) throw Error("--root-band: expected >= 0");
  const auto seg = t.root_segment();
  const double dx = seg[1][0] - seg[0][0], dz = seg[1][1] - seg[0][1];
  const double len2 = dx * dx + dz * dz;
  // Nodes on the root segment are collinear up to rounding of chord-unit coordinates.
  const double tol = root_band + 1e-9 * t.chord;
  std::vector<int> out;
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const double px = m.points[i][0] - seg[0][0], pz = m.points[i][1] - seg[0][1];
    const double u = std::clamp((px * dx + pz * dz) / len2, 0.0, 1.0);
    if (std::hypot(px - u * dx, pz - u * dz) <= tol) out.push_back(static_cast<int>(i));
  }
  return out;
}

NdArray<double> rest_points(const PlanformMesh& m) {
  NdArray<double> p({m.points.size(), 3});
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    p(i, 0) = m.points[i][0];
    p(i, 1) = 0.0;
    p(i, 2) = m.points[i][1];
  }
  return p;
}

stage::Mesh assemble_mesh(const FinTemplate& t, const PlanformMesh& m, const IbmSurface& ibm, double root_band) {
  stage::Mesh out;
  out.points = rest_points(m);
  const std::size_t nt = m.triangles.size();
  out.triangles = NdArray<std::int32_t>({nt, 3});
  for (std::size_t i = 0; i < nt; ++i)
    for (int k = 0; k < 3; ++k) out.triangles(i, k) = m.triangles[i][k];
  out.shell_thickness = NdArray<double>({nt}, t.membrane_thickness);
  out.shell_region = NdArray<std::int32_t>({nt}, 0);

  std::size_t nb = 0;
  for (const auto& chain : m.ray_nodes) nb += chain.size() - 1;
  out.beam_elements = NdArray<std::int32_t>({nb, 2});
  out.beam_ray = NdArray<std::int32_t>({nb});
  out.beam_s = NdArray<double>({nb, 2});
  out.beam_thickness = NdArray<double>({nb, 2});
  out.beam_width = NdArray<double>({nb, 2});
  std::size_t b = 0;
  for (std::size_t r = 0; r < m.ray_nodes.size(); ++r) {
    const auto& chain = m.ray_nodes[r];
    const auto& s = m.ray_node_s[r];
    for (std::size_t k = 0; k + 1 < chain.size(); ++k, ++b) {
      out.beam_ray(b) = static_cast<std::int32_t>(r + 1);
      for (int end = 0; end < 2; ++end) {
        out.beam_elements(b, end) = chain[k + end];
        out.beam_s(b, end) = s[k + end];
        const auto sec = t.section(r, s[k + end]);
        out.beam_thickness(b, end) = sec.thickness;
        out.beam_width(b, end) = sec.width;
      }
    }
  }
  const auto roots = root_nodes(t, m, root_band);
  if (roots.size() < 2) throw Error("fin-mesh: fewer than two root nodes: the fin would be free to rotate");
  out.root_nodes = NdArray<std::int32_t>({roots.size()}, std::vector<std::int32_t>(roots.begin(), roots.end()));

  const std::size_t nvi = ibm.points.size(), nti = ibm.body.triangles.size();
  out.ibm_points = NdArray<double>({nvi, 3});
  out.ibm_source_node = NdArray<std::int32_t>({nvi});
  out.ibm_offset_sign = NdArray<std::int32_t>({nvi});
  for (std::size_t i = 0; i < nvi; ++i) {
    for (int k = 0; k < 3; ++k) out.ibm_points(i, k) = ibm.points[i][k];
    out.ibm_source_node(i) = ibm.body.source_node[i];
    out.ibm_offset_sign(i) = ibm.body.offset_sign[i];
  }
  out.ibm_triangles = NdArray<std::int32_t>({nti, 3});
  for (std::size_t i = 0; i < nti; ++i)
    for (int k = 0; k < 3; ++k) out.ibm_triangles(i, k) = ibm.body.triangles[i][k];
  out.ibm_thickness = ibm.body.thickness;
  out.chord = t.chord;
  return out;
}

}  // namespace finverse::mesh
