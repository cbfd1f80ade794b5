// A periodic motion (motion.h5 with its period T) repeated to cover a time span. fin-cfd reports
// the loads of its last period, after the start-up ones, while the reconstruction samples one
// period from t = 0: fin-fem run and fin-fit run both repeat the motion to cover the loads' times.
#pragma once

#include "core/stage_files.hpp"

namespace finverse::fem::io {

// The frames of `motion` shifted by whole periods so that [t_begin, t_end] is covered; a frame one
// period after another (the seam) is kept once; velocities are dropped. Throws InvalidInput when
// the motion has no period.
stage::Motion periodic_extension(const stage::Motion& motion, double t_begin, double t_end);

// True when the motion is periodic and [t_begin, t_end] reaches outside its times.
bool needs_periodic_extension(const stage::Motion& motion, double t_begin, double t_end);

}  // namespace finverse::fem::io
