// Flow scales of the flapping fin (seed paper section 4.2): the chord Reynolds number
// Re = U c / nu gives the free-stream speed U, the Strouhal number St = f 2A / U the flapping
// frequency f (A the root heave amplitude, 2A its peak-to-peak excursion), and T = 2A / (St U)
// the period. The one place these conversions and the water viscosity are written: fin-synth's
// prescribed motion (vision/kinematic_model), fin-track's period (--reynolds ...), the fin's flow
// run (cfd/io/fin_flow_case).
#pragma once

namespace finverse {

// Kinematic viscosity of water at about 20 C (m^2/s), the seed paper's fluid.
inline constexpr double kWaterKinematicViscosity = 1.0e-6;

// U = Re nu / c (m/s).
double free_stream_speed(double reynolds, double chord, double viscosity = kWaterKinematicViscosity);

// f = St U / (2A) (1/s); heave_amplitude A in m.
double flapping_frequency(double strouhal, double speed, double heave_amplitude);

// T = 2A / (St U) (s), evaluated as written: 1 / flapping_frequency can differ from it in the
// last bit (fin-synth's truth.h5 stores 1 / f, fin-track's kinematics.h5 this).
double flapping_period(double strouhal, double speed, double heave_amplitude);

}  // namespace finverse
