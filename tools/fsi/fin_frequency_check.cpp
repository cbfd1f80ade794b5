// The fin's first natural frequency in water (see fin_frequency_check.hpp).
#include "fsi/fin_frequency_check.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "core/error.hpp"
#include "fem/modal.hpp"

namespace finverse::fsi {

FinFrequencies fin_frequencies(const fem::Model& model, double area, double chord, double rho_fluid, double flap_hz) {
  if (!(area > 0) || !(chord > 0) || !(rho_fluid > 0) || !(flap_hz > 0))
    throw Error("fin frequencies: expected a positive area, chord, fluid density and flapping frequency");
  FinFrequencies f;
  f.mass_per_area = model.total_mass() / area;
  if (!(f.mass_per_area > 0)) throw Error("fin frequencies: the structure has no mass");
  fem::ModalOptions options;
  options.modes = 1;
  const fem::ModalResult modes = fem::modal_analysis(model, model.reference_state(), options);
  f.vacuum_hz = modes.frequency(0);
  const double added = rho_fluid * std::numbers::pi * chord / 4;
  f.wet_hz = f.vacuum_hz / std::sqrt(1 + added / f.mass_per_area);
  f.ratio = f.wet_hz / flap_hz;
  return f;
}

}  // namespace finverse::fsi
