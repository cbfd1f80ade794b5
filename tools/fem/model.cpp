// Structural model bookkeeping and input checks (see model.hpp).
#include "fem/model.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fem/errors.hpp"

namespace finverse::fem {

namespace {
const char* dof_name(int dof) {
  static const char* names[] = {"ux", "uy", "uz", "rx", "ry", "rz"};
  return (dof >= 0 && dof < 6) ? names[dof] : "?";
}
}  // namespace

int Model::add_node(const Vec3& X) {
  if (!X.allFinite()) {
    std::ostringstream os;
    os << "node " << reference_.size() << ": non-finite coordinates (" << X.transpose() << ")";
    throw InvalidInput(os.str());
  }
  reference_.push_back(X);
  return node_count() - 1;
}

int Model::add_material(const Material& material) {
  fem::validate(material);
  materials_.push_back(material);
  return static_cast<int>(materials_.size()) - 1;
}

void Model::check_node(int node, const char* what) const {
  if (node < 0 || node >= node_count()) {
    std::ostringstream os;
    os << what << ": node " << node << " out of range (model has " << node_count() << " nodes)";
    throw InvalidInput(os.str());
  }
}

void Model::check_dof(int dof, const char* what) const {
  if (dof < 0 || dof >= kDofsPerNode) {
    std::ostringstream os;
    os << what << ": dof " << dof << " out of range, expected 0..5";
    throw InvalidInput(os.str());
  }
}

int Model::add_beam(int node1, int node2, int material_id, const TaperedRectangle& section,
                    const Vec3& y_axis_hint, std::optional<double> youngs_modulus,
                    CorotationalBeam::Options options) {
  check_node(node1, "beam");
  check_node(node2, "beam");
  if (material_id < 0 || material_id >= static_cast<int>(materials_.size()))
    throw InvalidInput("beam: material id " + std::to_string(material_id) + " out of range");
  Material m = materials_[material_id];
  if (youngs_modulus) m.youngs_modulus = *youngs_modulus;
  fem::validate(m);
  return add_element(std::make_unique<CorotationalBeam>(
                         node1, node2, reference_[node1], reference_[node2], y_axis_hint, m, section, options),
                     material_id, m.youngs_modulus);
}

int Model::add_element(std::unique_ptr<Element> element, int region, std::optional<double> E) {
  for (int n : element->nodes()) check_node(n, "element");
  if (region >= 0) check_region(region, "element");
  // Unknown base modulus (no region, no E): NaN, so that set_element_youngs_modulus refuses.
  const double e0 = E ? *E : (region >= 0 ? materials_[region].youngs_modulus : std::nan(""));
  if (E && (!std::isfinite(e0) || e0 <= 0))
    throw InvalidInput("element " + std::to_string(elements_.size()) + ": Young's modulus " +
                       std::to_string(e0) + ", expected a finite value > 0");
  elements_.push_back(std::move(element));
  element_region_.push_back(region);
  element_modulus_.push_back(e0);
  mass_factor_.push_back(1.0);
  stiffness_.resize(static_cast<int>(elements_.size()));
  return static_cast<int>(elements_.size()) - 1;
}

void Model::check_region(int region, const char* what) const {
  if (region < 0 || region >= static_cast<int>(materials_.size()))
    throw InvalidInput(std::string(what) + ": material region " + std::to_string(region) +
                       " out of range (" + std::to_string(materials_.size()) + " regions)");
}

void Model::set_element_youngs_modulus(int e, double E) {
  if (e < 0 || e >= static_cast<int>(elements_.size()))
    throw InvalidInput("element " + std::to_string(e) + " out of range");
  if (!std::isfinite(E) || E <= 0) {
    std::ostringstream os;
    os << "element " << e << ": Young's modulus E = " << E << ", expected a finite value > 0";
    throw InvalidInput(os.str());
  }
  if (!std::isfinite(element_modulus_[e]))
    throw InvalidInput("element " + std::to_string(e) + ": built without a known Young's modulus");
  stiffness_.set_factor(e, E / element_modulus_[e]);
}

void Model::set_region_youngs_modulus(int region, double E) {
  check_region(region, "region modulus");
  if (!std::isfinite(E) || E <= 0) {
    std::ostringstream os;
    os << "material '" << materials_[region].name << "': Young's modulus E = " << E
       << ", expected a finite value > 0";
    throw InvalidInput(os.str());
  }
  for (int e = 0; e < static_cast<int>(elements_.size()); ++e)
    if (element_region_[e] == region) set_element_youngs_modulus(e, E);
}

void Model::set_element_modulation(int e, const ModulusModulation& m) {
  if (e < 0 || e >= static_cast<int>(elements_.size()))
    throw InvalidInput("element " + std::to_string(e) + " out of range");
  stiffness_.set_modulation(e, m);
}

void Model::set_region_modulation(int region, const ModulusModulation& m) {
  check_region(region, "region modulation");
  for (int e = 0; e < static_cast<int>(elements_.size()); ++e)
    if (element_region_[e] == region) stiffness_.set_modulation(e, m);
}

void Model::set_load_history(LoadHistory history) {
  if (!history.empty() && history.at(history.times().front()).size() != kDofsPerNode * node_count())
    throw InvalidInput("load history: load vectors have " +
                       std::to_string(history.at(history.times().front()).size()) +
                       " entries, expected 6 per node (" + std::to_string(kDofsPerNode * node_count()) + ")");
  load_history_ = std::move(history);
}

void Model::fix(int node, int dof) { prescribe(node, dof, {}); }

void Model::fix_node(int node) {
  for (int d = 0; d < kDofsPerNode; ++d) fix(node, d);
}

void Model::prescribe(int node, int dof, TimeFunction value) {
  check_node(node, "prescribed dof");
  check_dof(dof, "prescribed dof");
  for (auto& p : prescribed_)
    if (p.node == node && p.dof == dof) {
      p.value = std::move(value);
      return;
    }
  prescribed_.push_back({node, dof, std::move(value)});
}

void Model::add_nodal_load(int node, int dof, double value) {
  check_node(node, "nodal load");
  check_dof(dof, "nodal load");
  if (!std::isfinite(value)) {
    std::ostringstream os;
    os << "nodal load on node " << node << " dof " << dof_name(dof) << " is " << value
       << ", expected a finite value";
    throw InvalidInput(os.str());
  }
  loads_.push_back({node, dof, value});
}

void Model::set_gravity(const Vec3& g) {
  if (!g.allFinite()) throw InvalidInput("gravity vector is not finite");
  gravity_ = g;
}

double Model::total_mass() const {
  double m = 0;
  for (std::size_t e = 0; e < elements_.size(); ++e) m += mass_factor_[e] * elements_[e]->total_mass();
  return m;
}

double Model::characteristic_length() const {
  if (reference_.empty()) return 1.0;
  Vec3 lo = reference_[0], hi = reference_[0];
  for (const auto& X : reference_) lo = lo.cwiseMin(X), hi = hi.cwiseMax(X);
  const double l = (hi - lo).norm();
  return l > 0 ? l : 1.0;
}

double Model::position_scale() const {
  double m = 0;
  for (const auto& X : reference_) m = std::max(m, X.norm());
  return m + characteristic_length();
}

NodalState Model::reference_state() const {
  NodalState s;
  s.position = reference_;
  s.rotation.assign(reference_.size(), Mat3::Identity());
  return s;
}

Eigen::VectorXd Model::reference_load() const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(kDofsPerNode * node_count());
  for (const auto& l : loads_) f(kDofsPerNode * l.node + l.dof) += l.value;
  return f;
}

Eigen::VectorXd Model::gravity_load() const {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(kDofsPerNode * node_count());
  if (gravity_.squaredNorm() == 0) return f;
  const NodalState s = reference_state();
  Eigen::VectorXd fe;
  for (std::size_t i = 0; i < elements_.size(); ++i) {
    const auto& e = elements_[i];
    fe.setZero(e->size());
    e->gravity_force(s, gravity_, fe);
    fe *= mass_factor_[i];
    const auto nodes = e->nodes();
    const auto dofs = e->active_dofs();
    int k = 0;
    for (int n : nodes)
      for (int d : dofs) f(kDofsPerNode * n + d) += fe(k++);
  }
  return f;
}

Eigen::VectorXd Model::external_load(double t) const {
  const double lf = load_factor(t);
  if (!std::isfinite(lf)) {
    std::ostringstream os;
    os << "load factor at t = " << t << " is " << lf << ", expected a finite value";
    throw InvalidInput(os.str());
  }
  Eigen::VectorXd f = lf * reference_load();
  if (!load_history_.empty()) f += load_history_.at(t);
  if (gravity_.squaredNorm() > 0) f += gravity_load();
  for (const auto& g : load_functions_) g(*this, t, f);
  return f;
}

void Model::set_element_mass_factor(int e, double factor) {
  if (e < 0 || e >= static_cast<int>(elements_.size()))
    throw InvalidInput("element " + std::to_string(e) + " out of range");
  if (!std::isfinite(factor) || factor <= 0) {
    std::ostringstream os;
    os << "element " << e << ": mass factor " << factor << ", expected a finite value > 0";
    throw InvalidInput(os.str());
  }
  mass_factor_[e] = factor;
}

void Model::set_rayleigh_damping(double mass, double stiffness) {
  if (!std::isfinite(mass) || !std::isfinite(stiffness) || mass < 0 || stiffness < 0) {
    std::ostringstream os;
    os << "Rayleigh damping a_M = " << mass << ", a_K = " << stiffness << ", expected finite values >= 0";
    throw InvalidInput(os.str());
  }
  rayleigh_mass_ = mass;
  rayleigh_stiffness_ = stiffness;
}

void Model::add_load_function(LoadFunction load) {
  if (load) load_functions_.push_back(std::move(load));
}

void Model::validate() const {
  if (elements_.empty()) throw InvalidInput("model has no elements");
  for (const auto& l : loads_)
    if (!std::isfinite(l.value)) {
      std::ostringstream os;
      os << "nodal load on node " << l.node << " dof " << dof_name(l.dof) << " is " << l.value;
      throw InvalidInput(os.str());
    }
  for (const auto& m : materials_) fem::validate(m);
}

bool same_topology(const Model& a, const Model& b) {
  if (a.node_count() != b.node_count() || a.elements().size() != b.elements().size() ||
      a.prescribed().size() != b.prescribed().size())
    return false;
  for (size_t e = 0; e < a.elements().size(); ++e) {
    const Element &x = *a.elements()[e], &y = *b.elements()[e];
    if (x.type() != y.type() || !std::ranges::equal(x.nodes(), y.nodes()) ||
        !std::ranges::equal(x.active_dofs(), y.active_dofs()))
      return false;
  }
  for (size_t k = 0; k < a.prescribed().size(); ++k)
    if (a.prescribed()[k].node != b.prescribed()[k].node || a.prescribed()[k].dof != b.prescribed()[k].dof)
      return false;
  return true;
}

}  // namespace finverse::fem
