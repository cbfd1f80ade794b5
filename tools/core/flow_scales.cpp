// Re -> U -> f -> T (see flow_scales.hpp). The expressions' order is part of the results' bits.
#include "core/flow_scales.hpp"

namespace finverse {

double free_stream_speed(double reynolds, double chord, double viscosity) { return reynolds * viscosity / chord; }

double flapping_frequency(double strouhal, double speed, double heave_amplitude) {
  return strouhal * speed / (2.0 * heave_amplitude);
}

double flapping_period(double strouhal, double speed, double heave_amplitude) {
  return 2.0 * heave_amplitude / (strouhal * speed);
}

}  // namespace finverse
