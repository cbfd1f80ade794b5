// A periodic motion kept to its first K harmonics (issue 44: the sheet's raw loads follow the
// body's acceleration, docs/studies/thin_surface.md "Goal 4"). Tracked positions carry noise at
// the frame rate, which the spline through the frames turns into an acceleration many times the
// fin's own; a zero-thickness sheet feels it as force. Each channel is replaced at the samples by
// its least-squares fit of the first K harmonics of the period P:
//     q(t_k) <- a_0 + sum_{m=1..K} (a_m cos(m w t_k) + b_m sin(m w t_k)),   w = 2 pi / P
// (for samples tiling whole periods, the truncated discrete Fourier series).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "cfd/immersed/time_spline.hpp"
#include "core/stage_files.hpp"

namespace finverse::cfd {

// values: frames rows of `channels` values (row-major) at time[0..frames-1]; harmonics >= 1 with
// at least 2 (2K + 1) frames. Throws finverse::Error naming `what` otherwise.
std::vector<double> periodic_low_pass(const std::vector<double>& time, const std::vector<double>& values,
                                      std::size_t channels, double period, int harmonics, const std::string& what);

// A motion.h5's points over the frames its periodic layout uses ([layout.frames, nodes, 3],
// row-major), kept to their first K harmonics of attribute T: `--motion-harmonics` of fin-cfd fin
// and fin-fsi fin. Throws finverse::Error naming `what` when the motion is not periodic.
std::vector<double> periodic_low_pass(const stage::Motion& motion, const PeriodicLayout& layout, int harmonics,
                                      const std::string& what);

}  // namespace finverse::cfd
