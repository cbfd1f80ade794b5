// Validation cases of the structural FEM (DESIGN.md section 6), run by `fin-fem <case>`; each returns
// the content of its summary.json (core/summary.hpp) but for the timing, which fin-fem adds.
#pragma once

#include <filesystem>
#include <string>

#include "core/summary.hpp"
#include "fem/sparse_solver.hpp"

namespace finverse::fem::validation {

// Cantilever under a dead tip load perpendicular to its axis (the elastica), PL^2/EI = 1, 2, 5,
// 10, 20; tip deflection, shortening and rotation against structures.json "elastica_tip_load".
struct ElasticaOptions {
  std::filesystem::path reference;  // structures.json
  int elements = 32;
  int load_steps_per_unit = 4;      // initial Newton load steps per unit of PL^2/EI
  double tolerance = 0.005;
  SolverBackend backend = SolverBackend::cholmod;
};
Summary run_elastica(const ElasticaOptions& options);

// Uniform cantilever: first three bending frequencies against Euler-Bernoulli, from the
// linearised eigenproblem and from the spectrum of a simulated free vibration; energy drift of an
// undamped free vibration over 100 periods of the first mode.
struct VibrationOptions {
  int elements = 20;
  int steps_per_period_spectrum = 1500;  // time step for the spectral run: T1 / this
  double periods_spectrum = 10;
  int steps_per_period_energy = 100;     // time step for the energy run
  double periods_energy = 100;
  double frequency_tolerance = 0.005;
  double energy_drift_goal = 0.001;
  SolverBackend backend = SolverBackend::cholmod;
};
Summary run_cantilever_vibration(const VibrationOptions& options);

// Roots beta_n L of the Euler-Bernoulli cantilever equation cos(x) cosh(x) + 1 = 0, n = 1, 2, ...
double cantilever_beta_l(int n);

}  // namespace finverse::fem::validation
