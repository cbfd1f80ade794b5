// Reading and cross-checking mesh.h5 + motion.h5 into the moving thin body (see fin_input.hpp).
#include "cfd/io/fin_input.hpp"

#include <algorithm>
#include <cmath>

#include "cfd/immersed/periodic_low_pass.hpp"
#include "core/error.hpp"
#include "core/stage_identity.hpp"

namespace finverse::cfd::io {

namespace {

std::vector<Vec3> rows3(const NdArray<double>& a, std::size_t offset, std::size_t n) {
  std::vector<Vec3> out(n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t d = 0; d < 3; ++d) out[i][d] = a.data[offset + 3 * i + d];
  return out;
}

std::vector<std::array<int, 3>> triangles_of(const NdArray<std::int32_t>& t) {
  std::vector<std::array<int, 3>> out(t.dim(0));
  for (std::size_t i = 0; i < out.size(); ++i)
    for (std::size_t k = 0; k < 3; ++k) out[i][k] = t(i, k);
  return out;
}

double norm(const Vec3& a) { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

}  // namespace

ThinBody thin_body_from_mesh(const stage::Mesh& mesh, const std::string& name, double* rest_mismatch) {
  // Optional in the contract (a structural mesh has no flow surface), required here.
  for (const auto& [dataset, size] : {std::pair{"points", mesh.ibm_points.size()},
                                      {"triangles", mesh.ibm_triangles.size()},
                                      {"source_node", mesh.ibm_source_node.size()},
                                      {"offset_sign", mesh.ibm_offset_sign.size()}})
    if (size == 0)
      throw Error(name + ": /ibm/" + dataset +
                  ": missing, expected the closed thin body the flow immerses (fin-mesh "
                  "writes it; a structural mesh has none)");
  const std::size_t nv = mesh.points.dim(0), nvi = mesh.ibm_points.dim(0);
  const auto mid = triangles_of(mesh.triangles);
  for (std::size_t t = 0; t < mid.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (mid[t][k] < 0 || mid[t][k] >= static_cast<int>(nv))
        throw Error(name + ": /triangles[" + std::to_string(t) + "] has node " + std::to_string(mid[t][k]) +
                    ", expected 0.." + std::to_string(nv - 1));
  ThinBody b;
  b.node_count = static_cast<int>(nv);
  b.triangles = triangles_of(mesh.ibm_triangles);
  b.source_node.assign(mesh.ibm_source_node.data.begin(), mesh.ibm_source_node.data.end());
  b.offset_sign.assign(mesh.ibm_offset_sign.data.begin(), mesh.ibm_offset_sign.data.end());
  for (std::size_t i = 0; i < nvi; ++i) {
    if (b.source_node[i] < 0 || b.source_node[i] >= static_cast<int>(nv))
      throw Error(name + ": /ibm/source_node[" + std::to_string(i) + "] = " + std::to_string(b.source_node[i]) +
                  ", expected a node 0.." + std::to_string(nv - 1));
    if (b.offset_sign[i] < -1 || b.offset_sign[i] > 1)
      throw Error(name + ": /ibm/offset_sign[" + std::to_string(i) + "] = " + std::to_string(b.offset_sign[i]) +
                  ", expected -1, 0 or +1");
  }
  check_watertight(b.triangles, static_cast<int>(nvi), name + ": /ibm/triangles");

  // Side convention and thickness from the rest geometry: offset = sign * normal_sign * t/2 * n.
  const auto rest = rows3(mesh.points, 0, nv);
  const auto ibm = rows3(mesh.ibm_points, 0, nvi);
  const VertexNormals n = vertex_normals(rest, {}, {}, mid);
  double along = 0, offset_sum = 0;
  std::size_t offset_count = 0;
  for (std::size_t i = 0; i < nvi; ++i) {
    if (b.offset_sign[i] == 0) continue;
    const auto s = static_cast<std::size_t>(b.source_node[i]);
    const Vec3 d{ibm[i][0] - rest[s][0], ibm[i][1] - rest[s][1], ibm[i][2] - rest[s][2]};
    along += b.offset_sign[i] * (d[0] * n.n[s][0] + d[1] * n.n[s][1] + d[2] * n.n[s][2]);
    offset_sum += norm(d);
    ++offset_count;
  }
  if (offset_count == 0 || along == 0)
    throw Error(name + ": /ibm/points: no vertex lies off the mid-surface (offset_sign all 0 or zero thickness)");
  b.normal_sign = along > 0 ? 1 : -1;
  b.thickness = mesh.ibm_thickness ? *mesh.ibm_thickness : 2 * offset_sum / static_cast<double>(offset_count);
  if (!(std::isfinite(b.thickness) && b.thickness > 0))
    throw Error(name + ": attribute ibm_thickness = " + std::to_string(b.thickness) + " m, expected > 0");
  const SurfaceState placed = place_thin_body(b, rest, {}, {}, mid);
  double worst = 0;
  std::size_t worst_i = 0;
  for (std::size_t i = 0; i < nvi; ++i) {
    const Vec3& p = placed.surface.points[i];
    const double e = norm({p[0] - ibm[i][0], p[1] - ibm[i][1], p[2] - ibm[i][2]});
    if (e > worst) worst = e, worst_i = i;
  }
  if (rest_mismatch) *rest_mismatch = worst;
  if (worst > 1e-6 * b.thickness)
    throw Error(name + ": /ibm/points[" + std::to_string(worst_i) + "] lies " + std::to_string(worst) +
                " m from its source node offset by offset_sign * ibm_thickness/2 (" + std::to_string(b.thickness / 2) +
                " m) along the mid-surface normal: not the closed thin body of /points");
  return b;
}

FinInput make_fin_input(const stage::Mesh& mesh, const stage::Motion& motion, const std::string& mesh_name,
                        const std::string& motion_name, int motion_harmonics) {
  FinInput in;
  const std::size_t nv = mesh.points.dim(0);
  if (motion.points.rank() != 3 || motion.points.dim(1) != nv)
    throw Error(motion_name + ": /points has " + std::to_string(motion.points.rank() == 3 ? motion.points.dim(1) : 0) +
                " nodes per frame, " + mesh_name + " /points has " + std::to_string(nv));
  const std::size_t nf = motion.time.size();
  if (nf < 2) throw Error(motion_name + ": /time has " + std::to_string(nf) + " frames, expected at least 2");
  for (std::size_t k = 1; k < nf; ++k)
    if (!(motion.time(k) > motion.time(k - 1)))
      throw Error(motion_name + ": /time is not strictly increasing at frame " + std::to_string(k) + " (" +
                  std::to_string(motion.time(k - 1)) + " s, then " + std::to_string(motion.time(k)) + " s)");
  in.frame_time = motion.time.data;
  in.period = motion.period;
  in.chord = mesh.chord;
  in.rest = rows3(mesh.points, 0, nv);
  in.mid_triangles = triangles_of(mesh.triangles);
  ThinBody body = thin_body_from_mesh(mesh, mesh_name, &in.rest_mismatch);
  for (const auto& t : in.mid_triangles) {
    const Vec3 &a = in.rest[t[0]], &b = in.rest[t[1]], &c = in.rest[t[2]];
    const Vec3 e1{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    in.reference_area +=
        0.5 * norm({e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]});
  }

  in.layout = periodic_layout(motion.time.data, motion.period);
  if (in.layout.frames < nf) {
    // The last frame sits one whole number of periods after the first: it must repeat it.
    double size = 0, worst = 0;
    for (std::size_t i = 0; i < 3 * nv; ++i) {
      size = std::max(size, std::abs(motion.points.data[i]));
      worst = std::max(worst, std::abs(motion.points.data[(nf - 1) * 3 * nv + i] - motion.points.data[i]));
    }
    if (worst > 1e-6 * std::max(size, body.thickness))
      throw Error(motion_name + ": /points: the last frame lies a whole number of periods T after the first but differs "
                  "from it by up to " + std::to_string(worst) + " m (periodic data expected)");
  }
  const std::vector<double> values =
      motion_harmonics > 0
          ? periodic_low_pass(motion, in.layout, motion_harmonics, motion_name)
          : std::vector<double>(motion.points.data.begin(),
                                motion.points.data.begin() + static_cast<std::ptrdiff_t>(in.layout.frames * 3 * nv));
  const std::vector<double> knots(motion.time.data.begin(),
                                  motion.time.data.begin() + static_cast<std::ptrdiff_t>(in.layout.frames));
  TimeSpline spline(knots, values, 3 * nv, in.layout.wrap, motion_name);
  in.motion = std::make_shared<const FinSurfaceMotion>(std::move(body), in.mid_triangles, std::move(spline));
  return in;
}

FinInput read_fin_input(const std::filesystem::path& mesh, const std::filesystem::path& motion, int motion_harmonics) {
  const auto m = stage::read<stage::Mesh>(mesh);
  const auto q = stage::read<stage::Motion>(motion);
  check_made_from(motion, mesh);  // the motion carried onto this mesh, not another template's
  return make_fin_input(m, q, mesh.string(), motion.string(), motion_harmonics);
}

}  // namespace finverse::cfd::io
