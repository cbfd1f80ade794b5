// Turek-Hron CSM benchmarks (Turek & Hron 2006, "Proposal for numerical benchmarking of fluid-
// structure interaction between an elastic object and laminar incompressible flow", in: Fluid-
// Structure Interaction, LNCSE 53, Springer, pp. 371-385, section 3.2): the elastic flag behind
// the cylinder, alone, under gravity g = 2 m/s^2, as a St. Venant-Kirchhoff plane-strain solid
// (Q9, plane_strain_solid.hpp).
//   CSM1, CSM2  static deflection (E = 1.4e6 / 5.6e6 Pa): ux, uy of point A (tip centre),
//               with a mesh convergence study.
//   CSM3        dynamic, released from rest in the undeformed shape with gravity switched on at
//               t = 0 (E = 1.4e6 Pa): undamped oscillation; mean, amplitude and frequency of
//               ux_A, uy_A over the last period (generalized-alpha), with a time-step study.
// Geometry, material and reference values come from turek_hron.json. The flag's left end is
// clamped on the cylinder: by default along the arc x = xc + sqrt(r^2 - (y - yc)^2) itself, as
// in the benchmark's geometry (the flag is the part of the 0.35 x 0.02 rectangle outside the
// cylinder); `straight_clamp` instead cuts it straight at the arc's corner abscissa
// xc + sqrt(r^2 - (h/2)^2) ~ 0.24899 (reported for comparison: the two differ by a 1 mm sliver).
#pragma once

#include <filesystem>
#include <vector>

#include "core/summary.hpp"
#include "fem/sparse_solver.hpp"
#include "fem/validation/turek_hron_flag.hpp"  // FlagMesh, the flag model

namespace finverse::fem::validation {

struct CsmStaticOptions {
  std::filesystem::path reference;  // turek_hron.json
  int case_number = 1;              // 1 (CSM1) or 2 (CSM2)
  bool coarse = false;              // CI variant: meshes 5x1, 10x1, 20x2 (default adds 40x4, 80x8)
  std::vector<FlagMesh> meshes;     // empty: the default study; the last mesh is graded
  bool straight_clamp = false;
  int load_steps = 4;
  double tolerance = 0.01;
  SolverBackend backend = SolverBackend::cholmod;
};
Summary run_turek_hron_csm_static(const CsmStaticOptions& options);

struct Csm3Options {
  std::filesystem::path reference;  // turek_hron.json
  bool coarse = false;              // CI variant: mesh 10x1, dt = 0.01 only, no check meshes
  FlagMesh mesh = {20, 2, 3.0};
  // Empty: the default study 0.01, 0.005, 0.0025, 0.00125 s; the last one is graded. rho_inf = 1
  // leaves the higher bending modes excited by the sudden gravity undamped, as in the benchmark;
  // the phase of the second mode (~7 Hz) at the last period moves the extremes, so the step must
  // resolve it (period error ~ (omega_2 dt)^2 / 12 accumulates over ~70 of its cycles).
  std::vector<double> time_steps;
  std::vector<FlagMesh> check_meshes = {{10, 1, 3.0}};  // also run at the graded step (info)
  double spectral_radius = 1.0;
  // Relative Newton residual per step. The Q9 flag's assembled residual stalls at ~2e-9 from
  // position round-off (each element's nodal forces are ~1e3 times the net gravity load), a
  // little above the integrator's estimated round-off floor, so 1e-9 can fail on noise; 1e-8
  // still leaves the displacement error per step at round-off level.
  double residual_tolerance = 1e-8;
  double end_time = 10.0;
  bool straight_clamp = false;
  double tolerance = 0.02;
  SolverBackend backend = SolverBackend::cholmod;
};
Summary run_turek_hron_csm3(const Csm3Options& options);

// Mean, amplitude and frequency of a sampled oscillation over its last full period.
struct LastPeriod {
  double t_begin = 0, t_end = 0;  // the period's window
  double frequency = 0;           // 1 / (t_end - t_begin)
  double mean_frequency = 0;      // periods completed after the first, averaged
  int periods = 0;                // full periods found
};
// Periods are delimited by upward crossings of `signal` through the midpoint of its range (linear
// interpolation between samples); a crossing counts only after the signal has been below the
// midpoint by a quarter of the half-range, so ripple from higher modes cannot add crossings.
// Throws NotConverged when fewer than two crossings exist.
LastPeriod last_period(const std::vector<double>& time, const std::vector<double>& signal);
// (max + min) / 2 and (max - min) / 2 of the samples in [t_begin, t_end], each extremum refined
// by the parabola through it and its neighbours.
struct MeanAmplitude {
  double mean = 0, amplitude = 0;
};
MeanAmplitude mean_amplitude(const std::vector<double>& time, const std::vector<double>& signal,
                             double t_begin, double t_end);

}  // namespace finverse::fem::validation
