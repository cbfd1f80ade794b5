// Grading of the fin twin fitted through tracking noise (issue 45, goal 6): the materials.h5 of
// fin-fit run --target-noise on the 22-parameter trout twin's target, one per noise seed, against
// the modulus field the target was computed with. Goals over all seeds: the 95 % intervals of the
// identified parameters cover the truth in >= 80 % of cases, >= 80 % of the rays are identified,
// the median ray modulus error <= 5 %. A parameter reported not identified is not held to its
// interval (the fit said it cannot tell) but counts against the identified fraction.
#pragma once

#include <string>
#include <vector>

#include "core/stage_files.hpp"
#include "core/summary.hpp"
#include "fem/io/material_spec.hpp"

namespace finverse::fit::validation {

struct FinTwinNoiseGoals {
  double coverage = 0.8;
  double rays_identified = 0.8;
  double median_ray = 0.05;
};

// Throws fit::InvalidInput when a fit has no intervals (fitted without the polish) or the fits
// name different parameters. `sources` names each fit in messages.
Summary grade_fin_twin_noise(const std::vector<stage::Materials>& fits, const std::vector<std::string>& sources,
                             const fem::io::MaterialSpec& truth, const std::string& case_name,
                             const FinTwinNoiseGoals& goals = {});

}  // namespace finverse::fit::validation
