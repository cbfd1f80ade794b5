// Fin model from mesh.h5, the materials file, loads.h5 and motion.h5 (see fin_model.hpp).
#include "fem/io/fin_model.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "fem/corotational_shell.hpp"
#include "fem/errors.hpp"

namespace finverse::fem::io {

namespace {
int node_index(std::int32_t v, int nodes, const std::string& source, const std::string& dataset, size_t row) {
  if (v < 0 || v >= nodes) {
    std::ostringstream os;
    os << source << ": " << dataset << "[" << row << "] names node " << v << ", expected 0.." << nodes - 1;
    throw InvalidInput(os.str());
  }
  return v;
}
}  // namespace

FinModel build_fin_model(const stage::Mesh& mesh, const MaterialSpec& spec, const std::string& source) {
  FinModel fm;
  Model& m = fm.model;
  const int nv = static_cast<int>(mesh.points.dim(0));
  for (int i = 0; i < nv; ++i) m.add_node(Vec3(mesh.points(i, 0), mesh.points(i, 1), mesh.points(i, 2)));
  fm.membrane_region = m.add_material(spec.membrane);

  // Shells; area-weighted node normals orient the beam sections (width in the fin plane).
  const size_t ntri = mesh.triangles.shape.empty() ? 0 : mesh.triangles.dim(0);
  std::vector<Vec3> normal(nv, Vec3::Zero());
  for (size_t e = 0; e < ntri; ++e) {
    int n[3];
    for (int a = 0; a < 3; ++a) n[a] = node_index(mesh.triangles(e, a), nv, source, "/triangles", e);
    const auto& X = m.reference_positions();
    const Vec3 an = (X[n[1]] - X[n[0]]).cross(X[n[2]] - X[n[0]]);
    if (!(an.norm() > 0)) throw InvalidInput(source + ": /triangles[" + std::to_string(e) + "] is degenerate");
    for (int a : n) normal[a] += an;
    const int r = mesh.shell_region.data[e];
    int region = fm.membrane_region;
    if (r != 0) {
      auto it = fm.shell_region.find(r);
      if (it == fm.shell_region.end()) {
        auto sm = spec.shell_region.find(r);
        if (sm == spec.shell_region.end())
          throw InvalidInput(source + ": /shell/region uses region " + std::to_string(r) +
                             ", which the materials file does not define (shell_region)");
        it = fm.shell_region.emplace(r, m.add_material(sm->second)).first;
      }
      region = it->second;
    }
    fm.shell_element.push_back(
        m.add_element(std::make_unique<CorotationalShell>(n[0], n[1], n[2], X[n[0]], X[n[1]], X[n[2]],
                                                          m.materials()[region], mesh.shell_thickness.data[e]),
                      region));
  }

  const size_t nb = mesh.beam_elements.shape.empty() ? 0 : mesh.beam_elements.dim(0);
  for (size_t e = 0; e < nb; ++e) {
    const int a = node_index(mesh.beam_elements(e, 0), nv, source, "/beams/elements", e);
    const int b = node_index(mesh.beam_elements(e, 1), nv, source, "/beams/elements", e);
    const int ray = mesh.beam_ray.data[e];
    auto it = fm.ray_region.find(ray);
    if (it == fm.ray_region.end()) it = fm.ray_region.emplace(ray, m.add_material(spec.ray_material(ray))).first;
    const Vec3 axis = m.reference_positions()[b] - m.reference_positions()[a];
    Vec3 hint = (normal[a] + normal[b]).cross(axis);
    if (!(hint.norm() > 1e-12 * axis.norm() * (normal[a] + normal[b]).norm())) {
      // No shell around: any direction not parallel to the beam.
      hint = std::abs(axis.normalized().y()) < 0.9 ? Vec3(0, 1, 0) : Vec3(1, 0, 0);
    }
    const TaperedRectangle section{{mesh.beam_width(e, 0), mesh.beam_width(e, 1)},
                                   {mesh.beam_thickness(e, 0), mesh.beam_thickness(e, 1)}};
    const double s_mid = 0.5 * (mesh.beam_s(e, 0) + mesh.beam_s(e, 1));
    const Material& rm = m.materials()[it->second];
    const double E = s_mid >= spec.distal_s_from ? rm.youngs_modulus * spec.distal_factor : rm.youngs_modulus;
    fm.beam_element.push_back(m.add_beam(a, b, it->second, section, hint, E));
  }
  // A material for a ray the mesh lacks is a mistake (another fin's file), not a default to skip.
  for (const auto& [id, material] : spec.ray)
    if (fm.ray_region.find(id) == fm.ray_region.end())
      throw InvalidInput(spec.source + ": \"ray\" gives ray " + std::to_string(id) + ", which " + source +
                         " does not have (its beams/ray holds " + std::to_string(fm.ray_region.size()) + " rays)");

  for (const auto& ms : spec.modulations) {
    const std::string& t = ms.target;
    if (t == "membrane") {
      m.set_region_modulation(fm.membrane_region, ms.modulation);
    } else if (t == "rays") {
      for (const auto& [id, region] : fm.ray_region) m.set_region_modulation(region, ms.modulation);
    } else {
      std::istringstream is(t);
      std::string kind;
      int id = -1;
      is >> kind >> id;
      const auto& table = kind == "ray" ? fm.ray_region : fm.shell_region;
      auto it = table.find(id);
      if ((kind != "ray" && kind != "shell_region") || it == table.end())
        throw InvalidInput("materials: modulation target '" + t +
                           "' names no region of the mesh (membrane, rays, ray <id>, shell_region <id>)");
      m.set_region_modulation(it->second, ms.modulation);
    }
  }

  if (mesh.root_nodes.data.empty())
    throw InvalidInput(source + ": /root_nodes is empty: the fin would be unconstrained");
  for (size_t i = 0; i < mesh.root_nodes.data.size(); ++i)
    m.fix_node(node_index(mesh.root_nodes.data[i], nv, source, "/root_nodes", i));
  return fm;
}

double apply_loads(Model& model, const stage::Loads& loads, double ramp, const std::string& source) {
  const size_t nt = loads.time.data.size(), nv = static_cast<size_t>(model.node_count());
  if (loads.nodal_force.dim(1) != nv)
    throw InvalidInput(source + ": /nodal_force has " + std::to_string(loads.nodal_force.dim(1)) +
                       " nodes, the mesh " + std::to_string(nv));
  std::vector<Eigen::VectorXd> f(nt, Eigen::VectorXd::Zero(kDofsPerNode * nv));
  for (size_t k = 0; k < nt; ++k)
    for (size_t i = 0; i < nv; ++i)
      for (int d = 0; d < 3; ++d) f[k](kDofsPerNode * i + d) = loads.nodal_force(k, i, d);
  // A force on a prescribed DOF is taken up by the support, not by the structure: measured here
  // so that the caller can say so (once) instead of dropping it silently.
  double dropped = 0;
  for (const auto& p : model.prescribed())
    if (p.dof < 3)
      for (size_t k = 0; k < nt; ++k) dropped = std::max(dropped, std::abs(f[k](kDofsPerNode * p.node + p.dof)));
  try {
    model.set_load_history(LoadHistory(loads.time.data, std::move(f), ramp));
  } catch (const InvalidInput& e) {
    throw InvalidInput(source + ": " + e.what());
  }
  return dropped;
}

void apply_root_motion(Model& model, const stage::Mesh& mesh, const stage::Motion& motion,
                       RootRotation rotation, double ramp, const std::string& source) {
  const size_t nf = motion.time.data.size(), nv = static_cast<size_t>(model.node_count());
  if (motion.points.dim(1) != nv)
    throw InvalidInput(source + ": /points has " + std::to_string(motion.points.dim(1)) +
                       " nodes, the mesh " + std::to_string(nv));
  std::vector<int> root(mesh.root_nodes.data.begin(), mesh.root_nodes.data.end());
  std::vector<Vec3> X;
  for (int n : root) X.push_back(model.reference_positions()[n]);
  std::vector<std::vector<Vec3>> positions(nf);
  for (size_t k = 0; k < nf; ++k)
    for (int n : root)
      positions[k].emplace_back(motion.points(k, n, 0), motion.points(k, n, 1), motion.points(k, n, 2));
  // The rotation is fitted to the root nodes and, per ray, a point one element along the ray's
  // tangent at the root: the root nodes alone lie on the pitch axis and cannot see the pitch
  // (root_motion.hpp). The rays leave the clamp with its rotation; the tangent at the root comes
  // from the quadratic through the ray's first three nodes, exact for a rigid motion and for a
  // constant curvature, so the root's own bending under the loads does not leak into the
  // rotation (the chord of the first element alone would tilt by half that element's bend). A
  // ray of one element gives its chord; without beams at the root, the nodes of every element
  // there (first order).
  const auto& Xref = model.reference_positions();
  auto point = [&](size_t k, int n) {
    return Vec3(motion.points(k, static_cast<size_t>(n), 0), motion.points(k, static_cast<size_t>(n), 1),
                motion.points(k, static_cast<size_t>(n), 2));
  };
  std::vector<char> is_root(nv, 0);
  for (int n : root) is_root[static_cast<size_t>(n)] = 1;
  std::vector<std::vector<int>> beam_neighbours(nv);
  for (const auto& e : model.elements())
    if (e->type() == "corotational_beam") {
      const auto en = e->nodes();
      beam_neighbours[static_cast<size_t>(en[0])].push_back(en[1]);
      beam_neighbours[static_cast<size_t>(en[1])].push_back(en[0]);
    }
  // Per support point: nodes (r, n1, n2) and weights of the tangent at r (n2 < 0: the chord r-n1).
  struct Tangent {
    int r, n1, n2;
    double w0, w1, w2, length;
  };
  std::vector<Tangent> tangents;
  for (int r : root)
    for (int n1 : beam_neighbours[static_cast<size_t>(r)]) {
      if (is_root[static_cast<size_t>(n1)]) continue;
      int n2 = -1;
      for (int c : beam_neighbours[static_cast<size_t>(n1)])
        if (c != r && !is_root[static_cast<size_t>(c)]) n2 = c;
      const double s1 = (Xref[n1] - Xref[r]).norm();
      Tangent t{r, n1, n2, -1 / s1, 1 / s1, 0, s1};
      if (n2 >= 0) {
        const double s2 = s1 + (Xref[n2] - Xref[n1]).norm();
        t.w0 = -(1 / s1 + 1 / s2);
        t.w1 = s2 / (s1 * (s2 - s1));
        t.w2 = -s1 / (s2 * (s2 - s1));
      }
      tangents.push_back(t);
    }
  RotationSupport support;
  if (rotation == RootRotation::per_ray && tangents.empty())
    throw InvalidInput(source + ": --root-rotation per_ray needs rays (beams) leaving the root nodes; the mesh has none");
  if (rotation != RootRotation::zero) {
    auto tip = [&](const Tangent& t, auto&& at) {
      Vec3 d = t.w0 * at(t.r) + t.w1 * at(t.n1);
      if (t.n2 >= 0) d += t.w2 * at(t.n2);
      return d;
    };
    if (!tangents.empty()) {
      std::vector<double> scale;
      for (const Tangent& t : tangents) {
        const Vec3 D = tip(t, [&](int n) { return Xref[n]; });
        scale.push_back(t.length / D.norm());
        support.reference.push_back(Xref[t.r] + scale.back() * D);
        support.root_index.push_back(
            static_cast<int>(std::find(root.begin(), root.end(), t.r) - root.begin()));
      }
      support.positions.resize(nf);
      for (size_t k = 0; k < nf; ++k)
        for (size_t i = 0; i < tangents.size(); ++i)
          support.positions[k].push_back(point(k, tangents[i].r) +
                                         scale[i] * tip(tangents[i], [&](int n) { return point(k, n); }));
    } else {
      std::vector<char> is_support(nv, 0);
      for (const auto& e : model.elements()) {
        const auto en = e->nodes();
        if (std::none_of(en.begin(), en.end(), [&](int n) { return is_root[static_cast<size_t>(n)] != 0; })) continue;
        for (int n : en)
          if (!is_root[static_cast<size_t>(n)]) is_support[static_cast<size_t>(n)] = 1;
      }
      for (size_t n = 0; n < nv; ++n)
        if (is_support[n]) support.reference.push_back(Xref[n]);
      if (!support.reference.empty()) {
        support.positions.resize(nf);
        for (size_t k = 0; k < nf; ++k)
          for (size_t n = 0; n < nv; ++n)
            if (is_support[n]) support.positions[k].push_back(point(k, static_cast<int>(n)));
      }
    }
  }
  try {
    RootMotion(root, X, motion.time.data, positions, rotation, ramp, support).apply(model);
  } catch (const InvalidInput& e) {
    throw InvalidInput(source + ": " + e.what());
  }
}

}  // namespace finverse::fem::io
