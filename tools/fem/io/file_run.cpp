// Stage files -> structural run -> stage files (see file_run.hpp).
#include "fem/io/file_run.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/log.hpp"
#include "core/stage_files.hpp"
#include "core/stage_identity.hpp"
#include "fem/errors.hpp"
#include "fem/io/fin_layout.hpp"
#include "fem/io/fin_model.hpp"
#include "fem/io/material_spec.hpp"
#include "fem/io/nodal_force_file.hpp"
#include "fem/io/periodic_motion.hpp"
#include "fem/io/root_drive_file.hpp"
#include "fem/io/run_output.hpp"

namespace finverse::fem::io {

FileRunSummary run_from_files(const FileRunOptions& o, const nlohmann::json& config) {
  const stage::Mesh mesh = stage::read<stage::Mesh>(o.mesh);
  const MaterialSpec spec = read_material_spec(o.materials);
  Effects effects;
  if (o.effects) effects = read_effects(*o.effects);
  std::optional<stage::Loads> loads;
  std::optional<stage::Motion> motion;
  // A structural load case needs no flow: nodal_loads.h5 carries only times and nodal forces.
  if (o.loads) loads = read_nodal_force_file(*o.loads).loads;
  if (o.motion) motion = stage::read<stage::Motion>(*o.motion);
  // Stages that disagree (issue 33): the motion or loads of another mesh, loads of another motion.
  if (o.motion) check_made_from(*o.motion, o.mesh);
  if (o.loads) check_made_from(*o.loads, o.mesh);
  if (o.loads && o.motion) check_made_from(*o.loads, *o.motion);
  std::optional<RootDriveSpec> drive_spec;
  double drive_frequency = 0;
  std::vector<double> drive_times;
  if (o.root_drive) {
    if (o.motion) throw InvalidInput("fin-fem run: give --motion or --root-drive, not both");
    drive_spec = read_root_drive(*o.root_drive);
    drive_frequency = drive_spec->frequency_hz;
    if (!(drive_frequency > 0))
      throw InvalidInput(o.root_drive->string() + ": frequency_hz: expected > 0 (a structural run has no flow speed for St)");
    if (!(o.periods > 0) || o.frames_per_period < 2)
      throw InvalidInput("fin-fem run: --periods > 0 and --frames-per-period >= 2 expected");
    const double T = 1 / drive_frequency, t0 = std::max(1.0, std::ceil(drive_spec->ramp_periods - 1e-9)) * T;
    const int n = static_cast<int>(std::lround(o.periods * o.frames_per_period));
    for (int k = 0; k <= n; ++k) drive_times.push_back(t0 + T * k / o.frames_per_period);
  }
  if (!loads && !motion && !drive_spec)
    throw InvalidInput("fin-fem run: give --loads, --motion or --root-drive (they define the output times)");

  if (loads && motion && !loads->time.data.empty() &&
      needs_periodic_extension(*motion, loads->time.data.front(), loads->time.data.back())) {
    *motion = periodic_extension(*motion, loads->time.data.front(), loads->time.data.back());
    log::info(o.motion->string() + ": periodic (T = " + std::to_string(*motion->period) +
              " s), repeated to cover the loads' times");
  }
  const std::vector<double>& times = loads ? loads->time.data : motion ? motion->time.data : drive_times;
  if (loads && motion &&
      (times.front() < motion->time.data.front() - 1e-12 || times.back() > motion->time.data.back() + 1e-12))
    throw InvalidInput(o.loads->string() + ": load times [" + std::to_string(times.front()) + ", " +
                       std::to_string(times.back()) + "] reach outside the motion times of " + o.motion->string());
  double ramp = o.ramp;
  if (drive_spec) ramp = times.front();  // from rest at t = 0, the drive's own smooth start
  if (ramp == 0) ramp = times.size() > 1 ? 10 * (times[1] - times[0]) : 1.0;
  if (!(ramp > 0)) throw InvalidInput("fin-fem run: --ramp must be > 0");

  FinLayout layout;
  stage::Mesh shaped = mesh;  // the rest shape the model is built on (rest-shape effects)
  if (!effects.empty()) {
    layout = make_fin_layout(mesh, o.mesh.string());
    const std::optional<double> T = loads ? loads->period : motion ? motion->period : std::optional<double>(1 / drive_frequency);
    if (drive_spec) layout.beat_frequency = drive_frequency;
    else if (T && *T > 0) layout.beat_frequency = 1.0 / *T;
    else if (motion && motion->period && *motion->period > 0) layout.beat_frequency = 1.0 / *motion->period;
    layout.start_time = times.front() - ramp;
    layout.ramp = ramp;
    reshape_mesh(shaped, effects, layout);
  }
  FinModel fm = build_fin_model(shaped, spec, o.mesh.string());
  if (loads) {
    const double dropped = apply_loads(fm.model, *loads, ramp, o.loads->string());
    if (dropped > 0) {
      std::ostringstream m;
      m << o.loads->string() << ": /nodal_force: forces on the prescribed root nodes go into the support, "
        << "not the structure (largest component " << dropped << " N)";
      log::warn(m.str());
    }
  }
  if (motion) apply_root_motion(fm.model, shaped, *motion, o.root_rotation, ramp, o.motion->string());
  if (drive_spec) {
    const double c = mesh.chord.value_or(0.0);
    if (!(c > 0)) throw InvalidInput(o.mesh.string() + ": attribute chord: expected > 0 (the drive's heave is h0/c times it)");
    make_root_drive(shaped, *drive_spec, drive_frequency, c, o.mesh.string()).apply(fm.model);
  }
  fm.model.set_gravity(Vec3(o.gravity[0], o.gravity[1], o.gravity[2]));
  if (!effects.empty()) {
    apply_effects(fm.model, effects, layout);
    log::info("effects: " + effects_to_json(effects).dump());
  }

  RunOptions run = o.run;
  run.start_time = times.front() - ramp;
  run.dynamic_options.rayleigh_mass = spec.rayleigh_mass;
  run.dynamic_options.rayleigh_stiffness = spec.rayleigh_stiffness;
  if (run.analysis != Analysis::dynamic && (spec.rayleigh_mass != 0 || spec.rayleigh_stiffness != 0))
    log::warn("Rayleigh damping is ignored by the " + std::string(to_string(run.analysis)) + " analysis");

  std::ostringstream head;
  head << to_string(run.analysis) << " run: " << fm.model.node_count() << " nodes, "
       << fm.model.elements().size() << " elements, " << times.size() << " frames from t = " << times.front()
       << " s (ramp " << ramp << " s)";
  log::info(head.str());
  log::Progress progress("fin-fem " + std::string(to_string(run.analysis)), times.size());
  FileRunSummary summary;
  const auto frames = run_structural_analysis(fm.model, run, times, [&](int k, const RunFrame& f) {
    summary.newton_iterations += f.iterations;
    std::ostringstream st;
    st << "t = " << f.time << " s, " << f.iterations << " Newton its";
    progress.update(static_cast<std::size_t>(k + 1), st.str());
  });
  progress.finish();
  summary.frames = static_cast<int>(frames.size());

  std::vector<std::filesystem::path> inputs{o.mesh, o.materials};
  if (o.loads) inputs.push_back(*o.loads);
  if (o.motion) inputs.push_back(*o.motion);
  if (o.root_drive) inputs.push_back(*o.root_drive);
  if (o.effects) inputs.push_back(*o.effects);
  std::optional<double> period = loads ? loads->period : motion ? motion->period : std::optional<double>(1 / drive_frequency);
  std::optional<std::string> recorded;
  if (o.effects) recorded = effects_to_json(effects).dump();
  write_run_output(o.out, o.pvd, mesh, frames, period, Provenance{"fin-fem", config, inputs}, recorded);
  return summary;
}

}  // namespace finverse::fem::io
