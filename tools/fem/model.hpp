// The structural model: nodes (6 DOF each), region materials, elements, prescribed DOFs, nodal
// loads and gravity. A model is built once and then read by the solvers; the configuration lives
// in NodalState.
//
// Loads: f_ext(t) = load_factor(t) * (sum of nodal loads) + load_history(t) + gravity loads. The static solver uses
// the load factor lambda itself as "time", so the same model serves a load-controlled static
// solve and a dynamic one.
// Prescribed DOFs: value(t) is a displacement for DOFs 0-2 and a rotation-vector component for
// DOFs 3-5. When all three rotations of a node are prescribed, R = exp(theta(t)) exactly;
// otherwise the change of a prescribed component between two times is applied as a spin about
// that global axis (exact for a rotation about a fixed axis, which covers root pitching/heaving).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "fem/beam_section.hpp"
#include "fem/corotational_beam.hpp"
#include "fem/element.hpp"
#include "fem/load_history.hpp"
#include "fem/material.hpp"
#include "fem/nodal_state.hpp"
#include "fem/stiffness_field.hpp"

namespace finverse::fem {

using TimeFunction = std::function<double(double)>;
class Model;
// Adds a load at time t to f (full length, 6 per node); may read the model (e.g. its moduli).
using LoadFunction = std::function<void(const Model&, double, Eigen::VectorXd&)>;

struct PrescribedDof {
  int node = 0;
  int dof = 0;             // 0..5
  TimeFunction value;      // empty: held at zero
  double at(double t) const { return value ? value(t) : 0.0; }
};

struct NodalLoad {
  int node = 0;
  int dof = 0;  // 0..2 force, 3..5 moment (spatial, i.e. a dead moment vector)
  double value = 0;
};

class Model {
 public:
  int add_node(const Vec3& X);
  int add_material(const Material& material);  // validates; returns the region id

  // Beam between two nodes; E of this element may differ from its region's (per-element
  // stiffness, as the inverse fit needs).
  int add_beam(int node1, int node2, int material_id, const TaperedRectangle& section,
               const Vec3& y_axis_hint, std::optional<double> youngs_modulus = std::nullopt,
               CorotationalBeam::Options options = {});
  // Any other element type (shell, solid) built by the caller. region: its material region
  // (-1: none); youngs_modulus: the E it was built with (default: the region's; unknown without a region), the
  // base of set_element_youngs_modulus.
  int add_element(std::unique_ptr<Element> element, int region = -1,
                  std::optional<double> youngs_modulus = std::nullopt);

  // Material fields (stiffness_field.hpp). Each throws InvalidInput for E <= 0 / non-finite or
  // an index out of range.
  void set_element_youngs_modulus(int element, double E);
  void set_region_youngs_modulus(int region, double E);  // every element of the region
  void set_element_modulation(int element, const ModulusModulation& modulation);
  void set_region_modulation(int region, const ModulusModulation& modulation);
  int element_region(int element) const { return element_region_.at(element); }
  double element_youngs_modulus(int element, double t = 0) const {
    return element_modulus_.at(element) * stiffness_.scale(element, t);
  }
  const StiffnessField& stiffness_field() const { return stiffness_; }
  // Distal softening and similar fixed shapes of the modulus field, on top of the moduli a fitter
  // sets (stiffness_field.hpp shape factor).
  void set_element_stiffness_shape(int element, double factor) { stiffness_.set_shape(element, factor); }

  // Mass of an element times a factor (mass matrix, gravity, total mass): a density error or an
  // added inertia (candidate effects, issue 34). Throws InvalidInput unless finite and > 0.
  void set_element_mass_factor(int element, double factor);
  double element_mass_factor(int element) const { return mass_factor_[element]; }
  // Rayleigh damping C = a_M M + a_K K carried by the model: the dynamic solvers add it to the
  // a_M, a_K of their options. Throws InvalidInput for negative or non-finite values.
  void set_rayleigh_damping(double mass, double stiffness);
  double rayleigh_mass() const { return rayleigh_mass_; }
  double rayleigh_stiffness() const { return rayleigh_stiffness_; }
  // Further time-dependent loads (eigen-curvature moments of root actuation, ...), in external_load.
  void add_load_function(LoadFunction load);

  void fix(int node, int dof);
  void fix_node(int node);  // all 6 DOFs
  void prescribe(int node, int dof, TimeFunction value);
  void add_nodal_load(int node, int dof, double value);
  void set_gravity(const Vec3& g);
  void set_load_factor(TimeFunction f) { load_factor_ = std::move(f); }
  // Tabulated nodal loads (loads.h5), added to the nodal loads; its vectors must be full length.
  void set_load_history(LoadHistory history);
  const LoadHistory& load_history() const { return load_history_; }

  int node_count() const { return static_cast<int>(reference_.size()); }
  const std::vector<Vec3>& reference_positions() const { return reference_; }
  const std::vector<std::unique_ptr<Element>>& elements() const { return elements_; }
  const Element& element(int i) const { return *elements_.at(i); }
  const std::vector<Material>& materials() const { return materials_; }
  const std::vector<PrescribedDof>& prescribed() const { return prescribed_; }
  const std::vector<NodalLoad>& nodal_loads() const { return loads_; }
  const Vec3& gravity() const { return gravity_; }
  double load_factor(double t) const { return load_factor_ ? load_factor_(t) : t; }
  double total_mass() const;
  // Largest extent of the reference geometry (scales translation increments in norms).
  double characteristic_length() const;
  // Largest |X| plus the extent: the scale of position round-off.
  double position_scale() const;

  NodalState reference_state() const;
  // Full-length (6 per node) reference load vector: sum of nodal loads (scaled by the load
  // factor in the solvers).
  Eigen::VectorXd reference_load() const;
  // Full-length gravity load (dead, from the reference configuration).
  Eigen::VectorXd gravity_load() const;
  // f_ext(t) = load_factor(t) * reference_load + load_history(t) + gravity_load + load functions
  Eigen::VectorXd external_load(double t) const;

  // Throws InvalidInput naming the first problem: no elements, indices out of range, NaN loads.
  void validate() const;

 private:
  void check_node(int node, const char* what) const;
  void check_dof(int dof, const char* what) const;
  void check_region(int region, const char* what) const;

  std::vector<Vec3> reference_;
  std::vector<Material> materials_;
  std::vector<std::unique_ptr<Element>> elements_;
  std::vector<int> element_region_;
  std::vector<double> element_modulus_;  // E each element was built with
  std::vector<double> mass_factor_;      // per element, 1 unless an effect changed it
  double rayleigh_mass_ = 0, rayleigh_stiffness_ = 0;
  std::vector<LoadFunction> load_functions_;
  StiffnessField stiffness_;
  LoadHistory load_history_;
  std::vector<PrescribedDof> prescribed_;
  std::vector<NodalLoad> loads_;
  Vec3 gravity_ = Vec3::Zero();
  TimeFunction load_factor_;
};

// True when b has a's nodes, elements (type, nodes, active DOFs, in order) and prescribed DOFs:
// the DofMap, assembly pattern and symbolic factorisation built on one serve the other.
bool same_topology(const Model& a, const Model& b);

}  // namespace finverse::fem
