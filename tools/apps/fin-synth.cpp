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
// The flags and their checks are vision/synth_flags; the motion and what truth.h5 records of it,
// vision/synth_motion.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/stage_files.hpp"
#include "core/vtk_output.hpp"
#include "mesh/template_options.hpp"
#include "vision/camera.hpp"
#include "vision/fin_surface.hpp"
#include "vision/fish_body.hpp"
#include "vision/footage_effects.hpp"
#include "vision/renderer.hpp"
#include "vision/synth_flags.hpp"
#include "vision/synth_motion.hpp"

namespace fs = std::filesystem;
using namespace finverse;

namespace {

// The sub-frames a frame at time t averages over its exposure (motion blur): their times and the
// surface at each (`at_t`: the surface at t itself, the one sub-frame without blur).
struct SubFrames {
  std::vector<NdArray<double>> positions;
  std::vector<double> times;
};
SubFrames sub_frames(const vision::MotionSource& source, const vision::FinSurface& surface, const NdArray<double>& at_t,
                     double t, int samples, double exposure_dt) {
  SubFrames s;
  if (samples == 1) s.positions.push_back(at_t), s.times.push_back(t);
  for (int j = 0; j < samples && samples > 1; ++j) {
    s.times.push_back(t + exposure_dt * (j / (samples - 1.0) - 0.5));
    s.positions.push_back(source.positions(surface, s.times.back()));
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fin-synth: simulate the fin's motion and render synchronized camera frames"};
  cli::Standard standard(app, "fin-synth");
  mesh::TemplateOptions tmpl;
  mesh::add_template_options(app, tmpl);
  vision::SynthFlags flags;
  vision::add_synth_flags(app, flags);

  return cli::run(app, standard, argc, argv, [&] {
    auto appearance = vision::apply_appearance_flags(app, flags);
    log::info("appearance: " + appearance.dump());
    vision::check_appearance_flags(app, flags);
    // The flags the render uses, as set once the preset is applied.
    const fs::path &out_dir = flags.out_dir, &cameras_in = flags.cameras_in;
    const double fps = flags.fps, periods = flags.periods, exposure = flags.exposure;
    const int blur_samples = flags.blur_samples, jpeg_quality = flags.jpeg_quality;
    const std::uint64_t seed = flags.seed;
    const bool video = flags.video;
    const auto fin = mesh::make_template(tmpl);
    flags.kin.chord_m = fin.chord;
    const auto surface = vision::make_fin_surface(fin, flags.subdivisions);
    vision::check_motion_flags(app, flags);
    const auto motion = vision::make_synth_motion(flags, fin, surface);
    const vision::MotionSource& source = motion.source();
    const double T = source.period();
    const auto nf = static_cast<std::size_t>(std::llround(periods * T * fps));
    if (nf < 1) throw Error("--periods/--fps: fewer than one frame to record");
    log::info("fin: " + std::to_string(fin.ray_count()) + " rays, chord " + std::to_string(fin.chord) + " m, area " +
              std::to_string(fin.area()) + " m^2; truth surface " + std::to_string(surface.size()) + " vertices");
    log::info("motion (" + source.name() + "): U = " + std::to_string(motion.model.speed()) +
              " m/s, f = " + std::to_string(1 / T) + " Hz, T = " + std::to_string(T) + " s; " + std::to_string(nf) +
              " frames at " + std::to_string(fps) + " fps");

    const auto cameras = cameras_in.empty() ? vision::default_rig(flags.views, fin.chord, flags.width, flags.height,
                                                                  flags.half_field, flags.field_centre)
                                            : vision::read_cameras(cameras_in);
    // Frames go to frames.tmp, renamed to frames when every one is written: a run killed half way
    // leaves no folder of frames that looks complete (issue 46).
    const fs::path frames_dir = out_dir / "frames", frames_tmp = temporary_for(frames_dir);
    fs::create_directories(out_dir);
    fs::remove_all(frames_tmp);
    fs::create_directories(frames_tmp);
    if (!video)
      for (const auto& c : cameras) fs::create_directories(frames_tmp / c.name);
    // With --video the frames are kept and written view by view after rendering (a video is sequential).
    std::vector<std::vector<cv::Mat>> clips(video ? cameras.size() : 0, std::vector<cv::Mat>(nf));
    const int video_quality = jpeg_quality > 0 ? jpeg_quality : 75;

    stage::Truth truth;
    truth.template_points = surface.rest;
    truth.template_triangles = surface.triangles;
    truth.time = NdArray<double>({nf});
    truth.points = NdArray<double>({nf, surface.size(), 3});
    vision::record_synth_motion(flags, motion, fin.chord, truth);

    std::optional<vision::FishBody> fish_body;
    if (flags.body && flags.body_options.pectoral_length > 0 && app.count("--pectoral-frequency") == 0) {
      flags.body_options.pectoral_frequency = 1 / T;  // the pectoral fins keep the tail's beat
      appearance["body_options"]["pectoral"]["frequency_hz"] = 1 / T;
    }
    if (flags.body) fish_body.emplace(surface, flags.body_options);
    const vision::Renderer renderer(surface, flags.ren, fish_body ? &*fish_body : nullptr);
    if (fish_body)
      truth.body_axis = NdArray<double>({nf, static_cast<std::size_t>(flags.body_options.stations) + 2, 3});
    std::vector<vision::Debris> specks;
    for (std::size_t v = 0; v < cameras.size(); ++v)
      specks.emplace_back(flags.debris, seed, v, cameras[v].width, cameras[v].height);
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
        const SubFrames sub = sub_frames(source, surface, p, t, blur_samples, exposure * dt);
        if (fish_body) {  // the body's axis, the 2-D mode's true midline (issue 47)
          const auto a = fish_body->axis(p);
          std::copy(a.data.begin(), a.data.end(), truth.body_axis.data.begin() + k * a.data.size());
        }
        const double t0 = log::elapsed_seconds();
        for (std::size_t v = 0; v < cameras.size(); ++v) {
          cv::Mat exposure = renderer.render_exposure(cameras[v], sub.positions, sub.times);
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
          write_text_atomic(frames_tmp / cameras[v].name / name, std::string(png.begin(), png.end()));
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
      vision::write_mjpg_avi(frames_tmp / (cameras[v].name + ".avi"), clips[v], fps, video_quality);
    fs::remove_all(frames_dir);
    fs::rename(frames_tmp, frames_dir);
    progress.finish();
    log::info("render: " + std::to_string(1e3 * render_seconds / (nf * cameras.size())) + " ms per view-frame (" +
              std::to_string(cameras[0].width) + "x" + std::to_string(cameras[0].height) + ", supersample " +
              std::to_string(flags.ren.supersample) + ", " + std::to_string(blur_samples) + " sub-frames)");

    vision::write_cameras(out_dir / "cameras.yml", cameras);
    mesh::write_template(out_dir / "template.json", fin);
    Provenance prov{"fin-synth", cli::effective_config(app), {}};
    prov.config["motion_source"] = source.parameters();
    prov.config["appearance"] = appearance;
    if (!tmpl.file.empty()) prov.inputs.push_back(tmpl.file);
    if (!cameras_in.empty()) prov.inputs.push_back(cameras_in);
    for (const auto& p : {flags.fsi_file, flags.fem_file, flags.fsi_mesh, flags.materials_file, flags.drive_file})
      if (!p.empty()) prov.inputs.push_back(p);
    if (flags.vtk) {
      std::vector<vtkio::SurfaceFrame> frames(nf);
      std::vector<double> times(nf);
      for (std::size_t k = 0; k < nf; ++k) {
        times[k] = truth.time(k);
        frames[k].points = NdArray<double>({surface.size(), 3});
        std::copy_n(truth.points.data.begin() + k * surface.size() * 3, surface.size() * 3,
                    frames[k].points.data.begin());
        frames[k].point_data.push_back({"ray_distance", NdArray<double>({surface.size()}, surface.ray_distance)});
      }
      vtkio::write_surface_series(out_dir / "truth.pvd", times, surface.triangles, frames);
    }
    stage::write(out_dir / "truth.h5", truth, prov);
    log::info("wrote " + (out_dir / "truth.h5").string() + ", cameras.yml, " + std::to_string(nf * cameras.size()) +
              " frames");
    return kExitOk;
  });
}
