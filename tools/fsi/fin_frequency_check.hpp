// Can the coupled run carry these materials? The fin's first natural frequency in water against
// the flapping frequency (issue 50: a stage never fails on a fit's answer). The in-vacuo
// frequency of the driven structure (root held, fem/modal.hpp) is lowered by the fluid's added
// mass, taken as a flat plate's in heave, rho_f pi c / 4 per unit area (strip theory), against
// the structure's own mass per unit area m_s:
//     f_wet = f_vacuum / sqrt(1 + rho_f pi c / (4 m_s)).
// A fin driven far above its first wet resonance folds within a coupling step; the partitioned
// coupling and the structure's Newton solve then fail, and the ratio below which they did on the
// default fin is measured in docs/studies/default_case.md ("The soft corner").
#pragma once

#include "fem/model.hpp"

namespace finverse::fsi {

struct FinFrequencies {
  double vacuum_hz = 0;      // first natural frequency, root held, in vacuo
  double wet_hz = 0;         // with the plate's added mass
  double mass_per_area = 0;  // structure [kg/m^2]
  double ratio = 0;          // wet_hz / flapping frequency
};

// model: the driven structure (its prescribed root DOFs held); area: the fin's planform [m^2];
// chord [m]; rho_fluid [kg/m^3]; flap_hz: the flapping frequency. Throws finverse::Error when the
// structure has no mass or the modal analysis fails.
FinFrequencies fin_frequencies(const fem::Model& model, double area, double chord, double rho_fluid, double flap_hz);

}  // namespace finverse::fsi
