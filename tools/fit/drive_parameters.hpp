// The root drive as fit parameters (issue 45, deliverable 1): the coefficients of
// fem/drive_correction.hpp's harmonic correction of the tracked root motion, named
//   drive_pitch_sin<k>, drive_pitch_cos<k>  [rad]  Legendre coefficient k of the pitch over the rays,
//   drive_heave_sin, drive_heave_cos        [m]    the heave along the fin's plane normal,
// all zero at the tracked drive. Bounds: pitch +-0.35 rad (20 deg, about the edge rays' whole
// amplitude in the paper's Fig. 12); heave +-0.25 of the root's length (the paper's trout heaves
// 0.44 c with a root 1.5 c long, so a quarter of the root is half the heave itself). Linear scale,
// so the intervals and the identifiability flags read in radians and metres.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/stage_files.hpp"
#include "fem/drive_correction.hpp"
#include "fit/parameter_space.hpp"

namespace finverse::fit {

struct DriveSlot {
  enum class Kind { pitch_sin, pitch_cos, heave_sin, heave_cos } kind = Kind::pitch_sin;
  int order = 0;  // k (pitch only)
};

// The slot a name stands for; nullopt for a name that is not a drive parameter.
std::optional<DriveSlot> parse_drive_name(const std::string& name);

// The parameter of a drive name with the bounds above (the root's length from mesh's root nodes);
// nullopt for a name that is not a drive parameter.
std::optional<Parameter> drive_parameter(const std::string& name, const stage::Mesh& mesh);

// The family of order K (0: none): the pitch's K sine and K cosine coefficients, then the heave's two.
std::vector<std::string> drive_parameter_names(int order);

// Writes the value of a drive parameter into the correction (its pitch vectors grown as needed).
void set_drive_coefficient(fem::DriveCorrection& c, const DriveSlot& slot, double value);

}  // namespace finverse::fit
