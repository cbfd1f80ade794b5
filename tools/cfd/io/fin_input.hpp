// fin-cfd's inputs (DESIGN.md sections 4 and 5.1): mesh.h5 and motion.h5, read through their
// contracts (core/stage_files.hpp) and checked for consistency with each other, turned into the
// moving closed thin body of the 3-D immersed boundary (fin_surface_motion.hpp).
//
// Checks beyond the contracts, each a one-line finverse::Error naming the file and dataset:
// motion nodes = mesh nodes; at least 2 frames with strictly increasing times; mid-surface
// triangles index existing nodes; /ibm/source_node indices valid and /ibm/offset_sign in
// {-1, 0, +1}; /ibm/triangles closed and consistently oriented (every edge in exactly two
// triangles traversing it in opposite directions); /ibm/points is the rest mid-surface offset by
// offset_sign (ibm_thickness / 2) along its normal (which fixes the side convention, normal_sign);
// for periodic data whose last frame repeats the first, that it does.
// motion.h5 /velocity, when present, is not used: the body's velocity and acceleration are the
// time derivatives of the spline through /points (time_spline.hpp), consistent with its positions.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cfd/immersed/fin_surface_motion.hpp"
#include "core/stage_files.hpp"

namespace finverse::cfd::io {

struct FinInput {
  std::vector<Vec3> rest;                          // mid-surface nodes at rest (mesh.h5 /points)
  std::vector<std::array<int, 3>> mid_triangles;   // shell triangles
  std::shared_ptr<const FinSurfaceMotion> motion;  // the moving thin body
  PeriodicLayout layout;                           // how motion.h5 wraps (periodic or not)
  std::optional<double> period;                    // motion.h5 attribute T
  std::optional<double> chord;                     // mesh.h5 attribute chord
  double reference_area = 0;                       // mid-surface area at rest [m^2]
  double rest_mismatch = 0;                        // largest |placed rest vertex - /ibm/points| [m]
  std::vector<double> frame_time;                  // motion.h5 /time
};

// From the stage structs (`mesh_name`, `motion_name` name them in messages). motion_harmonics > 0:
// a periodic motion is kept to its first K harmonics before the spline (periodic_low_pass.hpp;
// the tracked motion's frame-rate noise is acceleration the sheet feels as force); throws for a
// non-periodic motion.
FinInput make_fin_input(const stage::Mesh& mesh, const stage::Motion& motion, const std::string& mesh_name,
                        const std::string& motion_name, int motion_harmonics = 0);
// Reads and checks both files.
FinInput read_fin_input(const std::filesystem::path& mesh, const std::filesystem::path& motion,
                        int motion_harmonics = 0);

// The closed thin body of mesh.h5 /ibm (connectivity, sources, signs, thickness, side convention),
// validated; `rest_mismatch` receives the largest distance of a placed rest vertex from /ibm/points.
ThinBody thin_body_from_mesh(const stage::Mesh& mesh, const std::string& mesh_name, double* rest_mismatch = nullptr);

}  // namespace finverse::cfd::io
