// fin-loop residual and trace from stage files (file_loop.hpp).
#include "loop/io/file_loop.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "core/log.hpp"
#include "core/stage_identity.hpp"
#include "fem/effects/structural_effect.hpp"
#include "fem/io/fin_layout.hpp"
#include "fem/io/harmonic_motion.hpp"
#include "fem/io/material_spec.hpp"
#include "fem/io/periodic_motion.hpp"
#include "loop/fin_traced_model.hpp"

namespace finverse::loop::io {
namespace {

std::string schema_of(const std::filesystem::path& path) {
  const auto f = h5::File::open_read(path);
  const auto s = f.attr_string(".", "schema");
  if (!s) throw Error(path.string() + ": no root attribute 'schema': expected a finverse stage file");
  return *s;
}

// The prediction: fsi.h5 (finverse/fsi) or a structural response (finverse/motion, fin-fem run).
SampledMotion read_prediction(const std::filesystem::path& path, std::string& kind, std::optional<double>& period) {
  const auto schema = schema_of(path);
  if (schema == "finverse/fsi") {
    const auto f = stage::read<stage::Fsi>(path);
    kind = "fsi";
    period = f.period;
    return sampled_motion(f.time, f.points, path.string());
  }
  if (schema == "finverse/motion") {
    const auto m = stage::read<stage::Motion>(path);
    kind = "fem";
    period = m.period;
    return sampled_motion(m.time, m.points, path.string());
  }
  throw Error(path.string() + ": schema '" + schema + "': expected finverse/fsi or finverse/motion");
}

}  // namespace

Eigen::VectorXd mesh_node_weights(const stage::Mesh& mesh) {
  const std::size_t nv = mesh.points.dim(0);
  Eigen::VectorXd w = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(nv));
  const std::size_t ntri = mesh.triangles.shape.empty() ? 0 : mesh.triangles.dim(0);
  auto x = [&](std::size_t i) { return Eigen::Vector3d(mesh.points(i, 0), mesh.points(i, 1), mesh.points(i, 2)); };
  for (std::size_t e = 0; e < ntri; ++e) {
    const auto a = static_cast<std::size_t>(mesh.triangles(e, 0)), b = static_cast<std::size_t>(mesh.triangles(e, 1)),
               c = static_cast<std::size_t>(mesh.triangles(e, 2));
    if (a >= nv || b >= nv || c >= nv) throw Error("mesh.h5: /triangles: node out of range");
    const double area = 0.5 * (x(b) - x(a)).cross(x(c) - x(a)).norm();
    for (auto n : {a, b, c}) w(static_cast<Eigen::Index>(n)) += area / 3;
  }
  const double mean_on = w.sum() > 0 ? w.sum() / static_cast<double>((w.array() > 0).count()) : 1.0;
  for (Eigen::Index i = 0; i < w.size(); ++i)
    if (!(w(i) > 0)) w(i) = mean_on;
  for (auto n : mesh.root_nodes.data)
    if (n >= 0 && static_cast<std::size_t>(n) < nv) w(n) = 0;
  const double mean = w.sum() / static_cast<double>((w.array() > 0).count());
  return w / mean;
}

ResidualAnalysis run_residual_from_files(const FileResidualOptions& o, const nlohmann::json& config) {
  const auto mesh = stage::read<stage::Mesh>(o.mesh);
  const auto motion = stage::read<stage::Motion>(o.reconstruction);
  check_made_from(o.reconstruction, o.mesh);
  std::string kind;
  std::optional<double> prediction_period;
  const auto prediction = read_prediction(o.prediction, kind, prediction_period);
  const auto reconstruction = sampled_motion(motion.time, motion.points, o.reconstruction.string());

  ResidualAnalysisOptions ao;
  ao.period = o.period ? o.period : motion.period ? motion.period : prediction_period;
  ao.harmonics = o.harmonics;
  ao.modes = o.modes;
  ao.node_weights = mesh_node_weights(mesh);
  ao.trailing_edge_nodes = ray_tip_nodes(mesh);
  std::vector<int> root(mesh.root_nodes.data.begin(), mesh.root_nodes.data.end());
  auto analysis = analyse_residual(prediction, reconstruction, rest_positions(mesh), root, ao);
  for (const auto& f : analysis.flags) log::warn("fin-loop residual: " + f);

  Provenance provenance{"fin-loop", config, {o.mesh, o.reconstruction, o.prediction}};
  write_residual(o.out, analysis, ao.period, kind, provenance);
  if (o.summary) {
    auto j = residual_summary_json(analysis);
    j["prediction_kind"] = kind;
    write_text_atomic(*o.summary, j.dump(2) + "\n");
  }
  return analysis;
}

TraceRecord run_trace_from_files(const FileTraceOptions& o, const nlohmann::json& config) {
  const auto mesh = stage::read<stage::Mesh>(o.mesh);
  auto motion = stage::read<stage::Motion>(o.root_motion ? *o.root_motion : o.motion);
  const auto reconstruction = stage::read<stage::Motion>(o.motion);
  std::optional<stage::Loads> loads;
  if (o.loads) loads = stage::read<stage::Loads>(*o.loads);
  check_made_from(o.motion, o.mesh);
  if (o.loads) check_made_from(*o.loads, o.mesh);
  if (loads && !loads->time.data.empty() &&
      fem::io::needs_periodic_extension(motion, loads->time.data.front(), loads->time.data.back()))
    motion = fem::io::periodic_extension(motion, loads->time.data.front(), loads->time.data.back());

  // The base: materials.h5's parameters at their best values (without --fit: the fit's default
  // fin parameters at the materials file's values, a twin's start); the refitted subset.
  std::vector<fit::Parameter> all;
  std::vector<double> best_values;
  std::string fit_source = "default fin parameters";
  if (o.fit) {
    const auto fitted = stage::read<stage::Materials>(*o.fit);
    fit_source = o.fit->string();
    for (std::size_t i = 0; i < fitted.names.size(); ++i) {
      fit::Parameter p;
      p.name = fitted.names[i];
      p.unit = fitted.units[i];
      p.lower = fitted.lower.data[i];
      p.upper = fitted.upper.data[i];
      p.scale = fit::parse_scale(fitted.scale[i], fit_source);
      all.push_back(p);
      best_values.push_back(fitted.best.data[i]);
    }
  } else {
    all = fit::default_fin_parameters(mesh);
  }
  std::vector<std::string> all_names;
  for (const auto& p : all) all_names.push_back(p.name);
  // The drive's correction (--fit-drive, or drive_* names in --parameters) joins the base at
  // zero, the tracked drive, unless the fit already has it.
  std::vector<std::string> refit_names = o.parameters.empty() ? all_names : o.parameters;
  for (const auto& name : fit::drive_parameter_names(o.drive_order))
    if (std::find(refit_names.begin(), refit_names.end(), name) == refit_names.end()) refit_names.push_back(name);
  std::vector<fit::Parameter> refit;
  for (const auto& name : refit_names) {
    auto it = std::find(all_names.begin(), all_names.end(), name);
    if (it == all_names.end()) {
      const auto drive = fit::drive_parameter(name, mesh);
      if (!drive) throw Error("--parameters: '" + name + "' is not a parameter of " + fit_source);
      all.push_back(*drive);
      all_names.push_back(name);
      it = all_names.end() - 1;
    }
    refit.push_back(all[static_cast<std::size_t>(it - all_names.begin())]);
  }
  const std::optional<double> period = o.period ? o.period : reconstruction.period;
  const double beat_frequency = o.frequency ? *o.frequency : period ? 1.0 / *period : 0.0;

  if (o.drive_harmonics > 0)
    motion = fem::io::harmonic_motion(motion, beat_frequency, o.drive_harmonics,
                                      (o.root_motion ? *o.root_motion : o.motion).string());
  fit::FinDrive drive;
  drive.loads = loads;
  if (o.loads) drive.loads_source = o.loads->string();
  drive.root_motion = motion;
  drive.motion_source = (o.root_motion ? *o.root_motion : o.motion).string();
  drive.ramp = o.ramp;
  drive.root_rotation = o.root_rotation;
  drive.frequency = beat_frequency;
  const auto base_spec = fem::io::read_material_spec(o.materials);
  auto base = std::make_shared<fit::FinModelFactory>(mesh, base_spec, all_names, drive, o.mesh.string());
  Eigen::VectorXd best = base->default_parameters();
  for (std::size_t i = 0; i < best_values.size(); ++i) best(static_cast<Eigen::Index>(i)) = best_values[i];

  FinTraceSetup setup;
  setup.base = base;
  setup.best = best;
  setup.refit = fit::ParameterSpace(refit, fit_source);
  setup.layout = fem::io::make_fin_layout(mesh, o.mesh.string());
  setup.layout.beat_frequency = beat_frequency;
  setup.layout.start_time = base->start_time();
  setup.layout.ramp = base->ramp();
  if (o.candidates) {
    std::ifstream in(*o.candidates);
    if (!in) throw Error(o.candidates->string() + ": cannot read");
    nlohmann::json j;
    try {
      j = nlohmann::json::parse(in);
    } catch (const std::exception& e) {
      throw Error(o.candidates->string() + ": not JSON: " + e.what());
    }
    const auto& list = j.is_object() && j.contains("effects") ? j["effects"] : j;
    if (!list.is_array()) throw Error(o.candidates->string() + ": expected a JSON array of effect specs");
    for (const auto& s : list) setup.candidates.push_back(s);
  } else {
    for (const auto& n : fem::effect_names()) setup.candidates.push_back({{"name", n}});
  }
  for (const auto& s : setup.candidates) fem::make_effect(s);  // bad specs: before any run
  setup.target = fit::target_from_motion(reconstruction, static_cast<int>(mesh.points.dim(0)), o.motion.string(),
                                         o.mesh.string());
  setup.run.analysis = o.analysis;
  setup.run.substeps = o.substeps;
  setup.run.start_time = base->start_time();
  setup.run.dynamic_options.spectral_radius = o.spectral_radius;
  if (o.full_newton) setup.run.dynamic_options = fem::with_full_newton(setup.run.dynamic_options);
  setup.run.dynamic_options.rayleigh_mass = base->damping().mass;
  setup.run.dynamic_options.rayleigh_stiffness = base->damping().stiffness;
  setup.trailing_edge_nodes = ray_tip_nodes(mesh);
  setup.relative_step = o.relative_step;
  const FinTracedModel model(setup);

  TraceRecord rec;
  rec.candidates = model.candidates();
  const auto recon = sampled_motion(reconstruction.time, reconstruction.points, o.motion.string());
  rec.excursion = trailing_edge_excursion(recon, setup.trailing_edge_nodes);
  rec.split = held_out_split(reconstruction.time.data, period.value_or(0.0));
  if (rec.split.kind != "last_cycle")
    log::warn("fin-loop trace: fewer than two periods of frames: the held-out frames interleave with the fitted "
              "ones, so the held-out error is not from independent cycles");
  TraceOptions to;
  to.held_out_frames = rec.split.held_out;
  to.refit_base = o.refit_base;
  to.alpha = o.alpha;
  to.max_effects = o.max_effects;
  to.lm = o.lm;
  to.progress = [](const std::string& line) { log::info("fin-loop trace: " + line); };
  to.lm.progress = to.progress;
  std::ostringstream what;
  what << "fin-loop trace: " << rec.candidates.size() << " candidates, " << setup.refit.size()
       << " refitted parameters, " << setup.target.frame_count() << " frames (" << rec.split.held_out.size()
       << " held out, " << rec.split.kind << ")";
  log::info(what.str());
  rec.result = trace_effects(model, to);

  Provenance provenance{"fin-loop", config, {o.mesh, o.motion, o.materials}};
  if (o.fit) provenance.inputs.push_back(*o.fit);
  if (o.root_motion) provenance.inputs.push_back(*o.root_motion);
  if (o.loads) provenance.inputs.push_back(*o.loads);
  if (o.candidates) provenance.inputs.push_back(*o.candidates);
  write_loop(o.out, rec, provenance);
  if (o.summary) write_text_atomic(*o.summary, trace_summary_json(rec).dump(2) + "\n");
  return rec;
}

}  // namespace finverse::loop::io
