// Candidate effects (issue 34, DESIGN.md section 5.6): each is a parameterised extension of the
// structural model that the fitted model lacks (active ray stiffening, root curvature, damping,
// distal softening, a density error, a cupped rest shape). An effect is applied to a built
// fem::Model before a run (fin-fem run, fin-fsi fin, fin-fit); the effect tracing of fin-loop
// perturbs one parameter, applies, runs once and reads the sensitivity.
//
// Changes from the interface first sketched in the issue: apply() takes a FinLayout (which
// elements are rays, where along the ray, which ray group), since the effects act per ray group;
// rest-shape effects also move the rest positions before the model is built (reshape()). Errors
// are fem::InvalidInput (a finverse::fem::Error; the apps exit 2 on it).
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fem/model.hpp"

namespace finverse::fem {

// Ray groups by the rank of a ray's root along the dorsal axis: eta = +1 the dorsal edge ray ..
// -1 the ventral one (root_drive.hpp); dorsal eta > 1/3, ventral eta < -1/3, middle between.
enum class RayGroup { dorsal, middle, ventral };
// "all" | "dorsal" | "middle" | "ventral" | "edges" (dorsal and ventral); throws InvalidInput.
std::vector<RayGroup> parse_ray_groups(const std::string& name, const std::string& effect);

// What the effects need to know about the fin besides the Model.
struct FinLayout {
  struct Beam {
    int element = 0;        // model element index
    int ray = 0;            // ray id (mesh.h5 /beams/ray)
    int node0 = 0, node1 = 0;
    double s0 = 0, s1 = 0;  // arc-length fraction from the ray's root (0) to its tip (1) at node0, node1
  };
  std::vector<Beam> beams;             // every ray element
  std::map<int, RayGroup> ray_group;   // ray id -> group
  std::map<int, double> ray_eta;       // ray id -> eta (+1 dorsal .. -1 ventral)
  std::map<int, double> ray_length;    // ray id -> length at rest (sum of its elements) [m]
  std::vector<int> shell_elements;     // membrane (and other shell) elements
  std::vector<int> root_nodes;
  // Fin axes at rest: span (dorsal axis z, ventral -> dorsal), normal (out of the fin plane,
  // lateral), chord (root -> tips); root_centre: mean of the root nodes.
  Vec3 span_axis{0, 0, 1}, normal{0, 1, 0}, chord_axis{1, 0, 0}, root_centre{0, 0, 0};
  double beat_frequency = 0;  // [Hz], 0: unknown (time-periodic effects then need "frequency")
  double start_time = 0;      // time-dependent effects start from rest here ...
  double ramp = 0;            // ... and reach full amplitude after this many s (smooth, as the drive)
};

struct EffectParameter {
  std::string name, unit;
  double value = 0, lower = 0, upper = 0;  // value within [lower, upper]
};

class StructuralEffect {
 public:
  virtual ~StructuralEffect() = default;
  virtual std::string name() const = 0;
  // The continuous parameters (the effect tracing varies these), in a fixed order.
  virtual std::vector<EffectParameter> parameters() const = 0;
  // Same order and size as parameters(); throws InvalidInput naming the effect, the parameter
  // and the allowed range when one is outside it or not finite.
  virtual void set_parameters(const std::vector<double>& values) = 0;
  // Rest positions (one per mesh node) before the model is built: only rest-shape effects move
  // them; the default leaves them.
  virtual void reshape(std::vector<Vec3>& /*rest*/, const FinLayout& /*layout*/) const {}
  // Changes the model (material field, mass, damping, loads); call after the root motion and the
  // loads are set. Throws InvalidInput when the layout lacks what the effect acts on.
  virtual void apply(Model& model, const FinLayout& layout) const = 0;
  // The spec that make_effect() turns back into this effect (recorded in output files).
  virtual nlohmann::json to_json() const = 0;
};

std::vector<std::string> effect_names();
// Every effect's name, default spec and parameters with units and ranges (`fin-fem effects`).
nlohmann::json effects_catalogue();
// spec: {"name": "<effect>", "<parameter>": value, ...} plus non-continuous settings (e.g.
// "group", "frequency"); absent parameters take their defaults (a null effect where one exists).
// Throws InvalidInput for an unknown name or key, or a value out of range.
std::unique_ptr<StructuralEffect> make_effect(const nlohmann::json& spec);
// A JSON array of specs (or {"effects": [...]}); source names the file in messages.
std::vector<std::unique_ptr<StructuralEffect>> make_effects(const nlohmann::json& list,
                                                            const std::string& source = "effects");
std::vector<std::unique_ptr<StructuralEffect>> read_effects(const std::filesystem::path& json);
nlohmann::json effects_to_json(const std::vector<std::unique_ptr<StructuralEffect>>& effects);

}  // namespace finverse::fem
