// fin-synth's flags, the --footage preset and the flag checks (see synth_flags.hpp).
#include "vision/synth_flags.hpp"

#include <algorithm>

#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/machine_memory.hpp"

namespace finverse::vision {

void add_synth_flags(CLI::App& app, SynthFlags& f) {
  app.add_option("--out-dir", f.out_dir, "output directory (truth.h5, cameras.yml, frames/)")->required();
  app.add_option("--reynolds", f.kin.reynolds, "Re = U c / nu")->capture_default_str();
  app.add_option("--strouhal", f.kin.strouhal, "St = f A / U, A the trailing edge's peak-to-peak excursion")
      ->capture_default_str();
  app.add_option("--viscosity", f.kin.kinematic_viscosity, "kinematic viscosity nu (m^2/s)")->capture_default_str();
  app.add_option("--heave-over-chord", f.kin.heave_over_chord, "root heave half amplitude h0 / c")
      ->capture_default_str();
  app.add_option("--excursion-over-chord", f.kin.excursion_over_chord,
                 "trailing-edge peak-to-peak excursion A / c that St refers to (sets f = St U / A)")
      ->capture_default_str();
  app.add_option("--pitch-center-deg", f.kin.pitch_center_deg, "root pitch amplitude of the middle ray")
      ->capture_default_str();
  app.add_option("--pitch-edge-deg", f.kin.pitch_edge_deg, "root pitch amplitude of the edge rays")
      ->capture_default_str();
  app.add_option("--pitch-phase-deg", f.kin.pitch_phase_deg, "mean root pitch phase relative to heave (< 0: lags)")
      ->capture_default_str();
  app.add_option("--pitch-phase-w-deg", f.kin.pitch_phase_w_deg, "half swing of the W-shaped pitch phase")
      ->capture_default_str();
  app.add_option("--chordwise-over-chord", f.kin.chordwise_over_chord, "chordwise bending wave tip amplitude / c")
      ->capture_default_str();
  app.add_option("--chordwise-wavelength", f.kin.chordwise_wavelength, "chordwise bending wavelength (ray lengths)")
      ->capture_default_str();
  app.add_option("--chordwise-phase-deg", f.kin.chordwise_phase_deg,
                 "chordwise bending phase at the root relative to heave")
      ->capture_default_str();
  app.add_option("--spanwise-over-chord", f.kin.spanwise_over_chord, "spanwise cupping amplitude / c")
      ->capture_default_str();
  app.add_option("--spanwise-phase-deg", f.kin.spanwise_phase_deg, "spanwise cupping phase relative to heave")
      ->capture_default_str();
  app.add_option("--fps", f.fps, "camera frame rate (1/s)")->capture_default_str()->check(finverse::cli::positive());
  app.add_option("--periods", f.periods, "flapping periods to record")
      ->capture_default_str()
      ->check(finverse::cli::positive());
  app.add_option("--views", f.views, "camera views (side, back, ventral, dorsal)")
      ->delimiter(',')
      ->capture_default_str();
  app.add_option("--cameras", f.cameras_in, "use this cameras.yml instead of the default rig")
      ->check(CLI::ExistingFile);
  app.add_option("--field-chords", f.half_field, "default rig: half the field of view around the aim point (chords)")
      ->capture_default_str();
  app.add_option("--field-centre", f.field_centre,
                 "default rig: x of the cameras' aim point (chords; the fin's root at 0)")
      ->capture_default_str();
  app.add_option("--width", f.width, "image width (px)")->capture_default_str();
  app.add_option("--height", f.height, "image height (px)")->capture_default_str();
  app.add_option("--supersample", f.ren.supersample, "anti-aliasing samples per pixel per axis")->capture_default_str();
  app.add_option("--blur-samples", f.blur_samples, "motion-blur sub-frames per frame (1: no blur)")
      ->capture_default_str()
      ->check(finverse::cli::positive());
  app.add_option("--exposure", f.exposure, "shutter open time / frame interval (motion blur)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--noise-sigma", f.ren.noise_sigma, "sensor noise (8-bit levels, 0 = none)")->capture_default_str();
  app.add_option("--seed", f.seed, "seed of the sensor noise and the debris")->capture_default_str();
  // Realistic footage (issue 35, item 8): each effect on its own, or all of them with --footage.
  app.add_option("--footage", f.footage,
                 "appearance: clean (the backlit tank) or realistic (body, --vignetting 0.55 --vignetting-power 4 "
                 "--background-gradient 0.2 --gain 1.25 --debris 40 --jpeg-quality 75); the flags below override it")
      ->check(CLI::IsMember({"clean", "realistic"}))
      ->capture_default_str();
  app.add_flag("--body,!--no-body", f.body, "draw the fish's opaque body and peduncle, moving with the fin's root");
  app.add_option("--body-length", f.body_options.length, "body: snout to peduncle (chords)")->capture_default_str();
  app.add_option("--body-depth", f.body_options.max_depth, "body: largest dorsal-ventral depth (chords)")
      ->capture_default_str();
  app.add_option("--body-width", f.body_options.max_width, "body: largest lateral width (chords)")
      ->capture_default_str();
  app.add_option("--body-level", f.body_options.level, "body: grey level when lit (0..1)")->capture_default_str();
  app.add_option("--body-head-motion", f.body_options.head_motion,
                 "body: the snout's lateral excursion over the peduncle's (0..1)")
      ->capture_default_str();
  app.add_option("--pectoral-length", f.body_options.pectoral_length,
                 "body: pectoral fin length (chords; 0: none), fans in the mid-depth plane that open and close")
      ->capture_default_str();
  app.add_option("--pectoral-station", f.body_options.pectoral_station,
                 "body: the pectoral fins' hinge, as a fraction of the body's length from the snout")
      ->capture_default_str();
  app.add_option("--pectoral-open", f.pectoral_open,
                 "body: the pectoral fins' rays from the flank, closed,open (degrees); left and right in turn")
      ->delimiter(',')
      ->expected(2)
      ->capture_default_str();
  app.add_option("--pectoral-frequency", f.body_options.pectoral_frequency,
                 "body: pectoral opening cycles per second (default: the tail beat's)");
  app.add_option("--pectoral-level", f.body_options.pectoral_level, "body: grey level of a lit pectoral fin (0..1)")
      ->capture_default_str();
  app.add_option("--background-level", f.ren.background, "backlight at the image centre (fraction of full scale)")
      ->capture_default_str();
  app.add_option("--vignetting", f.ren.vignetting, "fraction the backlight falls to the image corners")
      ->capture_default_str();
  app.add_option("--vignetting-power", f.ren.vignetting_power, "falloff exponent of the vignetting in the radius")
      ->capture_default_str();
  app.add_option("--background-gradient", f.ren.background_gradient,
                 "fraction the backlight falls from the right to the left edge")
      ->capture_default_str();
  app.add_option("--gain", f.ren.gain, "sensor gain (> 1: the bright background clips at 255)")->capture_default_str();
  app.add_option("--debris", f.debris.count, "debris specks per view (a third still, the rest drifting)")
      ->capture_default_str();
  app.add_option("--debris-radius", f.debris.max_radius_px, "largest debris speck radius (px)")->capture_default_str();
  app.add_option("--debris-drift", f.debris.drift_px_per_s, "fastest debris drift (px/s)")->capture_default_str();
  app.add_option("--jpeg-quality", f.jpeg_quality,
                 "JPEG-compress every frame at this quality, as MJPG video does (0: none)")
      ->capture_default_str();
  app.add_flag(
      "--video", f.video,
      "write frames/<view>.avi (MJPG at --jpeg-quality, 75 when 0) instead of PNG folders, as a lab's camera records");
  app.add_option("--surface-subdivisions", f.subdivisions, "truth surface columns per gap between rays (even)")
      ->capture_default_str();
  app.add_option("--vtk", f.vtk, "also write truth.pvd for ParaView")->capture_default_str();
  app.add_option("--motion-source", f.motion_source, "what moves the truth fin: prescribed kinematics or the fin FSI")
      ->check(CLI::IsMember({"prescribed", "fsi", "fem"}))
      ->capture_default_str();
  app.add_option("--fsi", f.fsi_file, "fsi: fsi.h5 of fin-fsi fin (the truth motion)")->check(CLI::ExistingFile);
  app.add_option("--fem", f.fem_file, "fem: fin-fem run's motion.h5 (with T; the truth motion)")
      ->check(CLI::ExistingFile);
  app.add_option("--fsi-mesh", f.fsi_mesh, "fsi, fem: the mesh.h5 the FSI (or fin-fem run) ran on")
      ->check(CLI::ExistingFile);
  app.add_option("--materials", f.materials_file, "fsi: the materials file the FSI ran with (recorded in truth.h5)")
      ->check(CLI::ExistingFile);
  app.add_option("--root-drive", f.drive_file, "fsi: the root drive file the FSI ran with (recorded in truth.h5)")
      ->check(CLI::ExistingFile);
  app.add_option("--max-fsi-distance", f.max_fsi_distance,
                 "fsi: largest allowed distance of the truth surface from the FSI mesh's rest mid-surface / c")
      ->capture_default_str();
}

// The realistic preset of --footage (docs/studies/realistic_footage.md): every appearance flag the
// user did not give takes its value here.
nlohmann::json apply_appearance_flags(const CLI::App& app, SynthFlags& f) {
  auto& ren = f.ren;
  auto& debris = f.debris;
  if (f.pectoral_open.size() == 2) {  // else refused by check_appearance_flags
    f.body_options.pectoral_open_min = f.pectoral_open[0];
    f.body_options.pectoral_open_max = f.pectoral_open[1];
  }
  if (f.footage == "realistic") {
    auto unset = [&](const char* flag) { return app.count(flag) == 0; };
    if (unset("--body")) f.body = true;
    if (unset("--vignetting")) ren.vignetting = 0.55;
    if (unset("--vignetting-power")) ren.vignetting_power = 4;
    if (unset("--background-gradient")) ren.background_gradient = 0.2;
    if (unset("--gain")) ren.gain = 1.25;
    if (unset("--debris")) debris.count = 40;
    if (unset("--jpeg-quality")) f.jpeg_quality = 75;
  }
  // The flags' echo shows their defaults where the preset set them: this is what is rendered.
  nlohmann::json appearance = {{"body", f.body},
                               {"background_level", ren.background},
                               {"vignetting", ren.vignetting},
                               {"vignetting_power", ren.vignetting_power},
                               {"background_gradient", ren.background_gradient},
                               {"gain", ren.gain},
                               {"noise_sigma", ren.noise_sigma},
                               {"debris", debris.count},
                               {"debris_radius_px", debris.max_radius_px},
                               {"debris_drift_px_per_s", debris.drift_px_per_s},
                               {"jpeg_quality", f.jpeg_quality},
                               {"video", f.video}};
  const auto& b = f.body_options;
  if (f.body)
    appearance["body_options"] = {{"length", b.length},
                                  {"max_depth", b.max_depth},
                                  {"max_width", b.max_width},
                                  {"level", b.level},
                                  {"head_motion", b.head_motion}};
  if (f.body && b.pectoral_length > 0)
    appearance["body_options"]["pectoral"] = {{"length", b.pectoral_length},
                                              {"station", b.pectoral_station},
                                              {"open_deg", {b.pectoral_open_min, b.pectoral_open_max}},
                                              {"frequency_hz", b.pectoral_frequency},
                                              {"level", b.pectoral_level}};
  return appearance;
}

void check_appearance_flags(const CLI::App& app, const SynthFlags& f) {
  // A view's image: about 16 bytes per anti-aliasing sample (colour, depth) and 8 per pixel (the
  // frame and its encoding), one per view at a time, and the threads' own copies.
  const double pixels = static_cast<double>(f.width) * static_cast<double>(f.height);
  const double samples = pixels * f.ren.supersample * f.ren.supersample;
  require_memory((16 * samples + 8 * pixels) * std::max<std::size_t>(f.views.size(), 2),
                 "--width " + std::to_string(f.width) + " --height " + std::to_string(f.height) + " --supersample " +
                     std::to_string(f.ren.supersample));
  if (f.jpeg_quality < 0 || f.jpeg_quality > 100) throw Error("--jpeg-quality: expected 1..100 (0: no compression)");
  for (const char* flag :
       {"--body-length", "--body-depth", "--body-width", "--body-level", "--body-head-motion", "--pectoral-length",
        "--pectoral-station", "--pectoral-open", "--pectoral-frequency", "--pectoral-level"})
    if (!f.body && app.count(flag) > 0) throw Error(std::string(flag) + ": only with --body (or --footage realistic)");
  for (const char* flag : {"--pectoral-station", "--pectoral-open", "--pectoral-frequency", "--pectoral-level"})
    if (!(f.body_options.pectoral_length > 0) && app.count(flag) > 0)
      throw Error(std::string(flag) + ": only with --pectoral-length > 0");
  if (f.pectoral_open.size() != 2 ||
      !(f.pectoral_open[0] >= 0 && f.pectoral_open[0] < f.pectoral_open[1] && f.pectoral_open[1] <= 120))
    throw Error("--pectoral-open: expected closed,open degrees with 0 <= closed < open <= 120");
  for (const char* flag : {"--field-chords", "--field-centre"})
    if (!f.cameras_in.empty() && app.count(flag) > 0)
      throw Error(std::string(flag) + ": only for the default rig, not with --cameras");
}

void check_motion_flags(const CLI::App& app, const SynthFlags& f) {
  const bool from_fem = f.from_fem(), from_fsi = f.from_fsi();
  const std::vector<std::string> prescribed_only{"--heave-over-chord",
                                                 "--pitch-center-deg",
                                                 "--pitch-edge-deg",
                                                 "--pitch-phase-deg",
                                                 "--pitch-phase-w-deg",
                                                 "--chordwise-over-chord",
                                                 "--chordwise-wavelength",
                                                 "--chordwise-phase-deg",
                                                 "--spanwise-over-chord",
                                                 "--spanwise-phase-deg",
                                                 "--strouhal",
                                                 "--excursion-over-chord"};
  const std::vector<std::string> fsi_only{from_fem ? "--fem" : "--fsi", "--fsi-mesh", "--materials", "--root-drive"};
  for (const auto& flag : from_fsi ? prescribed_only : fsi_only)
    if (app.count(flag) > 0)
      throw Error(flag + ": only with --motion-source " + (from_fsi ? "prescribed" : "fsi or fem") +
                  (from_fsi ? " (the truth's root drive is --root-drive's)" : ""));
  if (app.count(from_fem ? "--fsi" : "--fem") > 0)
    throw Error(std::string(from_fem ? "--fsi" : "--fem") + ": not with --motion-source " + f.motion_source);
  for (const auto& flag : fsi_only)
    if (from_fsi && app.count(flag) == 0) throw Error(flag + ": required with --motion-source " + f.motion_source);
}

}  // namespace finverse::vision
