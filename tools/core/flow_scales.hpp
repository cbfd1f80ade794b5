// Flow scales of the flapping fin (seed paper section 4.2): the chord Reynolds number
// Re = U c / nu gives the free-stream speed U, and the Strouhal number St = f A / U the flapping
// frequency f and the period T = A / (St U). A is the trailing edge's PEAK-TO-PEAK lateral
// excursion, as in the paper's "St = fA/U" and in fish studies, not the root heave's half
// amplitude: basing St on the root's 2 x 0.44 c gave 5 Hz where the paper's trailing-edge points
// (about 1.0 c peak to peak) give 4.4 Hz (docs/studies/fin_kinematics_and_force_size.md).
// The one place these conversions and the water viscosity are written: fin-synth's prescribed
// motion (vision/kinematic_model), fin-track's period (--reynolds ...), the fin's flow run
// (cfd/io/fin_flow_case).
#pragma once

namespace finverse {

// Kinematic viscosity of water at about 20 C (m^2/s), the seed paper's fluid.
inline constexpr double kWaterKinematicViscosity = 1.0e-6;

// U = Re nu / c (m/s).
double free_stream_speed(double reynolds, double chord, double viscosity = kWaterKinematicViscosity);

// f = St U / A (1/s); peak_to_peak_excursion A in m (the trailing edge's, see above).
double flapping_frequency(double strouhal, double speed, double peak_to_peak_excursion);

// T = A / (St U) (s), evaluated as written: 1 / flapping_frequency can differ from it in the
// last bit (fin-synth's truth.h5 stores 1 / f, fin-track's kinematics.h5 this).
double flapping_period(double strouhal, double speed, double peak_to_peak_excursion);

}  // namespace finverse
