// The root drive as fit parameters (see drive_parameters.hpp).
#include "fit/drive_parameters.hpp"

#include <algorithm>
#include <cmath>

namespace finverse::fit {

namespace {
constexpr double kPitchBound = 0.35;        // rad
constexpr double kHeaveBoundOfRoot = 0.25;  // of the root's length

bool all_digits(const std::string& s) {
  return !s.empty() && s.size() <= 3 && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}
}  // namespace

std::optional<DriveSlot> parse_drive_name(const std::string& name) {
  if (name == "drive_heave_sin") return DriveSlot{DriveSlot::Kind::heave_sin, 0};
  if (name == "drive_heave_cos") return DriveSlot{DriveSlot::Kind::heave_cos, 0};
  for (const auto& [prefix, kind] : {std::pair{std::string("drive_pitch_sin"), DriveSlot::Kind::pitch_sin},
                                     std::pair{std::string("drive_pitch_cos"), DriveSlot::Kind::pitch_cos}}) {
    if (name.size() > prefix.size() && name.compare(0, prefix.size(), prefix) == 0 &&
        all_digits(name.substr(prefix.size())))
      return DriveSlot{kind, std::stoi(name.substr(prefix.size()))};
  }
  return std::nullopt;
}

std::optional<Parameter> drive_parameter(const std::string& name, const stage::Mesh& mesh) {
  const auto slot = parse_drive_name(name);
  if (!slot) return std::nullopt;
  Parameter p;
  p.name = name;
  p.scale = Scale::linear;
  if (slot->kind == DriveSlot::Kind::pitch_sin || slot->kind == DriveSlot::Kind::pitch_cos) {
    p.unit = "rad";
    p.lower = -kPitchBound;
    p.upper = kPitchBound;
    return p;
  }
  double length = 0;
  const auto& root = mesh.root_nodes.data;
  for (std::size_t a = 0; a < root.size(); ++a)
    for (std::size_t b = a + 1; b < root.size(); ++b) {
      double d2 = 0;
      for (std::size_t d = 0; d < 3; ++d) {
        const double x = mesh.points(static_cast<std::size_t>(root[a]), d) - mesh.points(static_cast<std::size_t>(root[b]), d);
        d2 += x * x;
      }
      length = std::max(length, std::sqrt(d2));
    }
  p.unit = "m";
  p.lower = -kHeaveBoundOfRoot * length;
  p.upper = kHeaveBoundOfRoot * length;
  return p;
}

std::vector<std::string> drive_parameter_names(int order) {
  std::vector<std::string> names;
  if (order <= 0) return names;
  for (int k = 0; k < order; ++k) names.push_back("drive_pitch_sin" + std::to_string(k));
  for (int k = 0; k < order; ++k) names.push_back("drive_pitch_cos" + std::to_string(k));
  names.emplace_back("drive_heave_sin");
  names.emplace_back("drive_heave_cos");
  return names;
}

void set_drive_coefficient(fem::DriveCorrection& c, const DriveSlot& slot, double value) {
  const auto k = static_cast<std::size_t>(slot.order);
  if ((slot.kind == DriveSlot::Kind::pitch_sin || slot.kind == DriveSlot::Kind::pitch_cos) &&
      c.pitch_sin.size() <= k) {
    c.pitch_sin.resize(k + 1, 0.0);
    c.pitch_cos.resize(k + 1, 0.0);
  }
  switch (slot.kind) {
    case DriveSlot::Kind::pitch_sin: c.pitch_sin[k] = value; break;
    case DriveSlot::Kind::pitch_cos: c.pitch_cos[k] = value; break;
    case DriveSlot::Kind::heave_sin: c.heave_sin = value; break;
    case DriveSlot::Kind::heave_cos: c.heave_cos = value; break;
  }
}

}  // namespace finverse::fit
