// Issue 34, validation 2 (ii), PLANE VERSION ONLY: the Hessenthaler et al. (2017) Phase I flow
// (two parabolic inlets, peaks 0.630 / 0.615 m/s; measured steady tip 16.41 mm) on a 2-D section
// through the junction's symmetry plane. Not the experiment: the plane flap spans the depth and
// walls off the two jets. Channel of the outlet's 76.2 mm, two inlet slots at the pipes' offsets,
// a 65 x 2 mm plane-strain Q9 strip (fem/validation/turek_hron_flag.hpp) with the fitted E, nu
// 0.45 and net buoyancy as a body force, coupled as the Turek-Hron FSI runs (IQN-ILS). Every
// geometric choice is in the summary's parameters and docs/studies/hessenthaler_flap.md. A failed
// step ends the run and still writes the summary, graded run_failed = 1. The summary also keeps the
// flow's time-mean load on the flap per station (fin-loop flap's Phase I load, labelled plane).
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "core/summary.hpp"
#include "fem/validation/turek_hron_flag.hpp"

namespace finverse::fsi::validation {

struct HessenthalerPlaneOptions {
  std::filesystem::path reference;  // hessenthaler2017.json
  double youngs_modulus = 0;        // [Pa], from fin-fit flap
  double h = 0.5e-3;                // uniform cell width around the flap [m]
  double outlet_length = 0.25;      // channel length behind the inlet [m]
  double stretch_ratio = 1.05;
  double cfl = 0.5;
  double t_end = 3.0;
  double ramp_time = 0.5;
  fem::validation::FlagMesh mesh{16, 2, 2.0};
  double tolerance = 1e-4;            // relative interface residual
  double absolute_tolerance = 1e-7;   // [m]
  int max_iterations = 20;
  int load_bins = 13;                 // stations of the recorded mean flow load (5 mm each)
  std::function<void(const std::string&)> progress;
};

Summary run_hessenthaler_plane_fsi(const HessenthalerPlaneOptions& options);

}  // namespace finverse::fsi::validation
