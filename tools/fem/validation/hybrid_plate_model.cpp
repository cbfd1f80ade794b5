// Hybrid plate model (see hybrid_plate_model.hpp).
#include "fem/validation/hybrid_plate_model.hpp"

#include <cmath>
#include <fstream>
#include <numbers>

#include <Eigen/Geometry>

#include <nlohmann/json.hpp>

#include "fem/corotational_shell.hpp"
#include "fem/errors.hpp"
#include "fem/validation/shell_meshes.hpp"

namespace finverse::fem::validation {

double HybridPlateCase::heave(double t) const {
  return heave_amplitude * (1.0 - std::cos(2.0 * std::numbers::pi * frequency * t));
}

HybridPlateCase read_hybrid_plate_case(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InvalidInput("cannot open hybrid-plate case " + path.string());
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw InvalidInput("hybrid-plate case " + path.string() + " is not valid JSON: " + e.what());
  }
  auto number = [&](const nlohmann::json& obj, const char* where, const char* key) {
    if (!obj.contains(key) || !obj[key].is_number())
      throw InvalidInput(path.string() + ": " + where + "." + key + " must be a number");
    return obj[key].get<double>();
  };
  auto object = [&](const char* key) -> const nlohmann::json& {
    if (!j.contains(key) || !j[key].is_object())
      throw InvalidInput(path.string() + ": missing object '" + key + "'");
    return j[key];
  };
  HybridPlateCase c;
  const auto& p = object("plate");
  c.chord = number(p, "plate", "chord");
  c.span = number(p, "plate", "span");
  c.thickness = number(p, "plate", "thickness");
  c.plate = {"plate", number(p, "plate", "E"), number(p, "plate", "nu"), number(p, "plate", "density")};
  if (!j.contains("beams") || !j["beams"].is_array() || j["beams"].empty())
    throw InvalidInput(path.string() + ": 'beams' must be a non-empty array");
  for (const auto& b : j["beams"]) {
    HybridPlateBeam beam;
    beam.name = b.value("name", "beam" + std::to_string(c.beams.size() + 1));
    beam.z = number(b, "beams[]", "z");
    beam.material = {beam.name, number(b, "beams[]", "E"), number(b, "beams[]", "nu"),
                     number(b, "beams[]", "density")};
    beam.width = number(b, "beams[]", "width");
    beam.thickness = number(b, "beams[]", "thickness");
    c.beams.push_back(beam);
  }
  const auto& s = object("static");
  c.pressure = number(s, "static", "pressure");
  c.load_steps = static_cast<int>(number(s, "static", "load_steps"));
  const auto& d = object("dynamic");
  c.heave_amplitude = number(d, "dynamic", "heave_amplitude");
  c.frequency = number(d, "dynamic", "frequency");
  c.periods = number(d, "dynamic", "periods");
  c.time_step = number(d, "dynamic", "time_step");
  if (!(c.chord > 0 && c.span > 0 && c.thickness > 0 && c.load_steps > 0 && c.frequency > 0 &&
        c.periods > 0 && c.time_step > 0))
    throw InvalidInput(path.string() + ": dimensions, load_steps, frequency, periods and "
                       "time_step must be positive");
  return c;
}

HybridPlateModel build_hybrid_plate(const HybridPlateCase& c, int nx, int nz, HybridPlateLoad load) {
  if (nx < 1 || nz < 1) throw InvalidInput("hybrid plate: --nx and --nz must be >= 1");
  // Grid in the x-y plane, mapped to the x-z plane: (x, y) -> (x, 0, y - span/2).
  TriangleMesh mesh = rectangle_mesh(c.chord, c.span, nx, nz);
  for (Vec3& X : mesh.nodes) X = Vec3(X.x(), 0.0, X.y() - 0.5 * c.span);

  HybridPlateModel hp;
  Model& m = hp.model;
  m.add_material(c.plate);  // validates it and records the region (each shell keeps a copy)
  const std::vector<int> id = add_shell_mesh(m, mesh, c.plate, c.thickness);
  hp.shell_elements = static_cast<int>(mesh.triangles.size());

  for (const auto& b : c.beams) {
    const double k = (b.z + 0.5 * c.span) / c.span * nz;
    const int j = static_cast<int>(std::lround(k));
    if (std::abs(k - j) > 1e-9 || j < 0 || j > nz)
      throw InvalidInput("hybrid plate: beam " + b.name + " at z = " + std::to_string(b.z) +
                         " is not on a grid line of nz = " + std::to_string(nz));
    const int region = m.add_material(b.material);
    std::vector<int> line;
    for (int i = 0; i <= nx; ++i) line.push_back(id[mesh.node(i, j)]);
    // Width in the plate plane: the section's local y axis along z, thickness along the normal.
    for (int i = 0; i < nx; ++i)
      m.add_beam(line[i], line[i + 1], region, TaperedRectangle::uniform(b.width, b.thickness),
                 Vec3::UnitZ());
    hp.beam_elements += nx;
    hp.tips.push_back(line.back());
    hp.beam_nodes.push_back(std::move(line));
  }

  for (int j = 0; j <= nz; ++j) {
    const int n = id[mesh.node(0, j)];
    hp.leading_edge.push_back(n);
    for (int dof : {0, 2, 3, 4, 5}) m.fix(n, dof);
    if (load == HybridPlateLoad::heave)
      m.prescribe(n, 1, [c](double t) { return c.heave(t); });
    else
      m.fix(n, 1);
  }

  if (load == HybridPlateLoad::pressure) {
    // Dead pressure load along -y: a third of each triangle's force on each of its vertices
    // (consistent for the linear interpolation of the plate's deflection).
    const auto& X = m.reference_positions();
    for (const auto& t : mesh.triangles) {
      const double area =
          0.5 * (X[id[t[1]]] - X[id[t[0]]]).cross(X[id[t[2]]] - X[id[t[0]]]).norm();
      for (int v : t) m.add_nodal_load(id[v], 1, -c.pressure * area / 3.0);
    }
  }
  return hp;
}

}  // namespace finverse::fem::validation
