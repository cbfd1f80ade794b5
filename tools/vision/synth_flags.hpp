// fin-synth's flags (the virtual experiment, DESIGN.md sections 1 and 5.5): the prescribed
// kinematics, the cameras and sensor, the appearance of realistic footage (--footage and each
// effect on its own) and the motion source with its files; the --footage realistic preset and the
// checks of flags that only go with others. The defaults are the seed paper's trout (section 4.4)
// on the backlit tank.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "vision/fish_body.hpp"
#include "vision/footage_effects.hpp"
#include "vision/kinematic_model.hpp"
#include "vision/renderer.hpp"

namespace finverse::vision {

struct SynthFlags {
  KinematicParams kin;
  RenderOptions ren;
  std::filesystem::path out_dir, cameras_in;
  double fps = 500, periods = 1, exposure = 0.5;
  int width = 512, height = 512, blur_samples = 1, subdivisions = 4;
  std::uint64_t seed = 1;
  bool vtk = true;
  std::vector<std::string> views{"side", "back", "ventral"};
  double half_field = 1.1, field_centre = 0.5;  // default rig (chords)
  // Appearance (issue 35, item 8).
  std::string footage = "clean";  // clean, realistic
  bool body = false;
  FishBodyOptions body_options;
  std::vector<double> pectoral_open{10, 80};  // closed, open (degrees from the flank)
  DebrisOptions debris;
  int jpeg_quality = 0;
  bool video = false;
  // Motion source: prescribed, fsi or fem (a fin-fem response standing where fsi.h5 would).
  std::string motion_source = "prescribed";
  std::filesystem::path fsi_file, fem_file, fsi_mesh, materials_file, drive_file;
  double max_fsi_distance = 0.05;

  bool from_fem() const { return motion_source == "fem"; }
  bool from_fsi() const { return motion_source == "fsi" || from_fem(); }
};

// Adds fin-synth's flags (after the template's) to `app`, bound to `flags`.
void add_synth_flags(CLI::App& app, SynthFlags& flags);

// Applies the --footage realistic preset to every appearance flag the user did not give and
// returns the appearance as rendered (logged and recorded in truth.h5's provenance).
nlohmann::json apply_appearance_flags(const CLI::App& app, SynthFlags& flags);

// Throws finverse::Error naming the flag for a --jpeg-quality out of range, body flags without
// --body, or default-rig flags with --cameras.
void check_appearance_flags(const CLI::App& app, const SynthFlags& flags);

// Throws finverse::Error naming the flag for flags of the other motion source, or a file the
// FSI (fem) source needs and did not get.
void check_motion_flags(const CLI::App& app, const SynthFlags& flags);

}  // namespace finverse::vision
