// The fin's coupled flow-structure simulation (issue 33; seed paper sections 2.3 and 4.4; DESIGN.md
// 5.3): the shell + beam fin of mesh.h5 with its materials (fem/io/fin_model.hpp), driven at the
// root either by the analytic drive (heave + per-ray pitch, fem/root_drive.hpp) or by the tracked
// root motion of motion.h5 (per-ray rotation, fem/root_motion.hpp), in a uniform stream. Each
// time step is the implicit coupling of SurfaceFlowStructureStep: the closed thin body around the
// mid-surface (thickness_cells cells thick) in the flow, the triangle forces on the nodes, the
// structure's generalized-alpha step, IQN-ILS (or Aitken) on the nodes' [X; V].
//
// Flow as fin-cfd fin (cfd/io/fin_flow_case.hpp): Re, U, nu, grid flags; the uniform core around
// the swept box of the drive (the rigid fin carried by the root drive, sampled over a period), or
// of motion.h5's frames; inlet / convective outlet / slip sides; the stream impulsive at the start.
// Time: the drive starts at t = 0 from rest with its own cosine ramp; a tracked motion starts one
// ramp (ramp_periods T, or ramp_time) before its first frame, blended from rest to the root's
// first-frame position and velocity (quintic Hermite). A periodic motion (attribute T, whole periods; tiled over the
// run) and the drive run `periods` periods (the ramp included) and write the last `output_periods` at the output
// interval (the motion's frame spacing shortened to divide T, or T / 100 for the drive unless given); a non-periodic
// motion runs to its last frame and writes its frames. The fixed dt is a whole fraction of it with (U + 2 v_max) dt / h
// <= cfl, v_max the drive's fastest node speed. Failures (a coupling that diverges, the cap under strict, the flow's
// CFL guard, a structure that does not converge or turns non-finite) end in one finverse::Error naming the step and the
// last good checkpoint. The run is the coupled run every case uses (coupled_run.hpp): checkpoints, a restart that
// continues bit for bit, and ParaView series.
#pragma once

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "cfd/io/fin_flow_case.hpp"
#include "core/stage_files.hpp"
#include "fem/io/material_spec.hpp"
#include "fem/io/root_drive_file.hpp"
#include "fem/model.hpp"

namespace finverse::fsi {

struct FinFsiOptions {
  cfd::io::FinFlowOptions flow;   // cells_per_chord 0: c / 16; output_interval 0: see above
  double thickness_cells = 2;     // closed thin body thickness [h]
  // How the flow sees the fin: "closed" (the closed thin body, ghost cells) or "sheet" (the
  // mid-surface as a zero-thickness sheet with flow.kernel and flow.marker_spacing;
  // docs/studies/thin_surface.md).
  std::string surface = "closed";
  // > 0: the stream starts from rest and its inflow ramps up as (1 - cos(pi t / ramp)) / 2 over
  // this many periods T (the flow's time 0 must be the run's start); 0: an impulsive start. A
  // sheet's impulsive start loads the fin with the momentum of the fluid in its kernel width
  // (docs/studies/thin_surface.md).
  double stream_ramp_periods = 0;
  // The sheet's load on the structure less the kernel band's inertia (cfd::SheetForcingOptions::
  // band_correction). Off by default: the band is much heavier than the fin's membrane, and
  // removing its inertia explicitly inside the partitioned coupling leaves the structure a negative
  // effective mass (docs/studies/thin_surface.md, "The entrained band").
  bool band_correction = false;
  double ramp_periods = 1;        // tracked motion only (the drive has its own)
  double ramp_time = 0;           // [s]; > 0: the tracked motion's ramp instead of ramp_periods T
  int motion_harmonics = 0;       // tracked periodic motion: > 0 keeps its first K harmonics (0: as given)
  std::string acceleration = "iqn-ils";
  double omega = 0.1;             // first iteration's relaxation
  double tolerance = 1e-3;        // relative interface displacement residual
  double absolute_tolerance = 1e-5;  // ... or |X_out - X_in| below this [c]
  int max_iterations = 15;
  bool strict = false;            // the cap is an error (default: accept the best iterate, counted)
  // generalized-alpha rho_inf and structure sub-steps: 0.8 let the default fin fail at t = 0.06 s,
  // 0.5 at c/10 in the second period; 0 with 2 sub-steps ran through (docs/studies/fin_fsi.md).
  double spectral_radius = 0;
  double structure_tolerance = 1e-7;
  int structure_max_iterations = 40;  // Newton iterations per (sub-)step
  int substeps = 2;                   // structure sub-steps per coupling step
  // A structure sub-step whose Newton solve fails is retried as two halves, up to this many times
  // nested (fem::CoupledStructureOptions::max_halvings; docs/studies/default_case.md).
  int structure_halvings = 3;
  // Every coupling iteration's flow solves start from the step's start (CoupledRunOptions).
  bool cold_repeats = false;
  // Refuse, before any step, materials whose fin's first natural frequency in water is below this
  // many times the flapping frequency (fin_frequency_check.hpp); 0: run whatever the materials.
  double min_frequency_ratio = 0;
  // Rayleigh damping C = a_M M + a_K K of the structure; < 0: the materials file's.
  double rayleigh_mass = -1, rayleigh_stiffness = -1;
  // Checkpoints (coupled_run.hpp): to `checkpoint` every checkpoint_every steps (0: only after the
  // last) and after the last step; `restart` continues from one written with the same options.
  std::filesystem::path checkpoint;
  long checkpoint_every = 0;
  std::filesystem::path restart;
  // ParaView series (fsi_paraview.hpp) of the structure and the flow at every paraview_every-th
  // fsi.h5 frame (empty: none).
  std::filesystem::path paraview_dir;
  long paraview_every = 1;
  std::function<void(const std::string&)> progress;
};

struct FinFsiInputs {
  stage::Mesh mesh;
  std::string mesh_name = "mesh.h5";
  fem::io::MaterialSpec materials;
  std::string materials_name = "materials";  // in error messages
  // The structure, root clamped (empty: fem::io::build_fin_model(mesh, materials)); e.g. fin-fit's
  // model factory with a materials.h5's best values. The root drive replaces the clamp.
  std::function<fem::Model()> build_model;
  std::optional<fem::io::RootDriveSpec> drive;  // exactly one of drive and motion
  std::optional<stage::Motion> motion;
  std::string motion_name = "motion.h5";
  // Candidate effects (fem/effects JSON list; empty: none): the structure runs with them (rest
  // shapes move the mesh and its IBM body first; the beat is the drive's or motion's period) and
  // fsi.h5 records them in its "effects" attribute.
  nlohmann::json effects = nlohmann::json::array();
  std::string effects_name = "effects.json";
};

struct FinFsiResult {
  stage::Fsi fsi;
  // Over every step and over the last period (every step of it).
  double iterations_mean = 0;
  int iterations_max = 0;
  long steps = 0, steps_at_cap = 0;
  double ct_mean = 0, ct_peak = 0, cl_amplitude = 0;  // last period
  double te_peak_to_peak_mean = 0, te_peak_to_peak_min = 0, te_peak_to_peak_max = 0;  // rays' tips, / c
  double transfer_mismatch = 0;
  double wall_seconds = 0, h = 0, dt = 0, period = 0, chord = 0, U = 0, frequency = 0;
  // The structure's first natural frequency in vacuo and in water (fin_frequency_check.hpp) and
  // the latter over the flapping frequency (0 for a motion without a period).
  double first_frequency_vacuum = 0, first_frequency_wet = 0, first_frequency_ratio = 0;
  long cells = 0;
  std::array<long, 3> grid{};
  nlohmann::json config;  // the effective parameters (stored in fsi.h5 and the summary)
  [[nodiscard]] nlohmann::json summary() const;
};

// Throws finverse::Error (bad input, failures as above).
FinFsiResult run_fin_fsi(const FinFsiInputs& in, const FinFsiOptions& options);

}  // namespace finverse::fsi
