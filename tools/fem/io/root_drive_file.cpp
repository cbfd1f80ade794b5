// The root drive file and the drive on a fin mesh (see root_drive_file.hpp).
#include "fem/io/root_drive_file.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>

#include "fem/errors.hpp"

namespace finverse::fem::io {

namespace {

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

}  // namespace

double RootDriveSpec::frequency(double speed, double chord) const {
  if (frequency_hz > 0) return frequency_hz;
  return strouhal * speed / (excursion_over_chord * chord);
}

nlohmann::json RootDriveSpec::to_json() const {
  return {{"heave_over_chord", heave_over_chord}, {"pitch_center_deg", pitch.center_deg},
          {"pitch_edge_deg", pitch.edge_deg},     {"pitch_phase_deg", pitch.phase_deg},
          {"pitch_phase_w_deg", pitch.phase_w_deg}, {"strouhal", strouhal},
          {"excursion_over_chord", excursion_over_chord}, {"frequency_hz", frequency_hz},
          {"ramp_periods", ramp_periods}};
}

RootDriveSpec parse_root_drive(const nlohmann::json& j, const std::string& source) {
  if (!j.is_object()) throw InvalidInput(source + ": expected a JSON object of root drive parameters");
  RootDriveSpec s;
  // key -> (target, lower, upper): the ranges a caudal fin's drive can take.
  const std::map<std::string, std::tuple<double*, double, double>> keys{
      {"heave_over_chord", {&s.heave_over_chord, 0, 2}},
      {"pitch_center_deg", {&s.pitch.center_deg, 0, 80}},
      {"pitch_edge_deg", {&s.pitch.edge_deg, 0, 80}},
      {"pitch_phase_deg", {&s.pitch.phase_deg, -360, 360}},
      {"pitch_phase_w_deg", {&s.pitch.phase_w_deg, -180, 180}},
      {"strouhal", {&s.strouhal, 1e-3, 2}},
      {"excursion_over_chord", {&s.excursion_over_chord, 1e-3, 10}},
      {"frequency_hz", {&s.frequency_hz, 0, 1e4}},
      {"ramp_periods", {&s.ramp_periods, 0, 20}}};
  for (const auto& [key, value] : j.items()) {
    const auto it = keys.find(key);
    if (it == keys.end())
      throw InvalidInput(source + ": unknown key '" + key +
                         "' (expected heave_over_chord, pitch_center_deg, pitch_edge_deg, pitch_phase_deg, "
                         "pitch_phase_w_deg, strouhal, excursion_over_chord, frequency_hz, ramp_periods)");
    const auto [target, lo, hi] = it->second;
    if (!value.is_number())
      throw InvalidInput(source + ": " + key + ": expected a number, got " + value.dump());
    const double v = value.get<double>();
    if (!(std::isfinite(v) && v >= lo && v <= hi))
      throw InvalidInput(source + ": " + key + " = " + num(v) + ", expected " + num(lo) + " .. " + num(hi));
    *target = v;
  }
  return s;
}

RootDriveSpec read_root_drive(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InvalidInput(path.string() + ": cannot open the root drive file");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw InvalidInput(path.string() + ": not valid JSON (" + e.what() + ")");
  }
  return parse_root_drive(j, path.string());
}

RootDrive make_root_drive(const stage::Mesh& mesh, const RootDriveSpec& spec, double frequency, double chord,
                          const std::string& source) {
  const std::size_t nv = mesh.points.shape.empty() ? 0 : mesh.points.dim(0);
  std::vector<int> root(mesh.root_nodes.data.begin(), mesh.root_nodes.data.end());
  if (root.empty()) throw InvalidInput(source + ": /root_nodes is empty: nothing to drive");
  std::vector<Vec3> X;
  for (int n : root) {
    if (n < 0 || static_cast<std::size_t>(n) >= nv)
      throw InvalidInput(source + ": /root_nodes names node " + std::to_string(n) + " outside the mesh");
    X.emplace_back(mesh.points(n, 0), mesh.points(n, 1), mesh.points(n, 2));
  }
  // The ray roots: a root node that a beam leaves towards a node off the root.
  const std::set<int> on_root(root.begin(), root.end());
  std::map<int, int> ray_root;  // ray id -> root list index
  const std::size_t nb = mesh.beam_elements.shape.empty() ? 0 : mesh.beam_elements.dim(0);
  for (std::size_t e = 0; e < nb; ++e)
    for (int end = 0; end < 2; ++end) {
      const int a = mesh.beam_elements(e, end), b = mesh.beam_elements(e, 1 - end);
      if (on_root.count(a) && !on_root.count(b))
        ray_root.emplace(mesh.beam_ray.data[e],
                         static_cast<int>(std::find(root.begin(), root.end(), a) - root.begin()));
    }
  if (ray_root.empty()) throw InvalidInput(source + ": no ray (beam) leaves the root nodes: the root pitch acts on rays");
  // Dorsal (largest z) first: eta = +1 .. -1, linear in the rank.
  std::vector<std::pair<double, int>> order;
  for (const auto& [id, i] : ray_root) order.emplace_back(-X[static_cast<std::size_t>(i)].z(), i);
  std::sort(order.begin(), order.end());
  std::vector<RayRoot> rays;
  const double n = static_cast<double>(order.size());
  for (std::size_t k = 0; k < order.size(); ++k)
    rays.push_back({order[k].second, order.size() > 1 ? 1.0 - 2.0 * static_cast<double>(k) / (n - 1) : 0.0});
  return RootDrive(root, X, rays, spec.heave_over_chord * chord, frequency, spec.ramp_periods / frequency, spec.pitch);
}

}  // namespace finverse::fem::io
