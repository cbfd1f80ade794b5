// Nodal forces over time from either kind of load file a structural run or a fit takes: fin-cfd's
// loads.h5 (a flow's loads, with its scales and coefficients) or nodal_loads.h5 (a user's
// structural load case: times and nodal forces only, finverse/nodal_loads in CONTRACTS.md), told
// apart by the file's schema attribute.
#pragma once

#include <filesystem>

#include "core/stage_files.hpp"

namespace finverse::fem::io {

struct NodalForceFile {
  stage::Loads loads;       // time and nodal_force filled in either case
  bool structural = false;  // true: nodal_loads.h5 (no flow)
};

// Throws finverse::Error naming the file (contract violations, unreadable file).
NodalForceFile read_nodal_force_file(const std::filesystem::path& path);

}  // namespace finverse::fem::io
