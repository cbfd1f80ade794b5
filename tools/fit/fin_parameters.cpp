// Fin parameters and the fin model factory (see fin_parameters.hpp).
#include "fit/fin_parameters.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "fem/io/fin_model.hpp"
#include "fit/errors.hpp"

namespace finverse::fit {

std::vector<int> mesh_ray_ids(const stage::Mesh& mesh) {
  const std::set<int> ids(mesh.beam_ray.data.begin(), mesh.beam_ray.data.end());
  return {ids.begin(), ids.end()};
}

std::vector<Parameter> default_fin_parameters(const stage::Mesh& mesh) {
  std::vector<Parameter> p;
  p.push_back({"E_membrane", "Pa", 1e5, 1e8, Scale::log10, std::nullopt});
  for (int id : mesh_ray_ids(mesh)) p.push_back({"E_ray" + std::to_string(id), "Pa", 1e7, 1e10, Scale::log10, std::nullopt});
  p.push_back({"nu", "1", 0.15, 0.49, Scale::linear, std::nullopt});
  return p;
}

nlohmann::json default_fin_parameter_spec(const stage::Mesh& mesh) {
  nlohmann::json list = nlohmann::json::array();
  for (const Parameter& p : default_fin_parameters(mesh))
    list.push_back({{"name", p.name},
                    {"lower", p.lower},
                    {"upper", p.upper},
                    {"scale", p.scale == Scale::log10 ? "log10" : "linear"},
                    {"unit", p.unit}});
  return {{"parameters", list}};
}

namespace {
constexpr int kNoModulus = -2, kMembrane = -1;  // element slots besides ray ids

// "E_ray<id>" -> id; nullopt for anything else.
std::optional<int> parse_ray_name(const std::string& name) {
  const std::string prefix = "E_ray";
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return std::nullopt;
  const std::string digits = name.substr(prefix.size());
  if (digits.size() > 9 || !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return std::nullopt;
  return std::stoi(digits);
}
}  // namespace

FinModelFactory::FinModelFactory(stage::Mesh mesh, fem::io::MaterialSpec base, std::vector<std::string> names,
                                 FinDrive drive, std::string mesh_source)
    : mesh_(std::move(mesh)),
      base_(std::move(base)),
      names_(std::move(names)),
      drive_(std::move(drive)),
      mesh_source_(std::move(mesh_source)) {
  const std::vector<int> rays = mesh_ray_ids(mesh_);
  std::set<std::string> seen;
  defaults_.resize(static_cast<Eigen::Index>(names_.size()));
  for (size_t i = 0; i < names_.size(); ++i) {
    const std::string& n = names_[i];
    const int idx = static_cast<int>(i);
    if (!seen.insert(n).second) throw InvalidInput("parameters: parameter '" + n + "' is given twice");
    if (n == "E_membrane") {
      membrane_ = idx;
      defaults_(idx) = base_.membrane.youngs_modulus;
    } else if (n == "E_rays") {
      rays_ = idx;
      defaults_(idx) = base_.rays.youngs_modulus;
    } else if (n == "nu") {
      nu_ = idx;
      defaults_(idx) = base_.membrane.poisson_ratio;
    } else if (const auto id = parse_ray_name(n)) {
      if (!std::binary_search(rays.begin(), rays.end(), *id))
        throw InvalidInput("parameters: parameter '" + n + "' names ray " + std::to_string(*id) + ", which " +
                           mesh_source_ + " does not have (beams/ray)");
      ray_.emplace_back(*id, idx);
      defaults_(idx) = base_.ray_material(*id).youngs_modulus;
    } else if (const auto slot = parse_drive_name(n)) {
      drive_slots_.emplace_back(*slot, idx);
      defaults_(idx) = 0;  // the tracked drive
    } else {
      throw InvalidInput("parameters: unknown parameter '" + n +
                         "' (a fin has E_membrane, E_ray<id>, E_rays, nu and drive_*)");
    }
  }
  root_nodes_.assign(mesh_.root_nodes.data.begin(), mesh_.root_nodes.data.end());
  if (!drive_slots_.empty() && !drive_.root_motion)
    throw InvalidInput("parameters: drive_* parameters correct a root motion, and none is given");
  if (!drive_slots_.empty() && !(std::isfinite(drive_.frequency) && drive_.frequency > 0))
    throw InvalidInput("parameters: drive_* parameters need the beat frequency (> 0)");

  // The ramp convention of fin-fem run: ten output intervals before the first output time.
  const std::vector<double>* times = drive_.loads ? &drive_.loads->time.data
                                     : drive_.root_motion ? &drive_.root_motion->time.data
                                                          : nullptr;
  if (drive_.ramp < 0 || !std::isfinite(drive_.ramp)) throw InvalidInput("fin drive: ramp must be >= 0");
  ramp_ = drive_.ramp > 0 ? drive_.ramp : (times && times->size() > 1 ? 10 * ((*times)[1] - (*times)[0]) : 1.0);
  start_time_ = times && !times->empty() ? times->front() - ramp_ : -ramp_;

  // The nominal model: finds bad data now, gives the load history once and each element's slot.
  fem::io::FinModel fm = fem::io::build_fin_model(mesh_, base_, mesh_source_);
  if (drive_.loads) {
    fem::io::apply_loads(fm.model, *drive_.loads, ramp_, drive_.loads_source);
    loads_ = fm.model.load_history();
  }
  if (drive_.root_motion)
    fem::io::apply_root_motion(fm.model, mesh_, *drive_.root_motion, drive_.root_rotation, ramp_,
                               drive_.motion_source);
  const fem::Model& m = fm.model;
  std::map<int, int> region_ray;
  for (const auto& [id, region] : fm.ray_region) region_ray[region] = id;
  for (int e = 0; e < static_cast<int>(m.elements().size()); ++e) {
    const int region = m.element_region(e);
    int slot = kNoModulus;
    if (region == fm.membrane_region) slot = kMembrane;
    else if (auto it = region_ray.find(region); it != region_ray.end()) slot = it->second;
    element_slot_.push_back(slot);
    // The element's own modulus (without the modulation) relative to its region's.
    const double own = m.element_youngs_modulus(e, 0.0) / m.stiffness_field().scale(e, 0.0);
    element_ratio_.push_back(slot == kNoModulus ? 1.0 : own / m.materials()[region].youngs_modulus);
  }
}

fem::io::MaterialSpec FinModelFactory::spec_for(const Eigen::VectorXd& p) const {
  if (p.size() != static_cast<Eigen::Index>(names_.size()))
    throw InvalidInput("fin model: " + std::to_string(p.size()) + " parameter values for " +
                       std::to_string(names_.size()) + " parameters");
  fem::io::MaterialSpec s = base_;
  if (membrane_ >= 0) s.membrane.youngs_modulus = p(membrane_);
  if (rays_ >= 0) {
    s.rays.youngs_modulus = p(rays_);
    for (auto& [id, m] : s.ray) m.youngs_modulus = p(rays_);
  }
  for (const auto& [id, idx] : ray_) {
    fem::Material m = s.ray_material(id);
    m.youngs_modulus = p(idx);
    s.ray[id] = m;
  }
  if (nu_ >= 0) {
    s.membrane.poisson_ratio = p(nu_);
    s.rays.poisson_ratio = p(nu_);
    for (auto& [id, m] : s.ray) m.poisson_ratio = p(nu_);
  }
  return s;
}

std::unique_ptr<fem::Model> FinModelFactory::build(const Eigen::VectorXd& p) const {
  fem::io::FinModel fm = fem::io::build_fin_model(mesh_, spec_for(p), mesh_source_);
  if (!loads_.empty()) fm.model.set_load_history(loads_);
  if (drive_.root_motion)
    fem::io::apply_root_motion(fm.model, mesh_, *drive_.root_motion, drive_.root_rotation, ramp_,
                               drive_.motion_source);
  if (!drive_slots_.empty()) {
    fem::DriveCorrection c;
    c.frequency = drive_.frequency;
    c.first_time = drive_.root_motion->time.data.front();
    c.ramp = ramp_;
    for (const auto& [slot, idx] : drive_slots_) set_drive_coefficient(c, slot, p(idx));
    c.apply(fm.model, root_nodes_);
  }
  fm.model.set_gravity(drive_.gravity);
  return std::make_unique<fem::Model>(std::move(fm.model));
}

Eigen::VectorXd FinModelFactory::rebuild_key(const Eigen::VectorXd& p) const {
  Eigen::VectorXd key = p;
  std::vector<char> kept(names_.size(), 0);  // nu and the drive are built in, not set in place
  if (nu_ >= 0) kept[static_cast<std::size_t>(nu_)] = 1;
  for (const auto& [slot, idx] : drive_slots_) kept[static_cast<std::size_t>(idx)] = 1;
  for (int i = 0; i < static_cast<int>(names_.size()); ++i)
    if (!kept[static_cast<std::size_t>(i)] && i < key.size()) key(i) = defaults_(i);
  return key;
}

double FinModelFactory::membrane_modulus(const Eigen::VectorXd& p) const {
  return membrane_ >= 0 ? p(membrane_) : std::numeric_limits<double>::quiet_NaN();
}

double FinModelFactory::ray_modulus(int ray, const Eigen::VectorXd& p) const {
  for (const auto& [id, idx] : ray_)
    if (id == ray) return p(idx);
  return rays_ >= 0 ? p(rays_) : std::numeric_limits<double>::quiet_NaN();
}

void FinModelFactory::set_moduli(fem::Model& model, const Eigen::VectorXd& p) const {
  if (p.size() != static_cast<Eigen::Index>(names_.size()))
    throw InvalidInput("fin model: " + std::to_string(p.size()) + " parameter values for " +
                       std::to_string(names_.size()) + " parameters");
  for (int e = 0; e < static_cast<int>(element_slot_.size()); ++e) {
    const int slot = element_slot_[e];
    if (slot == kNoModulus) continue;
    const double E = slot == kMembrane ? membrane_modulus(p) : ray_modulus(slot, p);
    if (std::isnan(E)) continue;  // not a parameter: as built
    model.set_element_youngs_modulus(e, E * element_ratio_[e]);
  }
}

}  // namespace finverse::fit

namespace finverse::fit {

std::shared_ptr<const ModelFactory> FinModelFactory::rebased(const std::vector<fem::Vec3>& positions) const {
  const size_t nv = mesh_.points.dim(0);
  if (positions.size() != nv)
    throw InvalidInput("fin model: rebase to " + std::to_string(positions.size()) + " positions, the mesh has " +
                       std::to_string(nv) + " nodes");
  stage::Mesh moved = mesh_;
  for (size_t i = 0; i < nv; ++i)
    for (int d = 0; d < 3; ++d) moved.points(i, static_cast<size_t>(d)) = positions[i](d);
  FinDrive drive = drive_;
  drive.ramp = ramp_;
  return std::make_shared<FinModelFactory>(std::move(moved), base_, names_, std::move(drive), mesh_source_);
}

}  // namespace finverse::fit
