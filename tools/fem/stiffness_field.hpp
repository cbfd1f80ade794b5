// Young's-modulus field over the elements: a per-element factor and an optional periodic
// modulation in time, E_e(t) = E_e g_e (1 + a sin(2 pi f t + phi)) (g_e: a fixed shape factor) (DESIGN.md section 5.2, issue 3:
// the material fields the inverse fit and the effect tracing vary).
//
// Why a factor and not a new element: with the Poisson ratio fixed, the corotational beam and
// shell and the St. Venant-Kirchhoff solid have internal forces, tangents and strain energies
// that are exactly linear in E (local linear elasticity, geometric stiffness proportional to the
// local forces), so E_e(t) = s_e(t) E_element enters as f_e <- s_e f_e, K_e <- s_e K_e. The
// elements stay immutable and built once, and a fitter varies the moduli of an existing model
// without rebuilding its assembler or the solver's symbolic factorisation.
#pragma once

#include <vector>

namespace finverse::fem {

struct ModulusModulation {
  double amplitude = 0;  // a, |a| < 1 keeps E > 0
  double frequency = 0;  // f [Hz]
  double phase = 0;      // phi [rad]
  double factor(double t) const;
};

class StiffnessField {
 public:
  void resize(int elements);  // new elements get factor 1, no modulation

  // E_e / E with which the element was built; throws InvalidInput unless finite and > 0.
  void set_factor(int element, double factor);
  // Throws InvalidInput unless |a| < 1, f >= 0 and every value finite.
  void set_modulation(int element, const ModulusModulation& modulation);
  void clear_modulation(int element);
  // A second fixed factor (a shape of the field, e.g. distal softening) that set_factor leaves
  // alone; throws InvalidInput unless finite and > 0.
  void set_shape(int element, double factor);
  double shape(int element) const { return shape_[element]; }

  double factor(int element) const { return factor_[element]; }
  double scale(int element, double t) const;  // factor times the modulation at time t
  bool uniform() const { return non_unit_ == 0 && modulated_ == 0 && shaped_ == 0; }  // every scale is 1, always
  int size() const { return static_cast<int>(factor_.size()); }

 private:
  void check(int element) const;
  bool modulated(int element) const;
  std::vector<double> factor_, shape_;
  std::vector<ModulusModulation> modulation_;  // amplitude 0: none
  // Counts kept up to date so that uniform() is O(1) (the assembly asks it per element) and a
  // fitter can reset every element's modulus in O(elements).
  int non_unit_ = 0, modulated_ = 0, shaped_ = 0;
};

}  // namespace finverse::fem
