// Fin layout from mesh.h5 and the effect steps of the apps (see fin_layout.hpp).
#include "fem/io/fin_layout.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "fem/errors.hpp"

namespace finverse::fem::io {

FinLayout make_fin_layout(const stage::Mesh& mesh, const std::string& source) {
  FinLayout L;
  const std::size_t nv = mesh.points.shape.empty() ? 0 : mesh.points.dim(0);
  auto X = [&](std::size_t i) { return Vec3(mesh.points(i, 0), mesh.points(i, 1), mesh.points(i, 2)); };
  const std::size_t ntri = mesh.triangles.shape.empty() ? 0 : mesh.triangles.dim(0);
  const std::size_t nb = mesh.beam_elements.shape.empty() ? 0 : mesh.beam_elements.dim(0);
  if (nb == 0) throw InvalidInput(source + ": /beams/elements is empty: the effects act on rays");
  if (mesh.root_nodes.data.empty()) throw InvalidInput(source + ": /root_nodes is empty");
  Vec3 normal = Vec3::Zero();
  for (std::size_t e = 0; e < ntri; ++e) {
    L.shell_elements.push_back(static_cast<int>(e));
    const auto a = static_cast<std::size_t>(mesh.triangles(e, 0)), b = static_cast<std::size_t>(mesh.triangles(e, 1)),
               c = static_cast<std::size_t>(mesh.triangles(e, 2));
    if (a >= nv || b >= nv || c >= nv) throw InvalidInput(source + ": /triangles names a node out of range");
    Vec3 n = (X(b) - X(a)).cross(X(c) - X(a));
    if (normal.dot(n) < 0) n = -n;  // a consistent side whatever the winding
    normal += n;
  }
  std::map<int, std::pair<double, Vec3>> ray_root;  // ray -> (smallest s, its node's position)
  for (std::size_t e = 0; e < nb; ++e) {
    FinLayout::Beam b;
    b.element = static_cast<int>(ntri + e);
    b.ray = mesh.beam_ray.data[e];
    b.node0 = mesh.beam_elements(e, 0);
    b.node1 = mesh.beam_elements(e, 1);
    if (b.node0 < 0 || b.node1 < 0 || static_cast<std::size_t>(std::max(b.node0, b.node1)) >= nv)
      throw InvalidInput(source + ": /beams/elements names a node out of range");
    b.s0 = mesh.beam_s(e, 0);
    b.s1 = mesh.beam_s(e, 1);
    L.beams.push_back(b);
    L.ray_length[b.ray] += (X(static_cast<std::size_t>(b.node1)) - X(static_cast<std::size_t>(b.node0))).norm();
    const bool first = b.s0 <= b.s1;
    const double s = std::min(b.s0, b.s1);
    const Vec3 at = X(static_cast<std::size_t>(first ? b.node0 : b.node1));
    auto [it, fresh] = ray_root.emplace(b.ray, std::make_pair(s, at));
    if (!fresh && s < it->second.first) it->second = {s, at};
  }
  for (const auto& [ray, len] : L.ray_length)
    if (!(len > 0)) throw InvalidInput(source + ": /beams/s: ray " + std::to_string(ray) + " has no length");
  // Dorsal (largest z) first, eta = +1 .. -1 linear in the rank (as root_drive_file.cpp).
  std::vector<std::pair<double, int>> order;
  for (const auto& [ray, r] : ray_root) order.emplace_back(-r.second.z(), ray);
  std::sort(order.begin(), order.end());
  const double n = static_cast<double>(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const double eta = order.size() > 1 ? 1.0 - 2.0 * static_cast<double>(k) / (n - 1) : 0.0;
    L.ray_eta[order[k].second] = eta;
    L.ray_group[order[k].second] = eta > 1.0 / 3 ? RayGroup::dorsal : eta < -1.0 / 3 ? RayGroup::ventral : RayGroup::middle;
  }
  Vec3 centre = Vec3::Zero();
  for (auto r : mesh.root_nodes.data) {
    if (r < 0 || static_cast<std::size_t>(r) >= nv) throw InvalidInput(source + ": /root_nodes names a node out of range");
    L.root_nodes.push_back(r);
    centre += X(static_cast<std::size_t>(r));
  }
  L.root_centre = centre / static_cast<double>(L.root_nodes.size());
  L.span_axis = Vec3(0, 0, 1);
  normal -= normal.dot(L.span_axis) * L.span_axis;
  L.normal = normal.norm() > 0 ? Vec3(normal.normalized()) : Vec3(0, 1, 0);
  if (L.normal.y() < 0) L.normal = -L.normal;
  L.chord_axis = L.normal.cross(L.span_axis);
  Vec3 out = Vec3::Zero();
  for (std::size_t i = 0; i < nv; ++i) out += X(i) - L.root_centre;
  if (out.dot(L.chord_axis) < 0) L.chord_axis = -L.chord_axis;
  return L;
}

void reshape_mesh(stage::Mesh& mesh, const Effects& effects, const FinLayout& layout) {
  const std::size_t nv = mesh.points.dim(0);
  std::vector<Vec3> rest(nv);
  for (std::size_t i = 0; i < nv; ++i) rest[i] = Vec3(mesh.points(i, 0), mesh.points(i, 1), mesh.points(i, 2));
  for (const auto& e : effects) e->reshape(rest, layout);
  // The immersed-boundary body follows its source node (ibm/source_node), so the FSI sees the
  // same rest shape as the structure.
  const std::size_t ni = mesh.ibm_points.shape.empty() ? 0 : mesh.ibm_points.dim(0);
  if (mesh.ibm_source_node.data.size() == ni)
    for (std::size_t i = 0; i < ni; ++i) {
      const auto src = static_cast<std::size_t>(mesh.ibm_source_node.data[i]);
      if (src >= nv) throw InvalidInput("mesh: /ibm/source_node names a node out of range");
      for (int d = 0; d < 3; ++d) mesh.ibm_points(i, static_cast<std::size_t>(d)) += rest[src](d) - mesh.points(src, static_cast<std::size_t>(d));
    }
  for (std::size_t i = 0; i < nv; ++i)
    for (int d = 0; d < 3; ++d) mesh.points(i, static_cast<std::size_t>(d)) = rest[i](d);
}

void apply_effects(Model& model, const Effects& effects, const FinLayout& layout) {
  for (const auto& b : layout.beams) {
    if (b.element >= static_cast<int>(model.elements().size()))
      throw InvalidInput("effects: the model has no element " + std::to_string(b.element) + " (a ray of the mesh)");
    const auto nodes = model.element(b.element).nodes();
    if (nodes.size() != 2 || nodes[0] != b.node0 || nodes[1] != b.node1)
      throw InvalidInput("effects: model element " + std::to_string(b.element) + " is not the mesh's ray element");
  }
  for (const auto& e : effects) e->apply(model, layout);
}

}  // namespace finverse::fem::io
