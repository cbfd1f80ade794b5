// A case-file body's `motion:` section: a prescribed rigid motion (prescribed_rigid_motion.hpp)
// whose channels are harmonics, a constant rate, or columns of a pose table (header t and any of
// x y z angle1 ..., optionally periodic). With a table, rotation: gives only the axes; a plane
// flow's body has a two-component pivot and rotates about z. The format with an example:
// data/cases/cfd/README.md, "Moving bodies".
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>

#include "cfd/cases/case_reader.hpp"
#include "cfd/immersed/prescribed_rigid_motion.hpp"

namespace finverse::cfd::cases {

// Throws finverse::Error naming the file, the key and its line (or the table file and its line).
PrescribedRigidMotion motion_section(const Reader& r, const YAML::Node& n, const std::string& at, int dim);

}  // namespace finverse::cfd::cases
