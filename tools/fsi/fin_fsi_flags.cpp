// `fin-fsi fin`'s coupled-run flags (fin_fsi_flags.hpp).
#include "fsi/fin_fsi_flags.hpp"

#include "core/cli.hpp"

namespace finverse::fsi {

void add_fin_fsi_flags(CLI::App& command, FinFsiOptions& o) {
  command.add_option("--thickness-cells", o.thickness_cells, "closed thin body thickness [cells]")
      ->capture_default_str();
  command
      .add_option("--surface", o.surface,
                  "how the flow sees the fin: closed (closed thin body, ghost cells) or sheet (zero-thickness "
                  "mid-surface, docs/studies/thin_surface.md)")
      ->capture_default_str()
      ->check(CLI::IsMember({"closed", "sheet"}));
  command
      .add_option("--stream-ramp-periods", o.stream_ramp_periods,
                  "the stream starts from rest and ramps up over this many periods (0: impulsive start)")
      ->capture_default_str();
  command.add_option("--kernel", o.flow.kernel, "sheet: regularized delta kernel (roma3, peskin4, smooth3, smooth4)")
      ->capture_default_str()
      ->check(CLI::IsMember({"roma3", "peskin4", "smooth3", "smooth4"}));
  command.add_option("--marker-spacing", o.flow.marker_spacing, "sheet: marker spacing in core cell widths")
      ->capture_default_str()
      ->check(CLI::Range(0.25, 4.0));
  command.add_flag(
      "--band-correction", o.band_correction,
      "sheet: load the structure with the markers' impulses less the kernel band's inertia (off: unstable for a "
      "structure lighter than the band; docs/studies/thin_surface.md)");
  command
      .add_option("--ramp-periods", o.ramp_periods,
                  "--motion: periods of the root's ramp from rest before its first frame")
      ->capture_default_str();
  command.add_option("--ramp-time", o.ramp_time, "--motion: the ramp in seconds instead (0: --ramp-periods)")
      ->capture_default_str();
  command
      .add_option("--motion-harmonics", o.motion_harmonics,
                  "--motion, periodic: drive the root with every node's first K harmonics of the period (the "
                  "tracking's frame-rate noise removed; 0: the frames as given)")
      ->capture_default_str()
      ->check(CLI::Range(0, 1000));
  command.add_option("--acceleration", o.acceleration, "iqn-ils, aitken or constant")->capture_default_str();
  command.add_option("--omega", o.omega, "omega0 (aitken, iqn-ils) or omega (constant)")->capture_default_str();
  command.add_option("--tolerance", o.tolerance, "relative interface displacement residual")->capture_default_str();
  command.add_option("--absolute-tolerance", o.absolute_tolerance, "... or interface displacement change [c]")
      ->capture_default_str();
  command.add_option("--max-iterations", o.max_iterations, "coupling iterations per step")->capture_default_str();
  command.add_flag("--strict", o.strict, "stop at the iteration cap (default: accept the best iterate, counted)");
  command.add_option("--spectral-radius", o.spectral_radius, "structure's generalized-alpha rho_inf")
      ->capture_default_str();
  command.add_option("--structure-tolerance", o.structure_tolerance, "structure Newton residual tolerance")
      ->capture_default_str();
  command
      .add_option("--structure-max-iterations", o.structure_max_iterations, "structure Newton iterations per sub-step")
      ->capture_default_str();
  command.add_option("--substeps", o.substeps, "structure sub-steps per coupling step")->capture_default_str();
  command
      .add_option("--structure-halvings", o.structure_halvings,
                  "a structure sub-step whose Newton solve fails is retried as two halves, up to this many times "
                  "nested (0: the failure ends the run)")
      ->capture_default_str()
      ->check(CLI::Range(0, 10));
  command
      .add_option("--min-frequency-ratio", o.min_frequency_ratio,
                  "refuse materials whose fin's first natural frequency in water is below this many times the "
                  "flapping frequency, before any step (0: run whatever the materials)")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  command.add_flag("--cold-repeats", o.cold_repeats,
                   "every coupling iteration's flow solves start from the step's start, not the last iteration's");
  command.add_option(
      "--checkpoint", o.checkpoint,
      "checkpoint file, replaced atomically (default with --checkpoint-every: <out stem>.checkpoint.h5 beside --out)");
  command.add_option("--checkpoint-every", o.checkpoint_every, "steps between checkpoints (0: after the last only)")
      ->capture_default_str()
      ->check(finverse::cli::non_negative());
  command
      .add_option("--restart", o.restart,
                  "continue from a checkpoint written with the same options (the coupling's and the structure's "
                  "iteration settings and sub-steps may differ)")
      ->check(CLI::ExistingFile);
  command.add_option("--paraview", o.paraview_dir, "ParaView series of the fin and the flow into this folder");
  command.add_option("--paraview-every", o.paraview_every, "every k-th fsi.h5 frame in the ParaView series")
      ->capture_default_str()
      ->check(finverse::cli::positive());
  command.add_option("--rayleigh-mass", o.rayleigh_mass, "structure damping a_M [1/s]; < 0: the materials file's")
      ->capture_default_str();
  command
      .add_option("--rayleigh-stiffness", o.rayleigh_stiffness,
                  "structure damping a_K [s] (damps the membrane's fast modes); < 0: the materials file's")
      ->capture_default_str();
}

}  // namespace finverse::fsi
