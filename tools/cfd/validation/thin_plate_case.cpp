// Heaving and pitching rigid thin plate as mesh.h5 / motion.h5 (see thin_plate_case.hpp).
#include "cfd/validation/thin_plate_case.hpp"

#include <cmath>
#include <numbers>

#include "cfd/immersed/thin_body.hpp"
#include "core/error.hpp"

namespace finverse::cfd::io {

ThinPlateFiles make_thin_plate(const ThinPlateSetup& s) {
  if (!(s.chord > 0 && s.span > 0 && s.thickness > 0 && s.period > 0) || s.nx < 1 || s.nz < 1 || s.frames < 2)
    throw Error("thin plate: chord, span, thickness, period must be positive, nx, nz >= 1, frames >= 2");
  const int nx = s.nx, nz = s.nz;
  const auto nv = static_cast<std::size_t>((nx + 1) * (nz + 1));
  auto node = [&](int i, int k) { return k * (nx + 1) + i; };
  ThinPlateFiles f;
  stage::Mesh& m = f.mesh;
  m.points = NdArray<double>({nv, 3}, 0.0);
  for (int k = 0; k <= nz; ++k)
    for (int i = 0; i <= nx; ++i) {
      m.points(static_cast<std::size_t>(node(i, k)), 0) = s.chord * i / nx;
      m.points(static_cast<std::size_t>(node(i, k)), 2) = s.span * k / nz;
    }
  // Counter-clockwise in (x, z); diagonals alternate so the mesh has no preferred direction.
  std::vector<std::array<int, 3>> tri;
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      const int a = node(i, k), b = node(i + 1, k), c = node(i + 1, k + 1), d = node(i, k + 1);
      if ((i + k) % 2 == 0) {
        tri.push_back({a, b, c});
        tri.push_back({a, c, d});
      } else {
        tri.push_back({a, b, d});
        tri.push_back({b, c, d});
      }
    }
  const std::size_t nt = tri.size();
  m.triangles = NdArray<std::int32_t>({nt, 3});
  for (std::size_t t = 0; t < nt; ++t)
    for (std::size_t q = 0; q < 3; ++q) m.triangles(t, q) = tri[t][q];
  m.shell_thickness = NdArray<double>({nt}, s.thickness);
  m.shell_region = NdArray<std::int32_t>({nt}, 0);
  // One ray along the leading edge, root to tip; its nodes are the prescribed root.
  const auto nb = static_cast<std::size_t>(nz);
  m.beam_elements = NdArray<std::int32_t>({nb, 2});
  m.beam_ray = NdArray<std::int32_t>({nb}, 1);
  m.beam_s = NdArray<double>({nb, 2});
  m.beam_thickness = NdArray<double>({nb, 2}, s.thickness);
  m.beam_width = NdArray<double>({nb, 2}, s.thickness);
  m.root_nodes = NdArray<std::int32_t>({static_cast<std::size_t>(nz + 1)});
  for (int k = 0; k < nz; ++k) {
    const auto b = static_cast<std::size_t>(k);
    m.beam_elements(b, 0) = node(0, k);
    m.beam_elements(b, 1) = node(0, k + 1);
    m.beam_s(b, 0) = static_cast<double>(k) / nz;
    m.beam_s(b, 1) = static_cast<double>(k + 1) / nz;
  }
  for (int k = 0; k <= nz; ++k) m.root_nodes(static_cast<std::size_t>(k)) = node(0, k);

  const ThinBody body = build_thin_body(tri, static_cast<int>(nv), s.thickness, "thin plate");
  std::vector<Vec3> rest(nv);
  for (std::size_t i = 0; i < nv; ++i) rest[i] = {m.points(i, 0), m.points(i, 1), m.points(i, 2)};
  const SurfaceState placed = place_thin_body(body, rest, {}, {}, tri);
  const std::size_t nvi = body.source_node.size();
  m.ibm_points = NdArray<double>({nvi, 3});
  m.ibm_source_node = NdArray<std::int32_t>({nvi});
  m.ibm_offset_sign = NdArray<std::int32_t>({nvi});
  for (std::size_t i = 0; i < nvi; ++i) {
    for (std::size_t d = 0; d < 3; ++d) m.ibm_points(i, d) = placed.surface.points[i][d];
    m.ibm_source_node(i) = body.source_node[i];
    m.ibm_offset_sign(i) = body.offset_sign[i];
  }
  m.ibm_triangles = NdArray<std::int32_t>({body.triangles.size(), 3});
  for (std::size_t t = 0; t < body.triangles.size(); ++t)
    for (std::size_t q = 0; q < 3; ++q) m.ibm_triangles(t, q) = body.triangles[t][q];
  m.ibm_thickness = s.thickness;
  m.chord = s.chord;

  // Rigid motion: rotation theta about the z axis through (pivot, 0), then heave along y.
  const auto nf = static_cast<std::size_t>(s.frames);
  const double w = 2 * std::numbers::pi / s.period;
  stage::Motion& q = f.motion;
  q.time = NdArray<double>({nf});
  q.points = NdArray<double>({nf, nv, 3});
  q.velocity = NdArray<double>({nf, nv, 3});
  q.period = s.period;
  for (std::size_t k = 0; k < nf; ++k) {
    const double t = s.period * static_cast<double>(k) / static_cast<double>(nf);
    q.time(k) = t;
    const double th = s.pitch * std::sin(w * t + s.phase), dth = s.pitch * w * std::cos(w * t + s.phase);
    const double y = s.heave * std::sin(w * t), dy = s.heave * w * std::cos(w * t);
    for (std::size_t i = 0; i < nv; ++i) {
      const double r = m.points(i, 0) - s.pivot;
      q.points(k, i, 0) = s.pivot + r * std::cos(th);
      q.points(k, i, 1) = y + r * std::sin(th);
      q.points(k, i, 2) = m.points(i, 2);
      q.velocity(k, i, 0) = -r * std::sin(th) * dth;
      q.velocity(k, i, 1) = dy + r * std::cos(th) * dth;
      q.velocity(k, i, 2) = 0;
    }
  }
  return f;
}

nlohmann::json describe(const ThinPlateSetup& p) {
  return {{"chord", p.chord},         {"span", p.span},     {"nx", p.nx},        {"nz", p.nz},
          {"thickness", p.thickness}, {"heave", p.heave},   {"pitch", p.pitch},  {"phase", p.phase},
          {"pivot", p.pivot},         {"period", p.period}, {"frames", p.frames}};
}

}  // namespace finverse::cfd::io
