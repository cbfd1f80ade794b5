// A case-file body's `motion:` section (data/cases/cfd/README.md, "Moving bodies"): a prescribed
// rigid motion (prescribed_rigid_motion.hpp) as harmonics, a constant rate, or a table of poses.
//   motion:
//     pivot: [0.25, 0, 0]                       # rotations are about axes through it (it moves along)
//     translation:
//       x: {rate: -1}                           # towing at 1 m/s towards -x
//       y: {harmonics: [{amplitude: 0.44, frequency: 0.5, phase: 90}]}   # phase in degrees
//     rotation:                                 # applied in this order; angles in degrees
//       - {axis: [0, 0, 1], offset: 10, harmonics: [{amplitude: 20, frequency: 0.5}]}
//     table: poses.csv                          # or: a table (header t and any of x y z angle1 ...)
//     period: 2                                 # optional: the table is periodic with this period [s]
// With a table, the translations and angles come from its columns (x, y, z; angle1 .. angleN, or
// angle for the one rotation), and rotation: gives only the axes. A plane flow's body gives a
// two-component pivot and rotates about z.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>

#include "cfd/cases/case_reader.hpp"
#include "cfd/immersed/prescribed_rigid_motion.hpp"

namespace finverse::cfd::cases {

// Throws finverse::Error naming the file, the key and its line (or the table file and its line).
PrescribedRigidMotion motion_section(const Reader& r, const YAML::Node& n, const std::string& at, int dim);

}  // namespace finverse::cfd::cases
