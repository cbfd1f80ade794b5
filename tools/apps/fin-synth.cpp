// fin-synth: the virtual experiment (DESIGN.md sections 1 and 5.5). Builds the truth fin from the
// template, moves it with a motion source (today the prescribed trout kinematics of the seed
// paper, section 4.4, at Re = 1000, St = 0.44 on a 1.0 c trailing-edge excursion: f = 4.4 Hz,
// 500 fps) and renders every calibrated view.
//
//   fin-synth --out-dir results/trout_caudal --periods 1 --views side,back,ventral
//
// Writes <out-dir>/truth.h5 (stage::Truth), cameras.yml, frames/<view>/NNNNNN.png, template.json
// and truth.pvd (ParaView). Same inputs, seed and threads give byte-identical files.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "core/atomic_file.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/log.hpp"
#include "core/stage_files.hpp"
#include "core/vtk_output.hpp"
#include "mesh/template_options.hpp"
#include "vision/camera.hpp"
#include "vision/fin_surface.hpp"
#include "vision/kinematic_model.hpp"
#include "vision/renderer.hpp"

namespace fs = std::filesystem;
using namespace finverse;

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
  app.add_option("--width", width, "image width (px)")->capture_default_str();
  app.add_option("--height", height, "image height (px)")->capture_default_str();
  app.add_option("--supersample", ren.supersample, "anti-aliasing samples per pixel per axis")->capture_default_str();
  app.add_option("--blur-samples", blur_samples, "motion-blur sub-frames per frame (1: no blur)")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--exposure", exposure, "shutter open time / frame interval (motion blur)")->capture_default_str()->check(CLI::Range(0.0, 1.0));
  app.add_option("--noise-sigma", ren.noise_sigma, "sensor noise (8-bit levels, 0 = none)")->capture_default_str();
  app.add_option("--seed", seed, "seed of the sensor noise")->capture_default_str();
  app.add_option("--surface-subdivisions", subdivisions, "truth surface columns per gap between rays (even)")->capture_default_str();
  app.add_option("--vtk", vtk, "also write truth.pvd for ParaView")->capture_default_str();

  return cli::run(app, standard, argc, argv, [&] {
    const auto fin = mesh::make_template(tmpl);
    kin.chord_m = fin.chord;
    const vision::PrescribedKinematics model(kin);
    const vision::MotionSource& source = model;
    const auto surface = vision::make_fin_surface(fin, subdivisions);
    const double T = source.period();
    const auto nf = static_cast<std::size_t>(std::llround(periods * T * fps));
    if (nf < 1) throw Error("--periods/--fps: fewer than one frame to record");
    log::info("fin: " + std::to_string(fin.ray_count()) + " rays, chord " + std::to_string(fin.chord) + " m, area " +
              std::to_string(fin.area()) + " m^2; truth surface " + std::to_string(surface.size()) + " vertices");
    log::info("motion: U = " + std::to_string(model.speed()) + " m/s, f = " + std::to_string(model.frequency()) +
              " Hz, T = " + std::to_string(T) + " s; " + std::to_string(nf) + " frames at " + std::to_string(fps) + " fps");

    const auto cameras = cameras_in.empty() ? vision::default_rig(views, fin.chord, width, height) : vision::read_cameras(cameras_in);
    fs::create_directories(out_dir);
    for (const auto& c : cameras) fs::create_directories(out_dir / "frames" / c.name);

    stage::Truth truth;
    truth.template_points = surface.rest;
    truth.template_triangles = surface.triangles;
    truth.time = NdArray<double>({nf});
    truth.points = NdArray<double>({nf, surface.size(), 3});
    // The prescribed motion has no materials: the lists are present and empty (np = 0).
    truth.material_values = NdArray<double>({0});
    truth.period = T;
    truth.effects = source.effects().dump();

    const vision::Renderer renderer(surface, ren);
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
          const auto img = renderer.render_frame(cameras[v], sub, vision::noise_key(seed, v, k));
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
    progress.finish();
    log::info("render: " + std::to_string(1e3 * render_seconds / (nf * cameras.size())) + " ms per view-frame (" +
              std::to_string(cameras[0].width) + "x" + std::to_string(cameras[0].height) + ", supersample " +
              std::to_string(ren.supersample) + ", " + std::to_string(blur_samples) + " sub-frames)");

    vision::write_cameras(out_dir / "cameras.yml", cameras);
    mesh::write_template(out_dir / "template.json", fin);
    Provenance prov{"fin-synth", cli::effective_config(app), {}};
    prov.config["motion_source"] = source.parameters();
    if (!tmpl.file.empty()) prov.inputs.push_back(tmpl.file);
    if (!cameras_in.empty()) prov.inputs.push_back(cameras_in);
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
