// fin-synth's truth motion (DESIGN.md sections 1 and 5.5; issues 33 and 34): the prescribed
// kinematics, or the FSI's fsi.h5 (fem: fin-fem run's motion.h5) bound to the truth surface and
// driven by the root drive file it ran with; and what truth.h5 records of it: the materials, each
// ray's root heave and pitch, the period, the source's name, the drive and the planted effects.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "core/stage_files.hpp"
#include "mesh/fin_template.hpp"
#include "vision/fin_surface.hpp"
#include "vision/fsi_motion_source.hpp"
#include "vision/kinematic_model.hpp"
#include "vision/synth_flags.hpp"

namespace finverse::vision {

struct SynthMotion {
  // The root kinematics: the flags' own, or on fsi and fem the drive file's heave and pitch on
  // the same U/W profiles (the FSI truth's bending is the FSI's, not the model's).
  KinematicParams kin;
  double drive_frequency_hz = 0;  // the drive's f, Hz (0: prescribed)
  nlohmann::json drive;           // the drive file as fin-fsi fin reads it (fsi, fem)
  PrescribedKinematics model;
  std::optional<FsiMotion> fsi;  // fsi, fem
  std::vector<int> ray_ids;      // the mesh's rays (fsi, fem), else 1..n

  const MotionSource& source() const { return fsi ? static_cast<const MotionSource&>(*fsi) : model; }
};

// Reads the drive, the FSI's (fin-fem run's) motion and its mesh for flags.from_fsi(), binding
// `surface` of `fin`. Throws finverse::Error naming the files when the motion's period is not
// the drive's.
SynthMotion make_synth_motion(const SynthFlags& flags, const mesh::FinTemplate& fin, const FinSurface& surface);

// Records the motion in `truth`: materials (fsi, fem: from flags.materials_file; else none),
// root kinematics per ray, T, the source's name, the drive and the effects.
void record_synth_motion(const SynthFlags& flags, const SynthMotion& motion, double chord, stage::Truth& truth);

}  // namespace finverse::vision
