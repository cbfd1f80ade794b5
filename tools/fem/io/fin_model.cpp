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
    m.add_element(std::make_unique<CorotationalShell>(n[0], n[1], n[2], X[n[0]], X[n[1]], X[n[2]],
                                                      m.materials()[region], mesh.shell_thickness.data[e]),
                  region);
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
    m.add_beam(a, b, it->second, section, hint, E);
  }

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
  try {
    RootMotion(root, X, motion.time.data, positions, rotation, ramp).apply(model);
  } catch (const InvalidInput& e) {
    throw InvalidInput(source + ": " + e.what());
  }
}

}  // namespace finverse::fem::io
