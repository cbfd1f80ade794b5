// fin-fit run from stage files (see file_fit.hpp).
#include "fit/io/file_fit.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <memory>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/log.hpp"
#include "core/provenance.hpp"
#include "core/stage_files.hpp"
#include "core/stage_identity.hpp"
#include "fem/errors.hpp"
#include "fem/io/material_spec.hpp"
#include "fem/io/nodal_force_file.hpp"
#include "fem/io/periodic_motion.hpp"
#include "fit/dynamic_objective.hpp"
#include "fit/errors.hpp"
#include "fit/fin_parameters.hpp"
#include "fit/io/materials_file.hpp"
#include "fit/io/tracking_noise.hpp"
#include "fit/parameter_space.hpp"
#include "fit/quasi_static_objective.hpp"
#include "fit/rank_pool.hpp"
#include "fit/static_objective.hpp"
#include "fit/target_motion.hpp"

namespace finverse::fit::io {

namespace {

std::string sci(double x, int digits = 3) {
  std::ostringstream s;
  s.precision(digits);
  s << std::scientific << x;
  return s.str();
}

// Instants of eq. (2): explicit, or `count` spread evenly over [t_lo, t_hi - dt] (the target's
// span, within the loads' when given) starting at its middle (count 1: the paper's mid-swing),
// each snapped to a target frame.
std::vector<double> quasi_static_instants(const FileFitOptions& o, const TargetMotion& target, double dt,
                                          double t_lo, double t_hi) {
  if (!o.instants.empty()) return o.instants;
  if (o.instant_count < 1) throw InvalidInput("--instant-count must be >= 1");
  const double span = t_hi - t_lo - dt;
  if (!(span > 0)) throw InvalidInput(target.source + ": the motion and loads overlap by less than one increment dt");
  std::vector<double> t;
  for (int j = 0; j < o.instant_count; ++j) {
    double s = 0.5 + static_cast<double>(j) / o.instant_count;
    s -= std::floor(s);
    const double want = t_lo + s * span;
    // Snap to the nearest target frame inside the range: the target increment is then a sample
    // difference, not an interpolation.
    double best = want, distance = std::numeric_limits<double>::infinity();
    for (double tf : target.times)
      if (tf >= t_lo && tf <= t_lo + span && std::abs(tf - want) < distance) {
        best = tf;
        distance = std::abs(tf - want);
      }
    t.push_back(best);
  }
  return t;
}

}  // namespace

FitProblem load_fit_problem(const FileFitOptions& o) {
  const auto mesh = stage::read<stage::Mesh>(o.mesh);
  auto motion = stage::read<stage::Motion>(o.motion);
  std::optional<stage::Loads> loads;
  bool structural = false;  // nodal_loads.h5: a structural load case, no flow
  if (o.loads) {
    auto file = fem::io::read_nodal_force_file(*o.loads);
    loads = std::move(file.loads);
    structural = file.structural;
  }
  // Stages that disagree (issue 33): the motion on another mesh, loads from another mesh or motion.
  check_made_from(o.motion, o.mesh);
  if (o.loads) check_made_from(*o.loads, o.mesh), check_made_from(*o.loads, o.motion);
  if (o.target_noise > 0) {
    if (!mesh.chord || !(*mesh.chord > 0))
      throw InvalidInput(o.mesh.string() + ": --target-noise needs the mesh's chord attribute (a fin mesh has one)");
    const double sigma = sigma_for_mean_error(o.target_noise * *mesh.chord);
    motion = with_tracking_noise(std::move(motion), sigma, o.target_noise_seed);
    log::info(o.motion.string() + ": Gaussian noise of " + sci(sigma) + " m per component added (mean vertex error " +
              sci(o.target_noise) + " c, seed " + std::to_string(o.target_noise_seed) + ")");
  }
  if (loads && !loads->time.data.empty() &&
      fem::io::needs_periodic_extension(motion, loads->time.data.front(), loads->time.data.back())) {
    motion = fem::io::periodic_extension(motion, loads->time.data.front(), loads->time.data.back());
    log::info(o.motion.string() + ": periodic (T = " + sci(*motion.period) + " s), repeated to cover the loads' times");
  }
  const auto base = fem::io::read_material_spec(o.materials);
  const ParameterSpace space = o.parameters ? read_parameter_space(*o.parameters)
                                            : ParameterSpace(default_fin_parameters(mesh), "default fin parameters");

  TargetMotion target = target_from_motion(motion, static_cast<int>(mesh.points.dim(0)), o.motion.string(),
                                           o.mesh.string());
  FinDrive drive;
  drive.loads = loads;
  if (o.loads) drive.loads_source = o.loads->string();
  drive.root_motion = motion;
  drive.motion_source = o.motion.string();
  drive.ramp = o.ramp;
  drive.frequency = motion.period && *motion.period > 0 ? 1.0 / *motion.period : 0.0;  // drive_* parameters
  // A clamp suits a structure (nodal_loads.h5, load levels); a swimming fin's root turns.
  const bool clamp = structural || o.objective == "static";
  drive.root_rotation = o.root_rotation.value_or(clamp ? fem::RootRotation::zero : fem::RootRotation::fit);
  if (!o.root_rotation && clamp) log::info("fin-fit: clamped root (no root rotation) for a structural load case");
  auto factory = std::make_shared<FinModelFactory>(mesh, base, space.names(), drive, o.mesh.string());
  FitProblem problem{space, factory, nullptr, nullptr, ""};

  std::unique_ptr<ResidualFunction>& objective = problem.objective;
  std::ostringstream what;
  if (o.objective == "quasi_static") {
    QuasiStaticOptions qs;
    qs.stress_free_base = o.stress_free_base;
    qs.inertia = o.inertia;
    qs.solve = o.increment;
    qs.reuse_reference_tangent = o.reuse_reference_tangent;
    qs.dt = o.dt > 0 ? o.dt : target.frame_spacing();
    double t_lo = target.times.front(), t_hi = target.times.back();
    if (loads) {
      t_lo = std::max(t_lo, loads->time.data.front());
      t_hi = std::min(t_hi, loads->time.data.back());
    }
    qs.instants = quasi_static_instants(o, target, qs.dt, t_lo, t_hi);
    const bool explore = o.explore_linear && qs.solve != QuasiStaticOptions::Solve::linear;
    what << "eq. (2) quasi-static increments of " << sci(qs.dt) << " s at " << qs.instants.size() << " instant(s)"
         << (qs.stress_free_base ? " from stress-free bases" : "") << (qs.inertia ? ", with inertia" : "")
         << (qs.solve == QuasiStaticOptions::Solve::linear ? ", linearised at the bases" : "")
         << (qs.solve == QuasiStaticOptions::Solve::stored ? ", converged from a stored reference" : "")
         << (explore ? ", explored linearised and polished converged" : "");
    if (explore) {
      QuasiStaticOptions linear = qs;
      linear.solve = QuasiStaticOptions::Solve::linear;
      problem.explore = std::make_unique<QuasiStaticObjective>(factory, target, linear);
    }
    objective = std::make_unique<QuasiStaticObjective>(factory, std::move(target), qs);
  } else if (o.objective == "dynamic") {
    DynamicObjectiveOptions dy;
    dy.substeps = o.substeps;
    dy.start_time = factory->start_time();
    TargetMotion compared = target;
    if (motion.period && o.periods > 0)
      compared = target.window(target.times.back() - o.periods * *motion.period + 1e-9 * target.frame_spacing(),
                               target.times.back());
    what << "eq. (1) dynamic run from rest at t = " << sci(dy.start_time) << " s, compared at "
         << compared.frame_count() << " frames";
    objective = std::make_unique<DynamicObjective>(factory, std::move(compared), dy);
  } else if (o.objective == "static") {
    if (!loads) throw InvalidInput("--objective static: needs --loads (the nodal forces of every load level)");
    StaticObjectiveOptions so;
    so.start_level = factory->start_time();
    what << "static equilibrium at " << target.frame_count() << " load level(s) from the unloaded reference";
    objective = std::make_unique<StaticObjective>(factory, std::move(target), so);
  } else {
    throw InvalidInput("--objective '" + o.objective + "': expected quasi_static, dynamic or static");
  }

  problem.description = what.str();
  return problem;
}

std::string format_misfit(const MisfitReport& m) {
  std::ostringstream os;
  os << "fin-fit evaluate: " << m.description << "\n";
  for (std::size_t i = 0; i < m.names.size(); ++i)
    os << "  " << std::left << std::setw(14) << m.names[i] << " " << std::setprecision(6)
       << m.values(static_cast<Eigen::Index>(i)) << "\n";
  os << "misfit (weighted mean distance) " << sci(m.total, 6) << " m\n";
  for (std::size_t b = 0; b < m.block_times.size(); ++b)
    os << "  t = " << std::left << std::setw(12) << std::setprecision(6) << m.block_times[b] << " "
       << sci(m.block_misfit[b], 6) << " m\n";
  return os.str();
}

std::vector<std::pair<std::string, double>> parse_parameter_values(const std::vector<std::string>& entries) {
  std::vector<std::pair<std::string, double>> at;
  for (const auto& e : entries) {
    const auto eq = e.find('=');
    double v = std::numeric_limits<double>::quiet_NaN();
    try {
      if (eq != std::string::npos) v = std::stod(e.substr(eq + 1));
    } catch (const std::exception&) {
    }
    if (eq == std::string::npos || eq == 0 || !std::isfinite(v))
      throw InvalidInput("--at '" + e + "': expected NAME=VALUE with a finite value");
    at.emplace_back(e.substr(0, eq), v);
  }
  return at;
}

MisfitReport evaluate_misfit(const FileFitOptions& o, const std::vector<std::pair<std::string, double>>& at) {
  const FitProblem problem = load_fit_problem(o);
  MisfitReport m;
  m.description = problem.description;
  m.names = problem.space.names();
  m.values = problem.factory->default_parameters();
  for (const auto& [name, value] : at) {
    const auto it = std::find(m.names.begin(), m.names.end(), name);
    if (it == m.names.end()) {
      std::string known;
      for (const auto& n : m.names) known += (known.empty() ? "" : ", ") + n;
      throw InvalidInput("--at: '" + name + "' is not a parameter of this fit (" + known + ")");
    }
    m.values(it - m.names.begin()) = value;
  }
  const Eigen::VectorXd r = problem.objective->residuals(m.values);
  const Eigen::VectorXd& w = problem.objective->sqrt_weights();
  m.total = mean_distance(r, w);
  m.block_times = problem.objective->block_times();
  const Eigen::Index blocks = static_cast<Eigen::Index>(m.block_times.size());
  if (blocks > 0 && w.size() % blocks == 0) {
    const Eigen::Index per = w.size() / blocks;
    for (Eigen::Index b = 0; b < blocks; ++b)
      m.block_misfit.push_back(mean_distance(r.segment(3 * b * per, 3 * per), w.segment(b * per, per)));
  } else {
    m.block_times.clear();
  }
  return m;
}

FitResult run_fit_from_files(const FileFitOptions& o, const nlohmann::json& config) {
  RankPool ranks;  // under mpirun: rank 0 fits, the others evaluate for it (rank_pool.hpp)
  FitProblem problem = load_fit_problem(o);
  const ParameterSpace& space = problem.space;
  const auto& factory = problem.factory;
  const ResidualFunction* objective = problem.objective.get();
  // In an MPI job every rank has read the inputs; the serving ranks now evaluate for rank 0.
  if (ranks.size() > 1) {
    ranks.set_functions({objective, problem.explore.get()});
    if (ranks.serving()) {
      ranks.serve(space);
      return {};
    }
    log::info("fin-fit: " + std::to_string(ranks.size()) + " MPI ranks evaluate, " + std::to_string(o.fit.threads) +
              " threads each");
  }

  // One evaluation at the materials file's values before any generation: an unconstrained root
  // node set, a singular model or a diverging solve is an input problem, reported as such.
  try {
    const Eigen::VectorXd r = objective->residuals(factory->default_parameters());
    log::info("fin-fit: " + problem.description + "; " + std::to_string(space.size()) + " parameters, " +
              std::to_string(objective->residual_count()) + " residuals; objective at the materials file's values " +
              sci(mean_distance(r, objective->sqrt_weights())) + " m");
  } catch (const fem::SingularMatrix& e) {
    throw InvalidInput(o.mesh.string() + ": /root_nodes: the structure is not held (" + std::string(e.what()) + ")");
  } catch (const fem::NotConverged& e) {
    // Not an input error: other parameters may converge; the optimisers score failures +inf.
    log::warn("fin-fit: the model does not converge at the materials file's values: " + std::string(e.what()));
  }

  FitOptions fo = o.fit;
  const auto user_progress = fo.progress;
  fo.progress = [&](int run, const std::string& method, const GenerationRecord& g, double eta) {
    if (user_progress) user_progress(run, method, g, eta);
    const double rate = g.wall_seconds > 0 ? g.evaluations / g.wall_seconds : 0.0;
    std::ostringstream s;
    s << "fin-fit run " << run + 1 << " (" << method << ") generation " << g.generation << ": best "
      << sci(g.best) << " m, " << std::fixed;
    s.precision(1);
    s << rate << " evaluations/s, ETA " << log::format_duration(eta);
    log::info(s.str());
  };
  // The polish is minutes on a fin (a Jacobian of n columns per step): each step is said too.
  if (!fo.polish_options.progress)
    fo.polish_options.progress = [](const std::string& line) { log::info("fin-fit polish: " + line); };
  FitResult result = run_fit(space, *objective, fo, o.objective, problem.explore.get());

  for (int i = 0; i < space.size(); ++i) {
    const bool have = result.uncertainty.identified.size() == static_cast<std::size_t>(space.size());
    if (have && !result.uncertainty.identified[i])
      log::warn("fin-fit: " + space[i].name + " is NOT identified by these data: " + result.uncertainty.verdict[i] +
                " (best " + sci(result.best_x(i)) + " " + space[i].unit + ")");
  }

  Provenance provenance{"fin-fit", config, {o.mesh, o.motion, o.materials}};
  if (o.loads) provenance.inputs.push_back(*o.loads);
  if (o.parameters) provenance.inputs.push_back(*o.parameters);
  write_materials(o.out, result, provenance);
  if (o.summary) write_text_atomic(*o.summary, fit_summary_json(result).dump(2) + "\n");
  return result;
}

}  // namespace finverse::fit::io
