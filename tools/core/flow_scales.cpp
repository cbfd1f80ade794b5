// Re -> U -> f -> T (see flow_scales.hpp). The expressions' order is part of the results' bits.
#include "core/flow_scales.hpp"

namespace finverse {

double free_stream_speed(double reynolds, double chord, double viscosity) { return reynolds * viscosity / chord; }

double flapping_frequency(double strouhal, double speed, double peak_to_peak_excursion) {
  return strouhal * speed / peak_to_peak_excursion;
}

double flapping_period(double strouhal, double speed, double peak_to_peak_excursion) {
  return peak_to_peak_excursion / (strouhal * speed);
}

}  // namespace finverse
