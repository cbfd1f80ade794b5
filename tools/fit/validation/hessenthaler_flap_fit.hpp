// Issue 34, validation 2 (i): the Hessenthaler et al. (2017) silicone flap's modulus from its
// measured buoyancy-only tip deflection (29.50 mm). One unknown E (log10, as every fit modulus)
// found by the Levenberg-Marquardt polish of fit_driver on predicted - measured tip deflection of
// the nonlinear flap model (fem/validation/hessenthaler_flap.hpp): no GA, since the deflection
// falls monotonically with E. The 95 % interval comes from the MRI voxel d (uniform quantisation,
// sd d / sqrt(12)), linearised and checked by refitting at the interval's ends. Also: a mesh
// study, mu = E / 2 (1 + nu) against others' 61 kPa, the uniaxial 96.9 kPa check, and the
// structure-alone residual against Phase I (16.41 mm). Numbers: docs/studies/hessenthaler_flap.md.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/summary.hpp"
#include "fem/validation/hessenthaler_flap.hpp"

namespace finverse::fit::validation {

struct FlapFitOptions {
  std::filesystem::path reference;  // hessenthaler2017.json (data/reference)
  std::string name = "loop_hessenthaler";
  fem::validation::FlapModel model = fem::validation::FlapModel::shell;  // graded on its finest mesh
  bool coarse = false;  // CI variant: the two coarsest meshes of each model
  int load_steps = 8;
  // Bounds of E [Pa] (log10): 20 kPa to 2 MPa, a decade and a half either side of the fit.
  double lower = 2e4, upper = 2e6;
  double mu_tolerance = 0.05;            // mu against the others' 61 kPa (their meshes spread 3 %)
  double deflection_tolerance = 1e-3;    // forward checks, the 1 mm pass rule others used [m]
  double mesh_change_tolerance = 0.005;  // E on the finest two meshes of the graded model
};

// The flap model's deflection residual for the fit: (0, 0, tip(E) - measured) [m].
double fit_flap_modulus(const fem::validation::HessenthalerFlap& flap, const fem::validation::FlapMesh& mesh,
                        double measured_tip, const FlapFitOptions& options, double* dtip_dlog10E = nullptr,
                        long* evaluations = nullptr);

Summary run_hessenthaler_flap_fit(const FlapFitOptions& options);

}  // namespace finverse::fit::validation
