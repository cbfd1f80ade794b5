// Fit validations on the seed paper's hybrid plate (sec. 3.4; issue 31, validations 2, 3, 5), a
// twin set up by hybrid_plate_setup.hpp:
//   hybrid_plate     eq. (1) over the last period, eq. (2) at mid-swing (T/400) in the paper's form
//                    and with inertia (measured_inertia.hpp) in one run:
//                    every parameter's error and the wall-time ratio of the two fits;
//   noise            the target with fin-track's noise (mean vertex error 0.3 % c), several seeds:
//                    errors, identified fraction and 95 % interval coverage;
//   identifiability  eq. (2) without loads: the modulus scale must come out not identified.
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
