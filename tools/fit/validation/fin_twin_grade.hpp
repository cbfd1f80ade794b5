// Grading of a fin twin's fit (issue 31, validation 4; seed paper sec. 4.3, Fig. 11): the
// materials.h5 of fin-fit run on a target that fin-fem computed with a known modulus field (the
// trout twin: data/cases/trout_fin_materials.json) compared with that field, parameter by
// parameter. Goals: the median ray modulus error <= 5 %, every identified ray <= 15 %, the
// membrane <= 10 %. A ray the fit reports as not identified is listed with its error but not
// graded: the fit said it cannot tell, which is the answer the product owes (never a confident
// wrong number); how many were identified is reported beside it.
#pragma once

#include "core/stage_files.hpp"
#include "core/summary.hpp"
#include "fem/io/material_spec.hpp"

namespace finverse::fit::validation {

struct FinTwinGoals {
  double median_ray = 0.05;
  double each_identified_ray = 0.15;
  double membrane = 0.10;
};

// The truth's value of a fin parameter: E_membrane, E_ray<id>, E_rays, nu (fin_parameters.hpp).
// Throws fit::InvalidInput for a parameter name that the truth does not define.
double fin_twin_truth_value(const std::string& name, const fem::io::MaterialSpec& truth);

Summary grade_fin_twin(const stage::Materials& fitted, const fem::io::MaterialSpec& truth,
                       const std::string& case_name, const FinTwinGoals& goals = {});

}  // namespace finverse::fit::validation
