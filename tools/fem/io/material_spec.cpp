// Parsing and range checks of the materials file (see material_spec.hpp).
#include "fem/io/material_spec.hpp"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "fem/errors.hpp"

namespace finverse::fem::io {

namespace {
[[noreturn]] void fail(const std::string& source, const std::string& key, const std::string& what) {
  throw InvalidInput(source + ": " + key + ": " + what);
}

void only_keys(const nlohmann::json& j, const std::string& source, const std::string& where,
               const std::set<std::string>& allowed) {
  if (!j.is_object()) fail(source, where, "expected a JSON object");
  for (const auto& [k, v] : j.items())
    if (!allowed.count(k)) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      fail(source, where.empty() ? k : where + "." + k, "unknown key (expected one of " + list + ")");
    }
}

double number(const nlohmann::json& j, const std::string& source, const std::string& key) {
  if (!j.is_number()) fail(source, key, "expected a number");
  const double v = j.get<double>();
  if (!std::isfinite(v)) fail(source, key, "expected a finite number");
  return v;
}

// Material from an object; fields it lacks come from `base` (when given).
Material material(const nlohmann::json& j, const std::string& source, const std::string& where,
                  const std::string& name, const Material* base) {
  only_keys(j, source, where, {"E", "nu", "density"});
  Material m = base ? *base : Material{};
  m.name = name;
  auto field = [&](const char* k, double& out) {
    if (j.contains(k))
      out = number(j[k], source, where + "." + k);
    else if (!base)
      fail(source, where + "." + k, "missing");
  };
  field("E", m.youngs_modulus);
  field("nu", m.poisson_ratio);
  field("density", m.density);
  std::ostringstream os;
  os.precision(6);
  if (!(m.youngs_modulus > 0)) os << "Young's modulus E = " << m.youngs_modulus << ", expected > 0";
  else if (!(m.poisson_ratio > -1 && m.poisson_ratio < 0.5))
    os << "Poisson ratio nu = " << m.poisson_ratio << ", expected -1 < nu < 0.5";
  else if (!(m.density > 0)) os << "density = " << m.density << ", expected > 0";
  if (!os.str().empty()) fail(source, where, os.str());
  return m;
}

int region_id(const std::string& key, const std::string& source, const std::string& where) {
  try {
    size_t used = 0;
    const int id = std::stoi(key, &used);
    if (used == key.size() && id >= 0) return id;
  } catch (const std::exception&) {
  }
  fail(source, where + "." + key, "expected a non-negative integer id");
}
}  // namespace

Material MaterialSpec::ray_material(int id) const {
  auto it = ray.find(id);
  Material m = it != ray.end() ? it->second : rays;
  m.name = "ray" + std::to_string(id);
  return m;
}

MaterialSpec parse_material_spec(const nlohmann::json& j, const std::string& source) {
  only_keys(j, source, "", {"description", "membrane", "rays", "ray", "shell_region", "distal", "modulation", "rayleigh"});
  MaterialSpec s;
  s.source = source;
  if (!j.contains("membrane")) fail(source, "membrane", "missing");
  if (!j.contains("rays")) fail(source, "rays", "missing");
  s.membrane = material(j["membrane"], source, "membrane", "membrane", nullptr);
  s.rays = material(j["rays"], source, "rays", "rays", nullptr);
  auto per_id = [&](const char* key, std::map<int, Material>& out, const Material& base, const char* prefix) {
    if (!j.contains(key)) return;
    if (!j[key].is_object()) fail(source, key, "expected a JSON object");
    for (const auto& [k, v] : j[key].items()) {
      const int id = region_id(k, source, key);
      out[id] = material(v, source, std::string(key) + "." + k, prefix + std::to_string(id), &base);
    }
  };
  per_id("ray", s.ray, s.rays, "ray");
  per_id("shell_region", s.shell_region, s.membrane, "shell_region");
  if (j.contains("distal")) {
    const auto& d = j["distal"];
    only_keys(d, source, "distal", {"s_from", "E_factor"});
    if (!d.contains("s_from") || !d.contains("E_factor")) fail(source, "distal", "needs s_from and E_factor");
    s.distal_s_from = number(d["s_from"], source, "distal.s_from");
    s.distal_factor = number(d["E_factor"], source, "distal.E_factor");
    if (!(s.distal_factor > 0)) fail(source, "distal.E_factor", "expected > 0");
    if (!(s.distal_s_from >= 0 && s.distal_s_from <= 1)) fail(source, "distal.s_from", "expected 0..1");
  }
  if (j.contains("modulation")) {
    if (!j["modulation"].is_array()) fail(source, "modulation", "expected an array");
    int k = 0;
    for (const auto& m : j["modulation"]) {
      const std::string where = "modulation[" + std::to_string(k++) + "]";
      only_keys(m, source, where, {"target", "amplitude", "frequency", "phase"});
      if (!m.contains("target") || !m["target"].is_string()) fail(source, where + ".target", "expected a string");
      ModulationSpec ms{m["target"].get<std::string>(), {}};
      ms.modulation.amplitude = m.contains("amplitude") ? number(m["amplitude"], source, where + ".amplitude") : 0.0;
      ms.modulation.frequency = m.contains("frequency") ? number(m["frequency"], source, where + ".frequency") : 0.0;
      ms.modulation.phase = m.contains("phase") ? number(m["phase"], source, where + ".phase") : 0.0;
      if (!(std::abs(ms.modulation.amplitude) < 1))
        fail(source, where + ".amplitude", "expected |a| < 1 (E must stay > 0)");
      if (!(ms.modulation.frequency >= 0)) fail(source, where + ".frequency", "expected >= 0");
      s.modulations.push_back(ms);
    }
  }
  if (j.contains("rayleigh")) {
    only_keys(j["rayleigh"], source, "rayleigh", {"mass", "stiffness"});
    if (j["rayleigh"].contains("mass")) s.rayleigh_mass = number(j["rayleigh"]["mass"], source, "rayleigh.mass");
    if (j["rayleigh"].contains("stiffness"))
      s.rayleigh_stiffness = number(j["rayleigh"]["stiffness"], source, "rayleigh.stiffness");
    if (s.rayleigh_mass < 0 || s.rayleigh_stiffness < 0) fail(source, "rayleigh", "coefficients must be >= 0");
  }
  return s;
}

MaterialSpec read_material_spec(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InvalidInput(path.string() + ": cannot open the materials file");
  nlohmann::json j;
  try {
    in >> j;
  } catch (const nlohmann::json::exception& e) {
    throw InvalidInput(path.string() + ": not valid JSON (" + std::string(e.what()) + ")");
  }
  return parse_material_spec(j, path.string());
}

}  // namespace finverse::fem::io
