// Per-element modulus factors and periodic modulation (see stiffness_field.hpp).
#include "fem/stiffness_field.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "fem/errors.hpp"

namespace finverse::fem {

double ModulusModulation::factor(double t) const {
  return 1.0 + amplitude * std::sin(2.0 * std::numbers::pi * frequency * t + phase);
}

void StiffnessField::resize(int elements) {
  factor_.resize(elements, 1.0);
  shape_.resize(elements, 1.0);
  modulation_.resize(elements);
}

void StiffnessField::check(int e) const {
  if (e < 0 || e >= size())
    throw InvalidInput("stiffness field: element " + std::to_string(e) + " out of range (" +
                       std::to_string(size()) + " elements)");
}

void StiffnessField::set_factor(int e, double f) {
  check(e);
  if (!std::isfinite(f) || f <= 0) {
    std::ostringstream os;
    os << "element " << e << ": Young's modulus factor " << f << ", expected a finite value > 0";
    throw InvalidInput(os.str());
  }
  non_unit_ += (f != 1.0) - (factor_[e] != 1.0);
  factor_[e] = f;
}

void StiffnessField::set_modulation(int e, const ModulusModulation& m) {
  check(e);
  if (!std::isfinite(m.amplitude) || !(std::abs(m.amplitude) < 1) || !std::isfinite(m.frequency) ||
      m.frequency < 0 || !std::isfinite(m.phase)) {
    std::ostringstream os;
    os << "element " << e << ": modulus modulation a = " << m.amplitude << ", f = " << m.frequency
       << ", phi = " << m.phase << ", expected |a| < 1 (E stays > 0), f >= 0, all finite";
    throw InvalidInput(os.str());
  }
  modulated_ -= modulated(e);
  modulation_[e] = m;
  modulated_ += modulated(e);
}

void StiffnessField::clear_modulation(int e) {
  check(e);
  modulated_ -= modulated(e);
  modulation_[e] = {};
}

void StiffnessField::set_shape(int e, double g) {
  check(e);
  if (!std::isfinite(g) || g <= 0) {
    std::ostringstream os;
    os << "element " << e << ": Young's modulus shape factor " << g << ", expected a finite value > 0";
    throw InvalidInput(os.str());
  }
  shaped_ += (g != 1.0) - (shape_[e] != 1.0);
  shape_[e] = g;
}

double StiffnessField::scale(int e, double t) const {
  const double f = factor_[e] * shape_[e];
  return modulated(e) ? f * modulation_[e].factor(t) : f;
}

bool StiffnessField::modulated(int e) const {
  return modulation_[e].amplitude != 0;
}

}  // namespace finverse::fem
