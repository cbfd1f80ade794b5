// A motion with the reconstruction's error put back in (issue 45, goal 6): isotropic Gaussian
// noise on every node of every frame, sized by the mean vertex error a tracking reaches (fin-track:
// about 0.3 % of the chord). A twin fitted through it shows whether the fit's intervals hold at a
// tracking's accuracy. The noise is independent per node and frame; fin-track's own error is
// smoother than that, so this is the kinder case for the intervals (docs/studies/fit_noise_twin.md).
#pragma once

#include <cstdint>

#include "core/stage_files.hpp"

namespace finverse::fit::io {

// Standard deviation per component of a 3-D isotropic Gaussian whose mean length is `mean_error`
// (E|e| = 2 sigma sqrt(2/pi)).
double sigma_for_mean_error(double mean_error);

// `motion` with N(0, sigma) added to each component of /points; the same seed gives the same
// noise. /velocity, when present, is dropped: a tracked motion's velocity is its positions'.
stage::Motion with_tracking_noise(stage::Motion motion, double sigma, std::uint64_t seed);

}  // namespace finverse::fit::io
