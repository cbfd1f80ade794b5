// The catalogue of candidate effects and their JSON specs (see structural_effect.hpp).
#include "fem/effects/structural_effect.hpp"

#include <fstream>
#include <functional>
#include <utility>

#include "fem/effects/catalogue.hpp"
#include "fem/errors.hpp"

namespace finverse::fem {

namespace {
using Maker = std::function<std::unique_ptr<effects::ParameterisedEffect>()>;
const std::vector<std::pair<std::string, Maker>>& catalogue() {
  static const std::vector<std::pair<std::string, Maker>> c{
      {"active_stiffening", effects::make_active_stiffening}, {"root_curvature", effects::make_root_curvature},
      {"rayleigh_damping", effects::make_rayleigh_damping},   {"distal_softening", effects::make_distal_softening},
      {"density_error", effects::make_density_error},         {"cupped_rest_shape", effects::make_cupped_rest_shape}};
  return c;
}
}  // namespace

std::vector<RayGroup> parse_ray_groups(const std::string& name, const std::string& effect) {
  if (name == "all") return {RayGroup::dorsal, RayGroup::middle, RayGroup::ventral};
  if (name == "dorsal") return {RayGroup::dorsal};
  if (name == "middle") return {RayGroup::middle};
  if (name == "ventral") return {RayGroup::ventral};
  if (name == "edges") return {RayGroup::dorsal, RayGroup::ventral};
  throw InvalidInput("effect " + effect + ": group '" + name + "', expected all, dorsal, middle, ventral or edges");
}

nlohmann::json effects_catalogue() {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& name : effect_names()) {
    const auto e = make_effect({{"name", name}});
    nlohmann::json j{{"name", name}, {"defaults", e->to_json()}};
    for (const auto& p : e->parameters())
      j["parameters"].push_back({{"name", p.name}, {"unit", p.unit}, {"lower", p.lower}, {"upper", p.upper}});
    out.push_back(j);
  }
  return out;
}

std::vector<std::string> effect_names() {
  std::vector<std::string> n;
  for (const auto& [name, make] : catalogue()) n.push_back(name);
  return n;
}

std::unique_ptr<StructuralEffect> make_effect(const nlohmann::json& spec) {
  if (!spec.is_object() || !spec.contains("name") || !spec["name"].is_string())
    throw InvalidInput("effect spec " + spec.dump() + ": expected an object with a \"name\"");
  const std::string name = spec["name"].get<std::string>();
  for (const auto& [n, make] : catalogue())
    if (n == name) {
      auto e = make();
      e->configure(spec);
      return e;
    }
  std::string known;
  for (const auto& n : effect_names()) known += (known.empty() ? "" : ", ") + n;
  throw InvalidInput("unknown effect '" + name + "', expected one of " + known);
}

std::vector<std::unique_ptr<StructuralEffect>> make_effects(const nlohmann::json& list, const std::string& source) {
  const nlohmann::json& a = list.is_object() && list.contains("effects") ? list["effects"] : list;
  if (!a.is_array()) throw InvalidInput(source + ": expected a JSON array of effects (or {\"effects\": [...]})");
  std::vector<std::unique_ptr<StructuralEffect>> out;
  for (const auto& spec : a) {
    try {
      out.push_back(make_effect(spec));
    } catch (const InvalidInput& e) {
      throw InvalidInput(source + ": " + e.what());
    }
  }
  return out;
}

std::vector<std::unique_ptr<StructuralEffect>> read_effects(const std::filesystem::path& json) {
  std::ifstream in(json);
  if (!in) throw InvalidInput(json.string() + ": cannot open the effects file");
  nlohmann::json j;
  try {
    in >> j;
  } catch (const nlohmann::json::exception& e) {
    throw InvalidInput(json.string() + ": not valid JSON (" + e.what() + ")");
  }
  return make_effects(j, json.string());
}

nlohmann::json effects_to_json(const std::vector<std::unique_ptr<StructuralEffect>>& effects) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& e : effects) a.push_back(e->to_json());
  return a;
}

}  // namespace finverse::fem
