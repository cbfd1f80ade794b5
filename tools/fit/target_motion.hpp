// The target of the fit: node positions x_target(t_k) sampled in time (motion.h5, DESIGN.md
// section 4, or a twin's truth run), from which eq. (1) takes x_target at its sampled frames and
// eq. (2) the increment dx_target = x(t + dt) - x(t). Positions are interpolated linearly in time
// between samples; outside the sampled span there is no target (InvalidInput), since
// extrapolating a measured motion would invent data.
#pragma once

#include <string>
#include <vector>

#include "core/stage_files.hpp"
#include "fem/rotation.hpp"

namespace finverse::fit {

struct TargetMotion {
  std::string source = "target";              // file or dataset named in messages
  std::vector<double> times;                  // strictly increasing
  std::vector<std::vector<fem::Vec3>> positions;  // [frame][node]

  int frame_count() const { return static_cast<int>(times.size()); }
  int node_count() const { return positions.empty() ? 0 : static_cast<int>(positions[0].size()); }
  // times[1] - times[0] (0 for a single frame).
  double frame_spacing() const;
  // Linear interpolation in time; throws InvalidInput naming `source` outside [times.front(),
  // times.back()] (beyond a round-off tolerance of 1e-9 frame spacings).
  std::vector<fem::Vec3> positions_at(double t) const;
  // The frames with t_begin <= t_k <= t_end (e.g. the last period, the window eq. (1) compares).
  // Throws InvalidInput when none is left.
  TargetMotion window(double t_begin, double t_end) const;
};

// Throws InvalidInput naming target.source: no frames, times not finite and increasing, frames
// of unequal node counts, a non-finite position (naming the frame and node).
void check_target(const TargetMotion& target);

// The target from motion.h5 (stage::Motion: /time [nf], /points [nf, nv, 3]). motion_source and
// mesh_source name the files in messages; mesh_nodes is the mesh's node count (a differing count
// throws InvalidInput naming both files).
TargetMotion target_from_motion(const stage::Motion& motion, int mesh_nodes,
                                const std::string& motion_source = "motion.h5",
                                const std::string& mesh_source = "mesh.h5");

}  // namespace finverse::fit
