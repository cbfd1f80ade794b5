// Case files (`fin-cfd run CASE.yaml`): a flow as a parameter file, as CaNS does, so that another
// geometry needs no new C++. YAML, with the key `case` naming what the file describes:
//   - a validation case (`case: dfg_2d2`, ...; tools/cfd/validation/cases.hpp) or the fin's loads
//     (`case: fin`, the flags of fin-cfd fin: mesh, motion, out, reynolds, ...): every other key,
//     at any depth (sections such as grid: or time: only group them), is that case's option
//     (`cells_per_diameter: 24` is --cells-per-diameter 24; true/false switch a flag), and a
//     `coarse:` section holds what the coarse (CI) variant changes (null: the case's own default);
//   - a user's own flow (`case: flow`; flow_case.hpp): domain, grid, fluid, boundaries, bodies,
//     time, solver and outputs sections, documented in data/cases/cfd/README.md; its coarse:
//     section is merged over the file (maps key by key) for the coarse variant.
// Paths in a case file are relative to the file's own folder. Errors name the file, the key and
// its line.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "cfd/cases/flow_case.hpp"

namespace finverse::cfd::cases {

struct CaseFile {
  std::string kind;                    // the validation case's name, or "flow"
  std::vector<std::string> arguments;  // a validation case's flags ("--cells-per-diameter", "24", ...)
  FlowCaseSpec flow;                   // kind == "flow"
};

// `coarse`: apply the file's coarse: section.
CaseFile read_case_file(const std::filesystem::path& file, bool coarse);

}  // namespace finverse::cfd::cases
