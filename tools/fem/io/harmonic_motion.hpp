// A tracked motion through its first harmonics of the beat (issue 45, deliverable 1): every
// node's coordinates replaced, at the same frames, by their least-squares fit
// x(t) = m + sum_{h=1..H} (s_h sin h w t + c_h cos h w t), w = 2 pi f. The model's root drive is
// read off the reconstruction's root nodes and the rays' tangents next to them, a derivative of
// tracked positions that amplifies the tracking's frame-to-frame noise; through H harmonics the
// drive keeps the beat and loses that noise (docs/studies/loop_virtual_fish.md, session 40).
#pragma once

#include "core/stage_files.hpp"

namespace finverse::fem::io {

// Throws InvalidInput (naming `source`) for f <= 0, H < 1, or fewer than 2 H + 1 frames; the
// velocities, if any, are dropped (they would no longer match).
stage::Motion harmonic_motion(const stage::Motion& motion, double frequency, int harmonics, const std::string& source);

}  // namespace finverse::fem::io
