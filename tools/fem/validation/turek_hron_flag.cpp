// The Turek-Hron flag model and its wet-surface node list (see turek_hron_flag.hpp).
#include "fem/validation/turek_hron_flag.hpp"

#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "fem/errors.hpp"
#include "fem/structured_mesh.hpp"

namespace finverse::fem::validation {

double TurekHronFlagSpec::clamp_x(double y) const {
  const double dy = straight_clamp ? 0.5 * thickness : y - yc;
  return xc + std::sqrt(radius * radius - dy * dy);
}

TurekHronFlagSpec turek_hron_flag_spec(const std::filesystem::path& path, const std::string& name) {
  std::ifstream in(path);
  if (!in) throw InvalidInput("cannot open reference file " + path.string());
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw InvalidInput("reference file " + path.string() + " is not valid JSON: " + e.what());
  }
  auto number = [&](const std::string& pointer) {
    const nlohmann::json::json_pointer p(pointer);
    if (!j.contains(p) || !j.at(p).is_number())
      throw InvalidInput(path.string() + ": missing number " + pointer);
    return j.at(p).get<double>();
  };
  TurekHronFlagSpec s;
  s.xc = number("/geometry/cylinder_centre/0");
  s.yc = number("/geometry/cylinder_centre/1");
  s.radius = number("/geometry/cylinder_radius");
  s.thickness = number("/geometry/flag_thickness");
  s.x_tip = number("/geometry/point_A/0");
  s.poisson_ratio = number("/solid/nu_s");
  s.youngs_modulus = number("/cases/" + name + "/E");
  s.density = number("/cases/" + name + "/rho_s");
  s.gravity = j.contains(nlohmann::json::json_pointer("/cases/" + name + "/g")) ? number("/cases/" + name + "/g") : 0.0;
  return s;
}

TurekHronFlag build_turek_hron_flag(const TurekHronFlagSpec& spec) {
  if (!(spec.thickness > 0 && spec.thickness < 2 * spec.radius && spec.x_tip > spec.xc + spec.radius))
    throw InvalidInput("turek_hron flag: need 0 < thickness < cylinder diameter and the tip behind the cylinder");
  StripSpec strip;
  strip.x_begin = [&spec](double y) { return spec.clamp_x(y); };
  strip.x_end = spec.x_tip;
  strip.y0 = spec.yc - 0.5 * spec.thickness;
  strip.y1 = spec.yc + 0.5 * spec.thickness;
  strip.nx = spec.mesh.nx;
  strip.ny = spec.mesh.ny;
  strip.grading_x = spec.mesh.grading;
  const StructuredMeshQ9 m = mesh_strip_q9(strip);
  const Material solid{"flag", spec.youngs_modulus, spec.poisson_ratio, spec.density};
  TurekHronFlag f;
  Model& model = f.model;
  model.add_material(solid);
  const std::vector<int> id = add_plane_strain_mesh(model, m, solid);
  for (int j = 0; j <= 2 * m.ny; ++j) {
    model.fix(id[m.node(0, j)], 0);
    model.fix(id[m.node(0, j)], 1);
    f.clamp_nodes.push_back(id[m.node(0, j)]);
  }
  f.point_a = id[m.node(2 * m.nx, m.ny)];
  model.set_gravity(Vec3(0, -spec.gravity, 0));
  if (spec.gravity_as_load) {
    const Eigen::VectorXd fg = model.gravity_load();
    model.set_gravity(Vec3::Zero());
    for (int g = 0; g < fg.size(); ++g)
      if (fg(g) != 0) model.add_nodal_load(g / kDofsPerNode, g % kDofsPerNode, fg(g));
  }
  f.mass = model.total_mass();
  // Counter-clockwise: lower edge clamp -> tip, tip upwards, upper edge tip -> clamp.
  const int ni = 2 * m.nx, nj = 2 * m.ny;
  for (int i = 0; i <= ni; ++i) f.wet_nodes.push_back(id[m.node(i, 0)]);
  for (int j = 1; j <= nj; ++j) f.wet_nodes.push_back(id[m.node(ni, j)]);
  for (int i = ni - 1; i >= 0; --i) f.wet_nodes.push_back(id[m.node(i, nj)]);
  return f;
}

}  // namespace finverse::fem::validation
