// DFG 2D-2 and 2D-3 wall time against OpenFOAM at equal accuracy (issue 4; fin-cfd-bench --dfg,
// --openfoam, --dfg2d3, --openfoam2d3): the cheapest finverse run (fin-cfd dfg_2d2 / dfg_2d3
// summaries) whose compared quantities are all within 1% of the reference, against the cheapest such
// OpenFOAM run (tools/scripts/openfoam_dfg.py), both measured on the same cores. A side with no
// accurate run offers its most accurate one, and the ratio is then not graded. Peer runs of one mesh
// at two time steps give the peer's own time-step error, the change of its CL_max.
// The meshes and steps: docs/studies/dfg_2d2_lift_maximum.md.
#pragma once

#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/summary.hpp"

namespace finverse::cfd::validation {

// One run of either code on a DFG case: its wall time and whether every compared quantity is
// within 1%.
struct DfgRun {
  std::string label;
  double wall_s = 0;
  double worst_error = 0;  // largest relative error to the reference over the case's quantities
  bool accurate = false;
  double cl_max = std::numeric_limits<double>::quiet_NaN();  // the largest lift
  // OpenFOAM: the mesh, the time step's Courant number and the PIMPLE outer iterations per step.
  int cells_per_quarter = 0;
  double courant = 0;
  int outer_correctors = 1;
};

// What one DFG comparison reads and writes: the fin-cfd summary's name, openfoam_dfg.py's case, the
// metric prefix, the flags named in errors, the compared quantities and whether the ratio is graded.
struct DfgCase {
  std::string summary_name, peer_case, prefix, flag, peer_flag;
  std::vector<std::string> quantities;
  bool graded = false;
};

// 2D-2 against the 1996 bound midpoints (CD_max, CL_max, St; graded).
const DfgCase& dfg_2d2_case();
// 2D-3 against John (2004) (CD_max, CL_max; reported: issue 4 sets its goal on 2D-2).
const DfgCase& dfg_2d3_case();

// A fin-cfd summary (full variant: the coarse one grades nothing) and an openfoam_dfg.py file (one
// run per mesh and time step); one-line finverse::Error naming the flag and file on bad input.
DfgRun read_finverse_dfg_run(const std::string& path, const DfgCase& c);
std::vector<DfgRun> read_openfoam_dfg_runs(const std::string& path, const DfgCase& c);

// The cheapest accurate run, or else the most accurate one (runs not empty).
const DfgRun& pick_dfg_run(const std::vector<DfgRun>& runs);

struct DfgComparison {
  nlohmann::json parameters;  // the summary's parameters block of the comparison
  std::string line;           // one line for the log; empty when nothing was measured
};

// Reads both sides' files (none of either: "not measured"; one side only: an error), adds the
// comparison's metrics (prefix_...) to `summary` and returns its parameters and log line.
DfgComparison compare_dfg_with_openfoam(Summary& summary, const std::vector<std::string>& ours_paths,
                                        const std::vector<std::string>& peer_paths, const DfgCase& c);

}  // namespace finverse::cfd::validation
