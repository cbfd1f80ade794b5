// Fitted moduli against the truth (issue 33 "Scores", rows 1-2; seed paper Fig. 11): the relative
// error of every fitted ray's E and of the membrane's E against the truth materials; graded are the
// median over the rays (goal 5 %), the worst ray the fit says it identified (15 %) and the membrane
// (10 %). A ray the fit reports as not identified is listed but not graded in the worst-ray score
// (the same rule as the fin twin's grading, tools/fit/validation/fin_twin_grade.hpp).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/stage_files.hpp"
#include "fem/io/material_spec.hpp"
#include "report/score.hpp"

namespace finverse::report {

struct ModulusRow {
  std::string name;               // materials.h5 parameter name (E_membrane, E_ray<id>, nu)
  double fitted = 0, lower = 0, upper = 0;  // best and its 95 % interval (= best when absent)
  std::optional<double> truth;    // absent when the truth does not define the parameter
  bool identified = true;
};

// The truth value of each of `names` (E_membrane, E_rays, E_ray<id>, nu) that the spec defines.
std::map<std::string, double> truth_parameters(const fem::io::MaterialSpec& spec, const std::vector<std::string>& names);
// The truth recorded in truth.h5 (materials/names and values); empty when it records none.
std::map<std::string, double> truth_parameters(const stage::Truth& truth);

// truth: parameter name -> value.
std::vector<ModulusRow> modulus_rows(const stage::Materials& m, const std::map<std::string, double>& truth);
// The three graded scores; `truth_note` says where the truth comes from.
std::vector<Score> modulus_scores(const std::vector<ModulusRow>& rows, const std::string& truth_note);

}  // namespace finverse::report
