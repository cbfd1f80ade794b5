// Fit validation on the hybrid plate of the seed paper's section 3.4 (issue 31, validations 2, 3
// and 5): a twin whose truth is the motion fin-fem computes with the case's moduli
// (data/cases/hybrid_plate.json: E_s, E_b1..3, nu) under known loads -- the leading-edge heave
// y = A (1 - cos 2 pi f t) and the thin-airfoil pressure of the heaving plate
// (thin_airfoil_loads.hpp) -- fitted back with bounds spanning three decades around the truth
// (placed off-centre so that a fit cannot win by returning the middle) and nu in [0.15, 0.45]:
//   hybrid_plate      eq. (1) (dynamic, compared over the last period) and eq. (2) (quasi-static
//                     increments of T/400 at mid-swing, as the paper) in one run: every parameter's
//                     error, the wall-time ratio of the two fits;
//   noise             the target perturbed by isotropic Gaussian noise of mean vertex error
//                     noise_over_chord (fin-track's 0.3 %), over several seeds: errors and how
//                     often the 95 % intervals cover the truth;
//   identifiability   eq. (2) with the loads removed: the modulus scale must come out not
//                     identified (DESIGN.md section 5.4's trap).
#pragma once

#include <filesystem>

#include "core/summary.hpp"
#include "fit/fit_driver.hpp"
#include "fit/validation/hybrid_plate_setup.hpp"

namespace finverse::fit::validation {

struct HybridPlateFitOptions : HybridPlateSetup {
  FitOptions fit;                   // runs, population, generations, seed, threads
  // hybrid_plate: also write the eq. (2) fit as materials.h5 (the golden-file regression test)
  std::filesystem::path materials_out;
  // noise
  int noise_seeds = 10;
  double noise_over_chord = 0.003;
  std::string noise_objective = "dynamic";
};

Summary run_hybrid_plate_fit(const HybridPlateFitOptions& options);
Summary run_hybrid_plate_noise(const HybridPlateFitOptions& options);
Summary run_hybrid_plate_identifiability(const HybridPlateFitOptions& options);

}  // namespace finverse::fit::validation
