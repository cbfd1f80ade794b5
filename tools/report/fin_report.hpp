// The report of one case (issue 33 "Deliver" 3; DESIGN.md sections 1 and 5.6): from the case's
// stage files it grades the scores of the table that the present files allow and gathers
// the data of the paper's figures (Fig. 10 pressure jump, 11 moduli, 12 root pitch, 14 trailing
// edge, 15 profiles and W shape, 16 force coefficients) for tools/scripts/report_figures.py.
// Every FSI-against-reconstruction score needs fsi.h5; without it the score is "not available"
// with that reason, and the reconstruction's own numbers (and the truth's) are given as info.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/stage_files.hpp"
#include "loop/io/loop_file.hpp"
#include "report/score.hpp"

namespace finverse::report {

struct ReportInputs {
  std::string case_name;
  std::optional<stage::Truth> truth;
  std::optional<stage::Kinematics> kinematics;
  std::optional<stage::Mesh> mesh;
  std::optional<stage::Motion> motion;
  std::optional<stage::Loads> loads;
  std::optional<stage::Materials> materials;
  std::optional<stage::Fsi> fsi;
  std::optional<loop::io::LoopFile> loop;         // fin-loop trace: the "Closing the loop" section
  std::string loop_source;                        // its path, for messages
  std::map<std::string, double> truth_materials;  // parameter name -> value (empty: none)
  std::string truth_materials_source;             // where they come from, for the notes
  double chord = 0;                               // [m]; 0: mesh.h5's chord attribute
  std::string scope;  // what this case's scores can test (the tiny case: the grading, not the method)
};

struct Report {
  std::vector<Score> scores;
  nlohmann::json figures;  // figure data, one key per figure
};

// Throws finverse::Error when present files disagree in shape (e.g. fsi.h5 on other nodes, a
// loop.h5 of another mesh) or loop.h5 comes without mesh.h5.
Report build_report(const ReportInputs& in);

// summary.json: {"schema": "finverse/report", "case", "scores": [...], "counts": {met, missed,
// not available}, "inputs": {stage: present}} ("loop" among the inputs only when given), and
// "scope" when ReportInputs::scope is set.
nlohmann::json summary_json(const ReportInputs& in, const Report& r);

}  // namespace finverse::report
