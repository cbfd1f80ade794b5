// fin-synth: the virtual experiment (DESIGN.md sections 1 and 5.5). Builds the truth fin from the
// template, moves it with a motion source and renders every calibrated view. Two sources:
//   prescribed  the reconstructed trout kinematics of the seed paper, section 4.4 (Re = 1000,
//               St = 0.44 on a 1.0 c trailing-edge excursion: f = 4.4 Hz, 500 fps);
//   fsi         the fin's flow-structure simulation (issue 33): fsi.h5 from fin-fsi fin on the
//               mesh.h5 it ran on, with the known materials and root drive it was given, which
//               truth.h5 records (materials/*, root/*, root_drive);
//   fem         a structural response (fin-fem run --root-drive, issue 34's cheap truth): its
//               motion.h5 (--fem) on its mesh, recorded like the FSI's.
//
//   fin-synth --out-dir results/trout_caudal --periods 1 --views side,back,ventral
//   fin-synth --out-dir results/c --motion-source fsi --fsi truth/fsi.h5 --fsi-mesh truth/mesh.h5
//             --materials data/cases/trout_fin_materials.json --root-drive truth/drive.json
//   fin-synth --out-dir results/f --footage realistic        the fish's body, vignetting, gradient,
//             saturation, debris and JPEG compression (vision/fish_body, footage_effects, renderer)
//
// Writes <out-dir>/truth.h5 (stage::Truth), cameras.yml, frames/<view>/NNNNNN.png, template.json
// and truth.pvd (ParaView). Same inputs, seed and threads give byte-identical files.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "core/atomic_file.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/stage_files.hpp"
#include "core/vtk_output.hpp"
#include "core/flow_scales.hpp"
#include "fem/io/material_spec.hpp"
#include "fem/io/root_drive_file.hpp"
#include "mesh/template_options.hpp"
#include "vision/camera.hpp"
#include "vision/fin_surface.hpp"
#include "vision/fish_body.hpp"
#include "vision/footage_effects.hpp"
#include "vision/fsi_motion_source.hpp"
#include "vision/kinematic_model.hpp"
#include "vision/renderer.hpp"

namespace fs = std::filesystem;
using namespace finverse;

namespace {

// The root drive file of the FSI (fem/io/root_drive_file.hpp, read as fin-fsi fin reads it) onto
// the prescribed model's parameters: the same heave and U/W root pitch profiles.
struct Drive {
  vision::KinematicParams kin;
  double frequency_hz = 0;  // the drive's f, Hz (0: prescribed)
  nlohmann::json json;
};
Drive read_drive(const fs::path& path, vision::KinematicParams kin, double chord) {
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
void record_root(const vision::PrescribedKinematics& model, double heave_m, const std::vector<int>& ray_ids,
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

// The realistic preset of --footage (docs/studies/realistic_footage.md): every appearance flag the
// user did not give takes its value here.
void apply_footage_preset(const CLI::App& app, bool& body, vision::RenderOptions& ren, vision::DebrisOptions& debris,
                          int& jpeg_quality) {
  auto unset = [&](const char* flag) { return app.count(flag) == 0; };
  if (unset("--body")) body = true;
  if (unset("--vignetting")) ren.vignetting = 0.55;
  if (unset("--vignetting-power")) ren.vignetting_power = 4;
  if (unset("--background-gradient")) ren.background_gradient = 0.2;
  if (unset("--gain")) ren.gain = 1.25;
  if (unset("--debris")) debris.count = 40;
  if (unset("--jpeg-quality")) jpeg_quality = 75;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fin-synth: simulate the fin's motion and render synchronized camera frames"};
  cli::Standard standard(app, "fin-synth");
  mesh::TemplateOptions tmpl;
  mesh::add_template_options(app, tmpl);
  vision::KinematicParams kin;
  vision::RenderOptions ren;
  fs::path out_dir, cameras_in;
  double fps = 500, periods = 1, exposure = 0.5;
  int width = 512, height = 512, blur_samples = 1, subdivisions = 4;
  std::uint64_t seed = 1;
  bool vtk = true;
  std::string motion_source = "prescribed";
  fs::path fsi_file, fem_file, fsi_mesh, materials_file, drive_file;
  double max_fsi_distance = 0.05;
  std::vector<std::string> views{"side", "back", "ventral"};
  app.add_option("--out-dir", out_dir, "output directory (truth.h5, cameras.yml, frames/)")->required();
  app.add_option("--reynolds", kin.reynolds, "Re = U c / nu")->capture_default_str();
  app.add_option("--strouhal", kin.strouhal, "St = f A / U, A the trailing edge's peak-to-peak excursion")->capture_default_str();
  app.add_option("--viscosity", kin.kinematic_viscosity, "kinematic viscosity nu (m^2/s)")->capture_default_str();
  app.add_option("--heave-over-chord", kin.heave_over_chord, "root heave half amplitude h0 / c")->capture_default_str();
  app.add_option("--excursion-over-chord", kin.excursion_over_chord,
                 "trailing-edge peak-to-peak excursion A / c that St refers to (sets f = St U / A)")
      ->capture_default_str();
  app.add_option("--pitch-center-deg", kin.pitch_center_deg, "root pitch amplitude of the middle ray")->capture_default_str();
  app.add_option("--pitch-edge-deg", kin.pitch_edge_deg, "root pitch amplitude of the edge rays")->capture_default_str();
  app.add_option("--pitch-phase-deg", kin.pitch_phase_deg, "mean root pitch phase relative to heave (< 0: lags)")->capture_default_str();
  app.add_option("--pitch-phase-w-deg", kin.pitch_phase_w_deg, "half swing of the W-shaped pitch phase")->capture_default_str();
  app.add_option("--chordwise-over-chord", kin.chordwise_over_chord, "chordwise bending wave tip amplitude / c")->capture_default_str();
  app.add_option("--chordwise-wavelength", kin.chordwise_wavelength, "chordwise bending wavelength (ray lengths)")->capture_default_str();
  app.add_option("--chordwise-phase-deg", kin.chordwise_phase_deg, "chordwise bending phase at the root relative to heave")
      ->capture_default_str();
  app.add_option("--spanwise-over-chord", kin.spanwise_over_chord, "spanwise cupping amplitude / c")->capture_default_str();
  app.add_option("--spanwise-phase-deg", kin.spanwise_phase_deg, "spanwise cupping phase relative to heave")->capture_default_str();
  app.add_option("--fps", fps, "camera frame rate (1/s)")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--periods", periods, "flapping periods to record")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--views", views, "camera views (side, back, ventral)")->delimiter(',')->capture_default_str();
  app.add_option("--cameras", cameras_in, "use this cameras.yml instead of the default rig")->check(CLI::ExistingFile);
  double half_field = 1.1, field_centre = 0.5;
  app.add_option("--field-chords", half_field, "default rig: half the field of view around the aim point (chords)")
      ->capture_default_str();
  app.add_option("--field-centre", field_centre, "default rig: x of the cameras' aim point (chords; the fin's root at 0)")
      ->capture_default_str();
  app.add_option("--width", width, "image width (px)")->capture_default_str();
  app.add_option("--height", height, "image height (px)")->capture_default_str();
  app.add_option("--supersample", ren.supersample, "anti-aliasing samples per pixel per axis")->capture_default_str();
  app.add_option("--blur-samples", blur_samples, "motion-blur sub-frames per frame (1: no blur)")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--exposure", exposure, "shutter open time / frame interval (motion blur)")->capture_default_str()->check(CLI::Range(0.0, 1.0));
  app.add_option("--noise-sigma", ren.noise_sigma, "sensor noise (8-bit levels, 0 = none)")->capture_default_str();
  app.add_option("--seed", seed, "seed of the sensor noise and the debris")->capture_default_str();
  // Realistic footage (issue 35, item 8): each effect on its own, or all of them with --footage.
  std::string footage = "clean";
  bool body = false;
  vision::FishBodyOptions body_options;
  vision::DebrisOptions debris;
  int jpeg_quality = 0;
  app.add_option("--footage", footage,
                 "appearance: clean (the backlit tank) or realistic (body, --vignetting 0.55 --vignetting-power 4 "
                 "--background-gradient 0.2 --gain 1.25 --debris 40 --jpeg-quality 75); the flags below override it")
      ->check(CLI::IsMember({"clean", "realistic"}))
      ->capture_default_str();
  app.add_flag("--body,!--no-body", body, "draw the fish's opaque body and peduncle, moving with the fin's root");
  app.add_option("--body-length", body_options.length, "body: snout to peduncle (chords)")->capture_default_str();
  app.add_option("--body-depth", body_options.max_depth, "body: largest dorsal-ventral depth (chords)")->capture_default_str();
  app.add_option("--body-width", body_options.max_width, "body: largest lateral width (chords)")->capture_default_str();
  app.add_option("--body-level", body_options.level, "body: grey level when lit (0..1)")->capture_default_str();
  app.add_option("--body-head-motion", body_options.head_motion, "body: the snout's lateral excursion over the peduncle's (0..1)")
      ->capture_default_str();
  app.add_option("--background-level", ren.background, "backlight at the image centre (fraction of full scale)")->capture_default_str();
  app.add_option("--vignetting", ren.vignetting, "fraction the backlight falls to the image corners")->capture_default_str();
  app.add_option("--vignetting-power", ren.vignetting_power, "falloff exponent of the vignetting in the radius")->capture_default_str();
  app.add_option("--background-gradient", ren.background_gradient, "fraction the backlight falls from the right to the left edge")
      ->capture_default_str();
  app.add_option("--gain", ren.gain, "sensor gain (> 1: the bright background clips at 255)")->capture_default_str();
  app.add_option("--debris", debris.count, "debris specks per view (a third still, the rest drifting)")->capture_default_str();
  app.add_option("--debris-radius", debris.max_radius_px, "largest debris speck radius (px)")->capture_default_str();
  app.add_option("--debris-drift", debris.drift_px_per_s, "fastest debris drift (px/s)")->capture_default_str();
  app.add_option("--jpeg-quality", jpeg_quality, "JPEG-compress every frame at this quality, as MJPG video does (0: none)")
      ->capture_default_str();
  bool video = false;
  app.add_flag("--video", video,
               "write frames/<view>.avi (MJPG at --jpeg-quality, 75 when 0) instead of PNG folders, as a lab's camera records");
  app.add_option("--surface-subdivisions", subdivisions, "truth surface columns per gap between rays (even)")->capture_default_str();
  app.add_option("--vtk", vtk, "also write truth.pvd for ParaView")->capture_default_str();
  app.add_option("--motion-source", motion_source, "what moves the truth fin: prescribed kinematics or the fin FSI")
      ->check(CLI::IsMember({"prescribed", "fsi", "fem"}))
      ->capture_default_str();
  app.add_option("--fsi", fsi_file, "fsi: fsi.h5 of fin-fsi fin (the truth motion)")->check(CLI::ExistingFile);
  app.add_option("--fem", fem_file, "fem: fin-fem run's motion.h5 (with T; the truth motion)")->check(CLI::ExistingFile);
  app.add_option("--fsi-mesh", fsi_mesh, "fsi, fem: the mesh.h5 the FSI (or fin-fem run) ran on")->check(CLI::ExistingFile);
  app.add_option("--materials", materials_file, "fsi: the materials file the FSI ran with (recorded in truth.h5)")
      ->check(CLI::ExistingFile);
  app.add_option("--root-drive", drive_file, "fsi: the root drive file the FSI ran with (recorded in truth.h5)")
      ->check(CLI::ExistingFile);
  app.add_option("--max-fsi-distance", max_fsi_distance,
                 "fsi: largest allowed distance of the truth surface from the FSI mesh's rest mid-surface / c")
      ->capture_default_str();

  return cli::run(app, standard, argc, argv, [&] {
    if (footage == "realistic") apply_footage_preset(app, body, ren, debris, jpeg_quality);
    // The flags' echo shows their defaults where the preset set them: this is what is rendered.
    nlohmann::json appearance = {{"body", body},           {"background_level", ren.background},
                                 {"vignetting", ren.vignetting}, {"vignetting_power", ren.vignetting_power},
                                 {"background_gradient", ren.background_gradient}, {"gain", ren.gain},
                                 {"noise_sigma", ren.noise_sigma}, {"debris", debris.count},
                                 {"debris_radius_px", debris.max_radius_px}, {"debris_drift_px_per_s", debris.drift_px_per_s},
                                 {"jpeg_quality", jpeg_quality}, {"video", video}};
    if (body)
      appearance["body_options"] = {{"length", body_options.length}, {"max_depth", body_options.max_depth},
                                    {"max_width", body_options.max_width}, {"level", body_options.level},
                                    {"head_motion", body_options.head_motion}};
    log::info("appearance: " + appearance.dump());
    if (jpeg_quality < 0 || jpeg_quality > 100) throw Error("--jpeg-quality: expected 1..100 (0: no compression)");
    for (const char* flag : {"--body-length", "--body-depth", "--body-width", "--body-level", "--body-head-motion"})
      if (!body && app.count(flag) > 0) throw Error(std::string(flag) + ": only with --body (or --footage realistic)");
    for (const char* flag : {"--field-chords", "--field-centre"})
      if (!cameras_in.empty() && app.count(flag) > 0) throw Error(std::string(flag) + ": only for the default rig, not with --cameras");
    const auto fin = mesh::make_template(tmpl);
    kin.chord_m = fin.chord;
    const auto surface = vision::make_fin_surface(fin, subdivisions);
    // fem: a fin-fem response stands where the FSI's fsi.h5 would (same binding, same records).
    const bool from_fem = motion_source == "fem", from_fsi = motion_source == "fsi" || from_fem;
    const std::vector<std::string> prescribed_only{"--heave-over-chord",    "--pitch-center-deg",    "--pitch-edge-deg",
                                            "--pitch-phase-deg",     "--pitch-phase-w-deg",   "--chordwise-over-chord",
                                            "--chordwise-wavelength", "--chordwise-phase-deg", "--spanwise-over-chord",
                                            "--spanwise-phase-deg",  "--strouhal",            "--excursion-over-chord"};
    const std::vector<std::string> fsi_only{from_fem ? "--fem" : "--fsi", "--fsi-mesh", "--materials", "--root-drive"};
    for (const auto& flag : from_fsi ? prescribed_only : fsi_only)
      if (app.count(flag) > 0)
        throw Error(flag + ": only with --motion-source " + (from_fsi ? "prescribed" : "fsi or fem") +
                    (from_fsi ? " (the truth's root drive is --root-drive's)" : ""));
    if (app.count(from_fem ? "--fsi" : "--fem") > 0)
      throw Error(std::string(from_fem ? "--fsi" : "--fem") + ": not with --motion-source " + motion_source);
    for (const auto& flag : fsi_only)
      if (from_fsi && app.count(flag) == 0) throw Error(flag + ": required with --motion-source " + motion_source);

    // The root kinematics: the prescribed model's own, or the FSI's drive file on the same U/W
    // profiles (the FSI truth's bending is the FSI's, not the model's).
    const auto drive = from_fsi ? read_drive(drive_file, kin, fin.chord) : Drive{kin, 0, {}};
    const vision::PrescribedKinematics model(drive.kin);
    std::optional<vision::FsiMotion> fsi;
    std::vector<int> ray_ids;
    if (from_fsi) {
      fsi.emplace(from_fem ? vision::read_fem_motion(fem_file, fsi_mesh, surface, max_fsi_distance)
                           : vision::read_fsi_motion(fsi_file, fsi_mesh, surface, max_fsi_distance));
      const auto m = stage::read<stage::Mesh>(fsi_mesh);
      const std::set<int> ids(m.beam_ray.data.begin(), m.beam_ray.data.end());
      ray_ids.assign(ids.begin(), ids.end());
      // The drive's frequency and the FSI's period must agree: the truth's T is the drive's.
      const double f = drive.frequency_hz;
      if (std::abs(fsi->period() * f - 1) > 1e-6)
        throw Error((from_fem ? fem_file : fsi_file).string() + ": T = " + std::to_string(fsi->period()) + " s, but " + drive_file.string() +
                    " drives at f = " + std::to_string(f) + " Hz (Re " + std::to_string(kin.reynolds) +
                    ", chord " + std::to_string(fin.chord) + " m): not the FSI of this drive");
      log::info("FSI motion: " + fsi->parameters().dump());
    } else {
      for (std::size_t r = 1; r <= fin.ray_count(); ++r) ray_ids.push_back(static_cast<int>(r));
    }
    const vision::MotionSource& source = from_fsi ? static_cast<const vision::MotionSource&>(*fsi) : model;
    const double T = source.period();
    const auto nf = static_cast<std::size_t>(std::llround(periods * T * fps));
    if (nf < 1) throw Error("--periods/--fps: fewer than one frame to record");
    log::info("fin: " + std::to_string(fin.ray_count()) + " rays, chord " + std::to_string(fin.chord) + " m, area " +
              std::to_string(fin.area()) + " m^2; truth surface " + std::to_string(surface.size()) + " vertices");
    log::info("motion (" + source.name() + "): U = " + std::to_string(model.speed()) + " m/s, f = " +
              std::to_string(1 / T) + " Hz, T = " + std::to_string(T) + " s; " + std::to_string(nf) + " frames at " +
              std::to_string(fps) + " fps");

    const auto cameras = cameras_in.empty() ? vision::default_rig(views, fin.chord, width, height, half_field, field_centre) : vision::read_cameras(cameras_in);
    fs::create_directories(out_dir);
    fs::create_directories(out_dir / "frames");
    if (!video)
      for (const auto& c : cameras) fs::create_directories(out_dir / "frames" / c.name);
    // With --video the frames are kept and written view by view after rendering (a video is sequential).
    std::vector<std::vector<cv::Mat>> clips(video ? cameras.size() : 0, std::vector<cv::Mat>(nf));
    const int video_quality = jpeg_quality > 0 ? jpeg_quality : 75;

    stage::Truth truth;
    truth.template_points = surface.rest;
    truth.template_triangles = surface.triangles;
    truth.time = NdArray<double>({nf});
    truth.points = NdArray<double>({nf, surface.size(), 3});
    // The prescribed motion has no materials: the lists are present and empty (np = 0).
    truth.material_values = NdArray<double>({0});
    if (from_fsi) record_materials(materials_file, ray_ids, truth);
    record_root(model, drive.kin.heave_over_chord * fin.chord, ray_ids, truth);
    truth.period = T;
    truth.motion_source = source.name();
    if (from_fsi) truth.root_drive = drive.json.dump();
    auto effects = source.effects();
    if (from_fsi) {
      // Effects beyond elastic rays and membrane that the materials file gives the FSI.
      std::ifstream in(materials_file);
      const auto j = nlohmann::json::parse(in);
      for (const char* key : {"distal", "modulation", "rayleigh", "shell_region"})
        if (j.contains(key)) effects[key] = j[key];
      // The candidate effects the FSI structure ran with (config truth.effects, fin-fsi --effects).
      if (const auto planted = h5::File::open_read(from_fem ? fem_file : fsi_file).attr_string(".", "effects"))
        effects["structural"] = nlohmann::json::parse(*planted);
    }
    truth.effects = effects.dump();

    std::optional<vision::FishBody> fish_body;
    if (body) fish_body.emplace(surface, body_options);
    const vision::Renderer renderer(surface, ren, fish_body ? &*fish_body : nullptr);
    std::vector<vision::Debris> specks;
    for (std::size_t v = 0; v < cameras.size(); ++v) specks.emplace_back(debris, seed, v, cameras[v].width, cameras[v].height);
    const double dt = 1.0 / fps;
    log::Progress progress("render", nf);
    std::size_t done = 0;
    double render_seconds = 0;
    std::string failure;
#pragma omp parallel for schedule(dynamic) reduction(+ : render_seconds)
    for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(nf); ++k) {
      try {
        const double t = k * dt;
        const auto p = source.positions(surface, t);
        std::copy(p.data.begin(), p.data.end(), truth.points.data.begin() + k * p.data.size());
        truth.time(k) = t;
        std::vector<NdArray<double>> sub;
        if (blur_samples == 1) sub.push_back(p);
        for (int j = 0; j < blur_samples && blur_samples > 1; ++j)
          sub.push_back(source.positions(surface, t + exposure * dt * (j / (blur_samples - 1.0) - 0.5)));
        const double t0 = log::elapsed_seconds();
        for (std::size_t v = 0; v < cameras.size(); ++v) {
          cv::Mat exposure = renderer.render_exposure(cameras[v], sub);
          specks[v].draw(exposure, t);
          cv::Mat img = renderer.sensor(exposure, vision::noise_key(seed, v, k));
          if (video) {
            clips[v][k] = img;
            continue;
          }
          if (jpeg_quality > 0) img = vision::jpeg_round_trip(img, jpeg_quality);
          std::vector<unsigned char> png;
          if (!cv::imencode(".png", img, png)) throw Error("cannot encode PNG");
          char name[32];
          std::snprintf(name, sizeof name, "%06td.png", k);
          write_text_atomic(out_dir / "frames" / cameras[v].name / name, std::string(png.begin(), png.end()));
        }
        render_seconds += log::elapsed_seconds() - t0;
#pragma omp critical
        progress.update(++done, "t = " + std::to_string(t) + " s");
      } catch (const std::exception& e) {
#pragma omp critical
        failure = e.what();
      }
    }
    if (!failure.empty()) throw Error(failure);
    for (std::size_t v = 0; v < clips.size(); ++v)
      vision::write_mjpg_avi(out_dir / "frames" / (cameras[v].name + ".avi"), clips[v], fps, video_quality);
    progress.finish();
    log::info("render: " + std::to_string(1e3 * render_seconds / (nf * cameras.size())) + " ms per view-frame (" +
              std::to_string(cameras[0].width) + "x" + std::to_string(cameras[0].height) + ", supersample " +
              std::to_string(ren.supersample) + ", " + std::to_string(blur_samples) + " sub-frames)");

    vision::write_cameras(out_dir / "cameras.yml", cameras);
    mesh::write_template(out_dir / "template.json", fin);
    Provenance prov{"fin-synth", cli::effective_config(app), {}};
    prov.config["motion_source"] = source.parameters();
    prov.config["appearance"] = appearance;
    if (!tmpl.file.empty()) prov.inputs.push_back(tmpl.file);
    if (!cameras_in.empty()) prov.inputs.push_back(cameras_in);
    for (const auto& p : {fsi_file, fem_file, fsi_mesh, materials_file, drive_file})
      if (!p.empty()) prov.inputs.push_back(p);
    if (vtk) {
      std::vector<vtkio::SurfaceFrame> frames(nf);
      std::vector<double> times(nf);
      for (std::size_t k = 0; k < nf; ++k) {
        times[k] = truth.time(k);
        frames[k].points = NdArray<double>({surface.size(), 3});
        std::copy_n(truth.points.data.begin() + k * surface.size() * 3, surface.size() * 3, frames[k].points.data.begin());
        frames[k].point_data.push_back({"ray_distance", NdArray<double>({surface.size()}, surface.ray_distance)});
      }
      vtkio::write_surface_series(out_dir / "truth.pvd", times, surface.triangles, frames);
    }
    stage::write(out_dir / "truth.h5", truth, prov);
    log::info("wrote " + (out_dir / "truth.h5").string() + ", cameras.yml, " + std::to_string(nf * cameras.size()) + " frames");
    return kExitOk;
  });
}
