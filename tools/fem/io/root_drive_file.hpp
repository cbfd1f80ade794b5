// The root drive file of a fin FSI run (fin-fsi fin --root-drive drive.json; fin-synth's truth):
// the parameters of fem/root_drive.hpp, as the seed paper gives them (section 4.4, Fig. 12):
//
//   {"heave_over_chord": 0.44,      // root heave half amplitude h0 / c
//    "pitch_center_deg": 12, "pitch_edge_deg": 22,       // U-shaped pitch amplitude
//    "pitch_phase_deg": -90, "pitch_phase_w_deg": -20,   // W-shaped phase, relative to the heave
//    "strouhal": 0.44, "excursion_over_chord": 1.0,      // f = St U / (A c)
//    "frequency_hz": 0,             // optional: > 0 overrides St
//    "ramp_periods": 1}             // smooth start over this many periods
// Every key is optional (the defaults above: the paper's trout); unknown keys and values out of
// range are refused with one line naming the file and the key.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/root_pitch_profile.hpp"
#include "core/stage_files.hpp"
#include "fem/root_drive.hpp"

namespace finverse::fem::io {

struct RootDriveSpec {
  double heave_over_chord = 0.44;
  RootPitchProfile pitch;
  double strouhal = 0.44, excursion_over_chord = 1.0;
  double frequency_hz = 0;  // > 0: overrides St
  double ramp_periods = 1;

  // f [Hz]: frequency_hz, else St U / (A c).
  [[nodiscard]] double frequency(double speed, double chord) const;
  [[nodiscard]] nlohmann::json to_json() const;
};

RootDriveSpec parse_root_drive(const nlohmann::json& j, const std::string& source);
RootDriveSpec read_root_drive(const std::filesystem::path& path);

// The drive on a fin mesh: the root nodes of mesh.h5, the rays' roots (a root node that a ray's
// beam leaves), eta from the rays' order along the root (dorsal, +z, first: +1 .. -1), the
// heave h0 = heave_over_chord c. Throws InvalidInput naming `source` when the mesh has no rays
// at its root.
RootDrive make_root_drive(const stage::Mesh& mesh, const RootDriveSpec& spec, double frequency, double chord,
                          const std::string& source);

}  // namespace finverse::fem::io
