// The Hessenthaler (2017) flap under buoyancy alone: geometry and data from hessenthaler2017.json,
// beam or shell-strip model, load-controlled static Newton (see hessenthaler_flap.hpp).
#include "fem/validation/hessenthaler_flap.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fem/errors.hpp"
#include "fem/model.hpp"
#include "fem/static_solver.hpp"
#include "fem/corotational_shell.hpp"
#include "fem/validation/shell_meshes.hpp"

namespace finverse::fem::validation {

namespace {

double positive(const nlohmann::json& root, const std::vector<std::string>& keys,
                const std::filesystem::path& path) {
  const nlohmann::json* j = &root;
  std::string name;
  for (const auto& k : keys) {
    name += (name.empty() ? "" : ".") + k;
    if (!j->is_object() || !j->contains(k))
      throw InvalidInput(path.string() + ": missing key '" + name + "'");
    j = &(*j)[k];
  }
  if (!j->is_number() || !std::isfinite(j->get<double>()) || j->get<double>() <= 0)
    throw InvalidInput(path.string() + ": '" + name + "' must be a positive number");
  return j->get<double>();
}

}  // namespace

HessenthalerFlap read_hessenthaler_flap(const std::filesystem::path& reference) {
  std::ifstream in(reference);
  if (!in) throw InvalidInput("cannot open reference file " + reference.string());
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw InvalidInput("reference file " + reference.string() + " is not valid JSON: " + e.what());
  }
  HessenthalerFlap f;
  const double mm = 1e-3;
  f.length = positive(j, {"geometry", "flap_mm", "length"}, reference) * mm;
  f.width = positive(j, {"geometry", "flap_mm", "width"}, reference) * mm;
  f.thickness = positive(j, {"geometry", "flap_mm", "thickness"}, reference) * mm;
  f.fluid_density = positive(j, {"fluid", "density"}, reference);
  f.solid_density = positive(j, {"solid", "density"}, reference);
  f.tip_deflection_no_flow = positive(j, {"measured_tip_deflection_mm", "no_flow_buoyancy_only"}, reference) * mm;
  f.tip_deflection_phase_I = positive(j, {"measured_tip_deflection_mm", "phase_I_steady_flow"}, reference) * mm;
  f.voxel = positive(j, {"measurement_resolution", "mri_voxel_flap_mm"}, reference) * mm;
  f.others_shear_modulus = positive(j, {"material_calibration_by_others", "neo_hookean_shear_modulus_Pa"}, reference);
  f.poisson_ratio = positive(j, {"material_calibration_by_others", "nu"}, reference);
  f.uniaxial_shear_modulus = positive(j, {"uniaxial_test", "neo_hookean_shear_modulus_Pa"}, reference);
  f.uniaxial_tip_deflection = positive(j, {"uniaxial_test", "tip_deflection_no_flow_mm"}, reference) * mm;
  if (f.fluid_density <= f.solid_density)
    throw InvalidInput(reference.string() + ": fluid.density must exceed solid.density (a buoyant flap)");
  if (f.poisson_ratio >= 0.5)
    throw InvalidInput(reference.string() + ": material_calibration_by_others.nu must be below 0.5");
  return f;
}

std::vector<std::array<double, 2>> zero_flow_centreline(const std::filesystem::path& reference, int points,
                                                        double z_first) {
  std::ifstream in(reference);
  if (!in) throw InvalidInput("cannot open reference file " + reference.string());
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  const std::string key = "zero_flow_centreline_fit";
  if (j.is_discarded() || !j.contains(key) || !j[key].contains("p") || !j[key]["p"].is_array())
    throw InvalidInput(reference.string() + ": missing " + key + " (scale_mm, length_mm, p)");
  const double scale = positive(j, {key, "scale_mm"}, reference) * 1e-3;
  const double length = positive(j, {key, "length_mm"}, reference) * 1e-3;
  std::vector<double> p;
  for (const auto& v : j[key]["p"]) {
    if (!v.is_number()) throw InvalidInput(reference.string() + ": " + key + ".p must hold numbers");
    p.push_back(v.get<double>());
  }
  if (points < 2 || !(z_first >= 0 && z_first < length))
    throw InvalidInput("zero-flow centreline: at least two points from a z below the fit's length");
  std::vector<std::array<double, 2>> out;
  for (int k = 0; k < points; ++k) {
    const double z = z_first + (length - z_first) * k / (points - 1), s = z / length;
    double y = 0, sp = s;
    for (double c : p) y += c * sp, sp *= s;
    out.push_back({z, scale * y});
  }
  return out;
}

FlapModel parse_flap_model(const std::string& name) {
  if (name == "beam") return FlapModel::beam;
  if (name == "shell") return FlapModel::shell;
  throw InvalidInput("flap model '" + name + "': expected beam or shell");
}

const char* to_string(FlapModel model) { return model == FlapModel::beam ? "beam" : "shell"; }

namespace {

// Station s along the flap -> rest position on the arc of curvature k (a straight line for k = 0),
// offset c along the arc's normal (the cupping).
Vec3 rest_position(double k, double s, double y, double c) {
  const double x = std::abs(k * s) < 1e-12 ? s : std::sin(k * s) / k;
  const double z = std::abs(k * s) < 1e-12 ? 0.5 * k * s * s : (1 - std::cos(k * s)) / k;
  return Vec3(x - c * std::sin(k * s), y, z + c * std::cos(k * s));
}

void check_shape(const FlapMesh& mesh, const FlapShape& shape) {
  if (mesh.along < 1 || (mesh.model == FlapModel::shell && mesh.across < 1))
    throw InvalidInput("flap: the mesh needs at least one cell along and across");
  if (!std::isfinite(shape.rest_curvature) || !std::isfinite(shape.rest_cupping) || !(shape.distal_softening < 1))
    throw InvalidInput("flap: the rest curvatures must be finite and the distal softening below 1");
  if (mesh.model == FlapModel::beam && shape.rest_cupping != 0)
    throw InvalidInput("flap: a cupped rest shape needs the shell model");
}

}  // namespace

std::vector<std::array<double, 2>> read_mri_centreline(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InvalidInput(path.string() + ": cannot be read (the MRI centreline, x_mm,y_mm,z_mm)");
  std::vector<std::array<double, 2>> out;
  std::string line;
  int number = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#') continue;
    if (!header) {
      if (line.rfind("x_mm,y_mm,z_mm", 0) != 0)
        throw InvalidInput(path.string() + ":" + std::to_string(number) + ": expected the header x_mm,y_mm,z_mm");
      header = true;
      continue;
    }
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream row(line);
    double x = 0, y = 0, z = 0;
    if (!(row >> x >> y >> z) || !std::isfinite(y) || !std::isfinite(z))
      throw InvalidInput(path.string() + ":" + std::to_string(number) + ": expected three numbers x_mm,y_mm,z_mm");
    out.push_back({z * 1e-3, y * 1e-3});
  }
  if (out.size() < 2) throw InvalidInput(path.string() + ": fewer than two centreline points");
  return out;
}

FlapShellModel flap_shell_model(const HessenthalerFlap& flap, double E, const FlapMesh& mesh, const FlapShape& shape) {
  if (!(E > 0) || !std::isfinite(E)) throw InvalidInput("flap: Young's modulus must be positive and finite");
  check_shape({FlapModel::shell, mesh.along, mesh.across}, shape);
  const double L = flap.length, b = flap.width;
  FlapShellModel f;
  Model& model = f.model;
  const int stiff = model.add_material({"silicone", E, flap.poisson_ratio, flap.solid_density});
  const int soft = model.add_material({"silicone_distal", E * (1 - shape.distal_softening), flap.poisson_ratio,
                                       flap.solid_density});
  const auto material_at = [&](double s) { return s > 0.5 * L && shape.distal_softening != 0 ? soft : stiff; };
  f.grid = rectangle_mesh(L, b, mesh.along, mesh.across);
  for (const Vec3& X : f.grid.nodes) {
    const double y = X.y() - 0.5 * b;
    model.add_node(rest_position(shape.rest_curvature, X.x(), X.y(), 0.5 * shape.rest_cupping * y * y));
  }
  const auto& X = model.reference_positions();
  for (const auto& t : f.grid.triangles) {
    const double centroid = (f.grid.nodes[t[0]].x() + f.grid.nodes[t[1]].x() + f.grid.nodes[t[2]].x()) / 3;
    const auto& m = model.materials()[static_cast<std::size_t>(material_at(centroid))];
    model.add_element(std::make_unique<CorotationalShell>(t[0], t[1], t[2], X[t[0]], X[t[1]], X[t[2]], m,
                                                          flap.thickness));
  }
  f.rows.resize(static_cast<std::size_t>(mesh.along + 1));
  for (int j = 0; j <= mesh.across; ++j) {
    const double wj = (j == 0 || j == mesh.across) ? 0.5 : 1.0;
    model.fix_node(f.grid.node(0, j));
    for (int i = 0; i <= mesh.along; ++i)
      f.rows[static_cast<std::size_t>(i)].push_back({f.grid.node(i, j), wj / mesh.across});
  }
  return f;
}

FlapDeflection flap_buoyancy_deflection(const HessenthalerFlap& flap, double E, const FlapMesh& mesh,
                                        int load_steps, SolverBackend backend) {
  return flap_deflection(flap, E, mesh, flap.buoyancy_per_length(), load_steps, backend);
}

FlapDeflection flap_deflection(const HessenthalerFlap& flap, double E, const FlapMesh& mesh, double q,
                               int load_steps, SolverBackend backend) {
  return flap_deflection(flap, E, mesh, FlapLoad{q, {}, {}, {}}, FlapShape{}, load_steps, backend);
}

FlapDeflection flap_deflection(const HessenthalerFlap& flap, double E, const FlapMesh& mesh, const FlapLoad& load,
                               const FlapShape& shape, int load_steps, SolverBackend backend) {
  if (!(E > 0) || !std::isfinite(E)) throw InvalidInput("flap: Young's modulus must be positive and finite");
  if (!std::isfinite(load.uniform)) throw InvalidInput("flap: the load per length must be finite");
  for (const auto* profile : {&load.transverse, &load.along})
    for (double v : *profile)
      if (!std::isfinite(v)) throw InvalidInput("flap: the load profile must be finite");
  for (double v : load.nodal)
    if (!std::isfinite(v)) throw InvalidInput("flap: the nodal load must be finite");
  check_shape(mesh, shape);
  const double L = flap.length, b = flap.width;
  const auto profile_at = [&](const std::vector<double>& p, double s) {
    if (p.empty()) return 0.0;
    const int n = static_cast<int>(p.size());
    return p[static_cast<std::size_t>(std::clamp(static_cast<int>(std::floor(s / L * n)), 0, n - 1))];
  };
  // Load per length [N/m] at station s along z and x.
  const auto qz = [&](double s) { return load.uniform + profile_at(load.transverse, s); };
  const auto qx = [&](double s) { return profile_at(load.along, s); };
  // The flap along +x, its width along y, its thickness (and the buoyancy) along +z.
  std::optional<FlapShellModel> shell;
  Model beam_model;
  if (mesh.model == FlapModel::shell) shell = flap_shell_model(flap, E, mesh, shape);
  Model& model = shell ? shell->model : beam_model;
  std::vector<std::pair<int, double>> tip, root;  // node, weight of the tip / clamp row's centre
  std::vector<std::vector<std::pair<int, double>>> stations(mesh.along + 1);  // the same per station
  const double ds = L / mesh.along;
  if (mesh.model == FlapModel::beam) {
    if (!load.nodal.empty()) throw InvalidInput("flap: a nodal load needs the shell model");
    const int stiff = model.add_material({"silicone", E, flap.poisson_ratio, flap.solid_density});
    const int soft = model.add_material({"silicone_distal", E * (1 - shape.distal_softening), flap.poisson_ratio,
                                         flap.solid_density});
    for (int i = 0; i <= mesh.along; ++i) model.add_node(rest_position(shape.rest_curvature, ds * i, 0, 0));
    for (int i = 0; i < mesh.along; ++i)
      model.add_beam(i, i + 1, ds * (i + 0.5) > 0.5 * L && shape.distal_softening != 0 ? soft : stiff,
                     TaperedRectangle::uniform(b, flap.thickness), Vec3(0, 1, 0));
    model.fix_node(0);
    // Lumped: half of each element's load at either end (O(h^2) in the tip deflection).
    for (int i = 1; i <= mesh.along; ++i) {
      const double w = ds * (i == mesh.along ? 0.5 : 1.0), s = ds * i;
      model.add_nodal_load(i, 2, qz(s) * w);
      if (qx(s) != 0) model.add_nodal_load(i, 0, qx(s) * w);
    }
    tip.push_back({mesh.along, 1.0});
    root.push_back({0, 1.0});
    for (int i = 0; i <= mesh.along; ++i) stations[i].push_back({i, 1.0});
  } else {
    const TriangleMesh& tm = shell->grid;
    stations = shell->rows;
    for (int j = 0; j <= mesh.across; ++j) {
      const double wj = (j == 0 || j == mesh.across) ? 0.5 : 1.0;
      for (int i = 1; i <= mesh.along; ++i) {
        const double w = ds * (i == mesh.along ? 0.5 : 1.0) * wj / mesh.across, s = ds * i;
        model.add_nodal_load(tm.node(i, j), 2, qz(s) * w);
        if (qx(s) != 0) model.add_nodal_load(tm.node(i, j), 0, qx(s) * w);
      }
    }
    tip = stations.back();
    root = stations.front();
    if (!load.nodal.empty() && load.nodal.size() != 3 * tm.nodes.size())
      throw InvalidInput("flap: the nodal load has " + std::to_string(load.nodal.size()) + " entries for " +
                         std::to_string(tm.nodes.size()) + " shell nodes (3 per node)");
    for (std::size_t k = 0; k < load.nodal.size(); ++k)
      if (load.nodal[k] != 0) model.add_nodal_load(static_cast<int>(k / 3), static_cast<int>(k % 3), load.nodal[k]);
  }
  StaticOptions so;
  so.steps = load_steps;
  so.backend = backend;
  StaticSolver solver(model, so);
  NodalState state = model.reference_state();
  const StaticResult r = solver.solve(state, 0.0, 1.0);
  FlapDeflection d;
  d.newton_iterations = r.total_iterations;
  for (const auto& [node, w] : tip) d.tip += w * state.position[node].z(), d.tip_axial += w * state.position[node].x();
  for (const auto& [node, w] : root) d.tip -= w * state.position[node].z();
  d.tip_axial -= L;
  for (const auto& station : stations) {
    std::array<double, 2> xz{0, 0};
    for (const auto& [node, w] : station) xz[0] += w * state.position[node].x(), xz[1] += w * state.position[node].z();
    d.centreline.push_back(xz);
  }
  return d;
}

}  // namespace finverse::fem::validation
