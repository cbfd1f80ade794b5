// fin-synth's truth motion and its records in truth.h5 (see synth_motion.hpp).
#include "vision/synth_motion.hpp"

#include <cmath>
#include <fstream>
#include <set>
#include <string>

#include "core/error.hpp"
#include "core/flow_scales.hpp"
#include "core/hdf5_file.hpp"
#include "core/log.hpp"
#include "fem/io/material_spec.hpp"
#include "fem/io/root_drive_file.hpp"

namespace fs = std::filesystem;

namespace finverse::vision {

namespace {

// The root drive file of the FSI (fem/io/root_drive_file.hpp, read as fin-fsi fin reads it) onto
// the prescribed model's parameters: the same heave and U/W root pitch profiles.
struct Drive {
  KinematicParams kin;
  double frequency_hz = 0;  // the drive's f, Hz (0: prescribed)
  nlohmann::json json;
};
Drive read_drive(const fs::path& path, KinematicParams kin, double chord) {
  const auto spec = fem::io::read_root_drive(path);
  kin.heave_over_chord = spec.heave_over_chord;
  kin.pitch_center_deg = spec.pitch.center_deg;
  kin.pitch_edge_deg = spec.pitch.edge_deg;
  kin.pitch_phase_deg = spec.pitch.phase_deg;
  kin.pitch_phase_w_deg = spec.pitch.phase_w_deg;
  kin.strouhal = spec.strouhal;
  kin.excursion_over_chord = spec.excursion_over_chord;
  const double speed = free_stream_speed(kin.reynolds, chord, kin.kinematic_viscosity);
  return {kin, spec.frequency(speed, chord), spec.to_json()};
}

// Every ray's E, the membrane's E and nu (the names fin-fit uses), the rays' nu and the densities.
void record_materials(const fs::path& path, const std::vector<int>& ray_ids, stage::Truth& truth) {
  const auto spec = fem::io::read_material_spec(path);
  auto add = [&](const std::string& name, const std::string& unit, double value) {
    truth.material_names.push_back(name);
    truth.material_units.push_back(unit);
    truth.material_values.data.push_back(value);
  };
  truth.material_values = NdArray<double>({0});
  add("E_membrane", "Pa", spec.membrane.youngs_modulus);
  for (int id : ray_ids) add("E_ray" + std::to_string(id), "Pa", spec.ray_material(id).youngs_modulus);
  add("nu", "1", spec.membrane.poisson_ratio);
  add("nu_rays", "1", spec.rays.poisson_ratio);
  add("density_membrane", "kg m-3", spec.membrane.density);
  add("density_rays", "kg m-3", spec.rays.density);
  truth.material_values.shape = {truth.material_values.data.size()};
}

// Root heave and per-ray root pitch (U-shaped amplitude, W-shaped phase) of the rays, eta linear
// in the ray's rank from +1 (first id, dorsal) to -1.
void record_root(const PrescribedKinematics& model, double heave_m, const std::vector<int>& ray_ids,
                 stage::Truth& truth) {
  const std::size_t n = ray_ids.size();
  truth.root_ray_ids = NdArray<std::int32_t>({n});
  truth.root_eta = truth.root_heave_amplitude = truth.root_heave_phase = NdArray<double>({n}, 0.0);
  truth.root_pitch_amplitude = truth.root_pitch_phase = NdArray<double>({n}, 0.0);
  for (std::size_t r = 0; r < n; ++r) {
    const double eta = n > 1 ? 1.0 - 2.0 * r / (n - 1.0) : 0.0;
    truth.root_ray_ids(r) = ray_ids[r];
    truth.root_eta(r) = eta;
    truth.root_heave_amplitude(r) = heave_m;
    truth.root_pitch_amplitude(r) = model.pitch_amplitude(eta);
    truth.root_pitch_phase(r) = model.pitch_phase(eta);
  }
}

}  // namespace

SynthMotion make_synth_motion(const SynthFlags& flags, const mesh::FinTemplate& fin, const FinSurface& surface) {
  const bool from_fem = flags.from_fem(), from_fsi = flags.from_fsi();
  const auto drive = from_fsi ? read_drive(flags.drive_file, flags.kin, fin.chord) : Drive{flags.kin, 0, {}};
  SynthMotion motion{drive.kin, drive.frequency_hz, drive.json, PrescribedKinematics(drive.kin), std::nullopt, {}};
  if (from_fsi) {
    const auto& file = from_fem ? flags.fem_file : flags.fsi_file;
    motion.fsi.emplace(from_fem ? read_fem_motion(file, flags.fsi_mesh, surface, flags.max_fsi_distance)
                                : read_fsi_motion(file, flags.fsi_mesh, surface, flags.max_fsi_distance));
    const auto m = stage::read<stage::Mesh>(flags.fsi_mesh);
    const std::set<int> ids(m.beam_ray.data.begin(), m.beam_ray.data.end());
    motion.ray_ids.assign(ids.begin(), ids.end());
    // The drive's frequency and the FSI's period must agree: the truth's T is the drive's.
    const double f = drive.frequency_hz;
    if (std::abs(motion.fsi->period() * f - 1) > 1e-6)
      throw Error(file.string() + ": T = " + std::to_string(motion.fsi->period()) + " s, but " +
                  flags.drive_file.string() + " drives at f = " + std::to_string(f) + " Hz (Re " +
                  std::to_string(flags.kin.reynolds) + ", chord " + std::to_string(fin.chord) +
                  " m): not the FSI of this drive");
    log::info("FSI motion: " + motion.fsi->parameters().dump());
  } else {
    for (std::size_t r = 1; r <= fin.ray_count(); ++r) motion.ray_ids.push_back(static_cast<int>(r));
  }
  return motion;
}

void record_synth_motion(const SynthFlags& flags, const SynthMotion& motion, double chord, stage::Truth& truth) {
  const bool from_fsi = flags.from_fsi();
  const auto& source = motion.source();
  // The prescribed motion has no materials: the lists are present and empty (np = 0).
  truth.material_values = NdArray<double>({0});
  if (from_fsi) record_materials(flags.materials_file, motion.ray_ids, truth);
  record_root(motion.model, motion.kin.heave_over_chord * chord, motion.ray_ids, truth);
  truth.period = source.period();
  truth.motion_source = source.name();
  if (from_fsi) truth.root_drive = motion.drive.dump();
  auto effects = source.effects();
  if (from_fsi) {
    // Effects beyond elastic rays and membrane that the materials file gives the FSI.
    std::ifstream in(flags.materials_file);
    const auto j = nlohmann::json::parse(in);
    for (const char* key : {"distal", "modulation", "rayleigh", "shell_region"})
      if (j.contains(key)) effects[key] = j[key];
    // The candidate effects the FSI structure ran with (config truth.effects, fin-fsi --effects).
    if (const auto planted =
            h5::File::open_read(flags.from_fem() ? flags.fem_file : flags.fsi_file).attr_string(".", "effects"))
      effects["structural"] = nlohmann::json::parse(*planted);
  }
  truth.effects = effects.dump();
}

}  // namespace finverse::vision
