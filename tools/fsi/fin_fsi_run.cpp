// The fin's coupled flow-structure run; see fin_fsi_run.hpp.
#include "fsi/fin_fsi_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <numbers>

#include "cfd/flow/flow_solver.hpp"
#include "cfd/immersed/periodic_low_pass.hpp"
#include "cfd/immersed/thin_body.hpp"
#include "cfd/immersed/time_spline.hpp"
#include "core/error.hpp"
#include "core/flow_scales.hpp"
#include "fem/coupled_structure.hpp"
#include "fem/io/fin_layout.hpp"
#include "fem/io/fin_model.hpp"
#include "fem/root_drive.hpp"
#include "fsi/acceleration_factory.hpp"
#include "fsi/coupled_run.hpp"
#include "fsi/fin_frequency_check.hpp"
#include "fsi/fsi_paraview.hpp"
#include "fsi/implicit_coupling.hpp"
#include "fsi/surface_flow_structure_step.hpp"

namespace finverse::fsi {

namespace {

std::string num(double v, const char* fmt = "%.4g") {
  char b[48];
  std::snprintf(b, sizeof b, fmt, v);
  return b;
}

struct Envelope {
  cfd::Vec3 lo{}, hi{};
  double max_speed = 0;
  void add(const Eigen::Vector3d& p) {
    for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], p(d)), hi[d] = std::max(hi[d], p(d));
  }
};

Envelope empty_envelope() {
  const double inf = std::numeric_limits<double>::infinity();
  return {{inf, inf, inf}, {-inf, -inf, -inf}, 0};
}

// A periodic motion.h5 repeated `reps` times over its wrap (its last frame dropped when it repeats
// the first).
stage::Motion tiled(const stage::Motion& m, const cfd::PeriodicLayout& layout, int reps) {
  const std::size_t frames = layout.frames, nv = m.points.dim(1), per = 3 * nv;
  const double wrap = *layout.wrap;
  stage::Motion t;
  t.period = m.period;
  t.time = NdArray<double>({frames * static_cast<std::size_t>(reps)});
  t.points = NdArray<double>({frames * static_cast<std::size_t>(reps), nv, 3});
  for (int r = 0; r < reps; ++r)
    for (std::size_t k = 0; k < frames; ++k) {
      const std::size_t q = static_cast<std::size_t>(r) * frames + k;
      t.time.data[q] = m.time.data[k] + r * wrap;
      std::copy_n(m.points.data.begin() + static_cast<std::ptrdiff_t>(k * per), per,
                  t.points.data.begin() + static_cast<std::ptrdiff_t>(q * per));
    }
  return t;
}

// The periodic motion with every node kept to its first `harmonics` harmonics of the period
// (cfd::periodic_low_pass): the root drive of a tracked motion without its frame-rate noise. A
// reconstruction's one-frame glitch (2 % c on a few nodes) jerks the prescribed root and fails the
// structure's Newton whatever the materials (docs/studies/default_case.md).
stage::Motion low_passed(const stage::Motion& m, const cfd::PeriodicLayout& layout, int harmonics,
                         const std::string& name) {
  const std::vector<double> kept = cfd::periodic_low_pass(m, layout, harmonics, name);
  stage::Motion out = m;
  std::copy(kept.begin(), kept.end(), out.points.data.begin());
  // A last frame one period after the first repeats it.
  const std::size_t per = 3 * m.points.dim(1);
  for (std::size_t k = layout.frames; k < m.time.size(); ++k)
    std::copy_n(kept.begin(), per, out.points.data.begin() + static_cast<std::ptrdiff_t>(k * per));
  return out;
}

// Each ray's tip: the beam node farthest along the ray (largest beams/s).
std::vector<int> ray_tips(const stage::Mesh& mesh) {
  std::map<int, std::pair<double, int>> tip;  // ray -> (s, node)
  const std::size_t nb = mesh.beam_elements.shape.empty() ? 0 : mesh.beam_elements.dim(0);
  for (std::size_t e = 0; e < nb; ++e)
    for (std::size_t a = 0; a < 2; ++a) {
      const int ray = mesh.beam_ray.data[e];
      const double s = mesh.beam_s(e, a);
      auto it = tip.find(ray);
      if (it == tip.end() || s > it->second.first) tip[ray] = {s, mesh.beam_elements(e, a)};
    }
  std::vector<int> nodes;
  for (const auto& [ray, sn] : tip) nodes.push_back(sn.second);
  return nodes;
}

// Everything the fin's run needs before the flow exists: the mesh (with rest-shape effects), its
// mid-surface and area, the flow scales, the driven structure, the time span, the grid and step.
struct FinSetup {
  stage::Mesh shaped;                 // the rest shape with the rest-shape effects
  const stage::Mesh* mesh = nullptr;  // the input mesh, or `shaped`
  fem::io::Effects effects;
  fem::FinLayout effect_layout;
  Eigen::Matrix3Xd X0;
  std::vector<std::array<int, 3>> mid;
  double area = 0, c = 0, U = 0, nu = 0, h = 0;
  fem::Model model;
  double T = 0, t_start = 0, t_end = 0, t_first_output = 0, interval = 0;
  bool periodic = true;
  Envelope env;
  nlohmann::json drive_config;
  cfd::StretchedGrid grid;
  long m_sub = 1, steps = 0, out_first = 0, period_steps = 0;
  double dt = 0;
  FinFsiResult result;  // the scales and the effective parameters
};

// The mesh, its mid-surface and the flow scales (as fin-cfd fin); checks the flags.
void read_mesh_and_scales(const FinFsiInputs& in, const FinFsiOptions& o, FinSetup& s) {
  if (in.drive.has_value() == in.motion.has_value())
    throw Error("fin fsi: expected exactly one of --root-drive and --motion");
  const std::string& mn = in.mesh_name;
  fem::io::Effects& effects = s.effects;
  fem::FinLayout& effect_layout = s.effect_layout;
  stage::Mesh& shaped = s.shaped;
  if (!in.effects.empty()) {
    try {
      effects = fem::make_effects(in.effects, in.effects_name);
      effect_layout = fem::io::make_fin_layout(in.mesh, mn);
      shaped = in.mesh;
      fem::io::reshape_mesh(shaped, effects, effect_layout);
    } catch (const std::exception& e) {
      throw Error(std::string("fin fsi: ") + e.what());
    }
    if (in.build_model && shaped.points.data != in.mesh.points.data)
      throw Error(in.effects_name + ": a rest-shape effect needs the structure built from the mesh (a materials file)");
  }
  s.mesh = effects.empty() ? &in.mesh : &shaped;
  const stage::Mesh& mesh = *s.mesh;
  if (mesh.points.rank() != 2 || mesh.points.dim(1) != 3 || mesh.points.dim(0) < 3)
    throw Error(mn + ": /points: expected [nv, 3] with nv >= 3");
  const auto nv = static_cast<Eigen::Index>(mesh.points.dim(0));
  Eigen::Matrix3Xd& X0 = s.X0;
  X0.resize(3, nv);
  for (Eigen::Index i = 0; i < nv; ++i)
    for (int d = 0; d < 3; ++d) X0(d, i) = mesh.points(static_cast<std::size_t>(i), static_cast<std::size_t>(d));
  std::vector<std::array<int, 3>>& mid = s.mid;
  for (std::size_t e = 0; e < (mesh.triangles.shape.empty() ? 0 : mesh.triangles.dim(0)); ++e)
    mid.push_back({mesh.triangles(e, 0), mesh.triangles(e, 1), mesh.triangles(e, 2)});
  double& area = s.area;
  for (const auto& t : mid) {
    for (int a : t)
      if (a < 0 || a >= nv) throw Error(mn + ": /triangles names node " + std::to_string(a) + " outside the mesh");
    area += 0.5 * (X0.col(t[1]) - X0.col(t[0])).cross(X0.col(t[2]) - X0.col(t[0])).norm();
  }
  if (!(area > 0)) throw Error(mn + ": /triangles: the mid-surface has no area");

  // Flow scales (as fin-cfd fin).
  const cfd::io::FinFlowOptions& fo = o.flow;
  double& c = s.c;
  c = fo.chord > 0 ? fo.chord : mesh.chord.value_or(0.0);
  if (!(c > 0)) c = X0.row(0).maxCoeff() - X0.row(0).minCoeff();
  if (!(c > 0)) throw Error("fin fsi: chord: not given and the rest mesh has no x extent");
  if (!(fo.reynolds > 0)) throw Error("--reynolds: " + num(fo.reynolds) + ", expected > 0");
  if (!(fo.rho > 0)) throw Error("--rho: " + num(fo.rho) + ", expected > 0");
  double& U = s.U;
  U = fo.speed > 0 ? fo.speed : free_stream_speed(fo.reynolds, c, fo.viscosity);
  if (!(U > 0)) throw Error("--speed / --viscosity: free-stream speed " + num(U) + " m/s, expected > 0");
  s.nu = U * c / fo.reynolds;
  s.h = c / (fo.cells_per_chord > 0 ? fo.cells_per_chord : 16.0);
  if (!(o.thickness_cells > 0)) throw Error("--thickness-cells: expected > 0");
  if (!(fo.periods >= 1)) throw Error("--periods: " + num(fo.periods) + ", expected >= 1");
  if (!(fo.output_periods >= 0 && fo.output_periods <= fo.periods))
    throw Error("--output-periods: " + num(fo.output_periods) + ", expected 0 .. --periods");
  if (o.max_iterations < 1) throw Error("--max-iterations: expected >= 1");
}

// The structure with its root drive (the analytic drive, or the tracked root motion with a smooth
// start) and candidate effects; the swept envelope and fastest node speed for the grid and step.
void drive_structure(const FinFsiInputs& in, const FinFsiOptions& o, FinSetup& s) {
  const std::string& mn = in.mesh_name;
  const cfd::io::FinFlowOptions& fo = o.flow;
  const stage::Mesh& mesh = *s.mesh;
  const Eigen::Matrix3Xd& X0 = s.X0;
  const Eigen::Index nv = X0.cols();
  const double c = s.c, U = s.U;
  fem::io::Effects& effects = s.effects;
  fem::FinLayout& effect_layout = s.effect_layout;
  fem::Model& model = s.model;
  try {
    model = in.build_model ? in.build_model() : std::move(fem::io::build_fin_model(mesh, in.materials, mn).model);
  } catch (const std::exception& e) {
    throw Error(std::string("fin fsi: building the structure: ") + e.what());
  }
  if (model.node_count() != nv) throw Error("fin fsi: the structure has another node count than " + mn);
  double &T = s.T, &t_start = s.t_start, &t_end = s.t_end, &t_first_output = s.t_first_output;
  double& interval = s.interval;
  interval = fo.output_interval;
  bool& periodic = s.periodic;
  Envelope& env = s.env;
  env = empty_envelope();
  for (Eigen::Index i = 0; i < nv; ++i) env.add(X0.col(i));
  nlohmann::json& drive_config = s.drive_config;
  if (in.drive) {
    const double f = in.drive->frequency(U, c);
    T = 1 / f;
    t_end = fo.periods * T;
    const fem::RootDrive drive = fem::io::make_root_drive(mesh, *in.drive, f, c, mn);
    drive.apply(model);
    if (!(interval > 0)) interval = T / 100;
    // The rigid fin carried by the drive, over the first whole period after the ramp.
    const double t_env = std::ceil(in.drive->ramp_periods - 1e-9) * T, eps = T * 1e-4;
    for (int k = 0; k <= 200; ++k) {
      const double t = t_env + T * k / 200.0;
      for (Eigen::Index i = 0; i < nv; ++i) {
        const Eigen::Vector3d X = X0.col(i);
        env.add(drive.rigid_position(X, t));
        env.max_speed = std::max(env.max_speed,
                                 (drive.rigid_position(X, t + eps) - drive.rigid_position(X, t - eps)).norm() / (2 * eps));
      }
    }
    drive_config = in.drive->to_json();
    drive_config["frequency_used_hz"] = f;
  } else {
    const stage::Motion& m_in = *in.motion;
    if (m_in.points.rank() != 3 || m_in.points.dim(1) != static_cast<std::size_t>(nv) || m_in.time.size() < 2 ||
        m_in.time.size() != m_in.points.dim(0))
      throw Error(in.motion_name + ": /points: expected [frames >= 2, " + std::to_string(nv) + ", 3] (the mesh's nodes)");
    if (m_in.period && !(*m_in.period > 0)) throw Error(in.motion_name + ": attribute T: expected > 0");
    // Without T (a motion shorter than a period, e.g. the tiny case's), the frames' span stands in
    // for the period of the ramp and of the last-period measures.
    T = m_in.period.value_or(m_in.time.data.back() - m_in.time(0));
    double spacing = std::numeric_limits<double>::infinity();
    for (std::size_t k = 1; k < m_in.time.size(); ++k) spacing = std::min(spacing, m_in.time(k) - m_in.time(k - 1));
    const cfd::PeriodicLayout layout = cfd::periodic_layout(m_in.time.data, m_in.period);
    periodic = layout.wrap.has_value();
    const stage::Motion m =
        o.motion_harmonics > 0 ? low_passed(m_in, layout, o.motion_harmonics, in.motion_name) : m_in;
    // A periodic motion: outputs at the frame spacing shortened to divide T; otherwise at the frames.
    if (!(interval > 0)) interval = periodic ? T / std::ceil(T / spacing - 1e-9) : spacing;
    // The ramp: a whole number of output intervals before the first frame.
    if (!(o.ramp_periods >= 0 && o.ramp_time >= 0)) throw Error("--ramp-periods, --ramp-time: expected >= 0");
    const double ramp = std::round((o.ramp_time > 0 ? o.ramp_time : o.ramp_periods * T) / interval) * interval;
    t_start = m.time(0) - ramp;
    t_first_output = m.time(0);
    t_end = periodic ? t_start + fo.periods * T : m.time.data.back();
    const stage::Motion drive =
        periodic ? tiled(m, layout, static_cast<int>(std::ceil((t_end - m.time(0)) / *layout.wrap)) + 1) : m;
    try {
      fem::io::apply_root_motion(model, mesh, drive, fem::RootRotation::per_ray, 0, in.motion_name);
    } catch (const std::exception& e) {
      throw Error(std::string("fin fsi: root motion: ") + e.what());
    }
    // The smooth start: from rest at t_start to the root's first-frame state f0 and velocity v0
    // (its first interval's slope) at t0, by the quintic Hermite blend
    //   g = f0 h(s) + v0 L k(s), s = (t - t_start) / L, h = 10s^3 - 15s^4 + 6s^5, k = -4s^3 + 7s^4 - 3s^5
    // (h, k and their first two derivatives vanish at s = 0; at s = 1, h = 1, k = 0, h' = 0, k' = 1,
    // h'' = k'' = 0), so position and velocity are continuous at both ends. A linear ramp's
    // velocity jump at t_start, or a ramp arriving at rest while the tracked root moves, stalled the
    // structure's Newton solve (tiny case: relative residual 1e-2 at the first step, 8e-2 at t0).
    const std::vector<fem::PrescribedDof> held = model.prescribed();
    const double t0 = m.time(0), d = 0.5 * (m.time(1) - m.time(0));
    for (const fem::PrescribedDof& p : held) {
      const fem::TimeFunction f = p.value;
      if (!f) continue;
      const double f0 = f(t0), v0 = (f(t0 + d) - f0) / d;
      model.prescribe(p.node, p.dof, [f, t0, ramp, f0, v0](double t) {
        if (t >= t0 || ramp <= 0) return f(t);
        if (t <= t0 - ramp) return 0.0;
        const double x = (t - (t0 - ramp)) / ramp, x3 = x * x * x;
        return f0 * x3 * (10 - 15 * x + 6 * x * x) + v0 * ramp * x3 * (-4 + 7 * x - 3 * x * x);
      });
    }
    const std::size_t nf = m.time.size();
    for (std::size_t k = 0; k < nf; ++k)
      for (Eigen::Index i = 0; i < nv; ++i) {
        const auto I = static_cast<std::size_t>(i);
        env.add(Eigen::Vector3d(m.points(k, I, 0), m.points(k, I, 1), m.points(k, I, 2)));
        if (k > 0) {
          const Eigen::Vector3d d(m.points(k, I, 0) - m.points(k - 1, I, 0), m.points(k, I, 1) - m.points(k - 1, I, 1),
                                  m.points(k, I, 2) - m.points(k - 1, I, 2));
          env.max_speed = std::max(env.max_speed, d.norm() / (m.time(k) - m.time(k - 1)));
        }
      }
    drive_config = {{"motion", in.motion_name},
                    {"root_rotation", "per_ray"},
                    {"ramp_periods", o.ramp_periods},
                    {"ramp_time_s", o.ramp_time},
                    {"periodic", periodic}};
    if (o.motion_harmonics > 0) drive_config["motion_harmonics"] = o.motion_harmonics;
  }
  if (!effects.empty()) {
    effect_layout.beat_frequency = 1 / T;
    effect_layout.start_time = in.drive ? 0.0 : t_start;
    effect_layout.ramp = in.drive ? in.drive->ramp_periods * T : t_first_output - t_start;
    try {
      fem::io::apply_effects(model, effects, effect_layout);
    } catch (const std::exception& e) {
      throw Error(in.effects_name + ": " + e.what());
    }
  }
  const long per_period = std::lround(T / interval);
  if (periodic && (per_period < 1 || std::abs(per_period * interval - T) > 1e-6 * interval))
    throw Error("--output-interval: " + num(interval) + " s does not divide the period T = " + num(T) + " s");
}

// The grid around the swept envelope, the fixed time step, the output steps and the run's
// effective parameters.
void grid_time_and_config(const FinFsiInputs& in, const FinFsiOptions& o, FinSetup& s) {
  const cfd::io::FinFlowOptions& fo = o.flow;
  const double c = s.c, U = s.U, nu = s.nu, h = s.h, T = s.T, t_start = s.t_start, t_end = s.t_end;
  const double t_first_output = s.t_first_output, interval = s.interval;
  const bool periodic = s.periodic;
  const Envelope& env = s.env;
  const nlohmann::json& drive_config = s.drive_config;
  s.grid = cfd::io::fin_flow_grid(env.lo, env.hi, c, h, fo);
  const cfd::StretchedGrid& grid = s.grid;
  if (!(fo.cfl > 0)) throw Error("--cfl: expected > 0");
  const double dt_cfl = fo.cfl * h / (U + 2 * env.max_speed);
  long& m_sub = s.m_sub;
  m_sub = std::max(1L, static_cast<long>(std::ceil(interval / dt_cfl - 1e-9)));
  s.dt = interval / static_cast<double>(m_sub);
  const double dt = s.dt;
  s.steps = std::lround((t_end - t_start) / dt);
  const long steps = s.steps;
  if (steps < 1) throw Error("fin fsi: the run is shorter than one time step");
  // Outputs at steps n > out_first (multiples of m_sub): the last output_periods periods, or a
  // non-periodic motion's frames.
  s.out_first = periodic ? steps - (fo.output_periods > 0 ? std::lround(fo.output_periods * T / dt) : steps)
                         : std::lround((t_first_output - t_start) / dt) - 1;
  s.period_steps = std::min(steps, std::lround(T / dt));

  const double so_rayleigh_mass = o.rayleigh_mass >= 0 ? o.rayleigh_mass : in.materials.rayleigh_mass;
  const double so_rayleigh_stiffness = o.rayleigh_stiffness >= 0 ? o.rayleigh_stiffness : in.materials.rayleigh_stiffness;
  FinFsiResult& res = s.result;
  res.h = h;
  res.dt = dt;
  res.period = T;
  res.frequency = 1 / T;
  res.chord = c;
  res.U = U;
  res.grid = {static_cast<long>(grid.nx()), static_cast<long>(grid.ny()), static_cast<long>(grid.nz())};
  res.cells = static_cast<long>(grid.cells());
  res.config = {{"reynolds", fo.reynolds},
                {"U_m_s", U},
                {"nu_m2_s", nu},
                {"rho", fo.rho},
                {"chord_m", c},
                {"cells_per_chord", c / h},
                {"thickness_cells", o.thickness_cells},
                {"surface", o.surface},
                {"stream_ramp_periods", o.stream_ramp_periods},
                {"core_margin", fo.core_margin},
                {"wake", fo.wake},
                {"domain", {fo.upstream, fo.downstream, fo.lateral, fo.spanwise}},
                {"stretch_ratio", fo.stretch_ratio},
                {"cfl", fo.cfl},
                {"cfl_limit", fo.cfl_limit},
                {"poisson_rtol", fo.poisson_rtol},
                {"periods", fo.periods},
                {"output_periods", fo.output_periods},
                {"output_interval_s", interval},
                {"dt_s", dt},
                {"acceleration", o.acceleration},
                {"omega0", o.omega},
                {"relative_tolerance", o.tolerance},
                {"absolute_tolerance_c", o.absolute_tolerance},
                {"max_iterations", o.max_iterations},
                {"strict", o.strict},
                {"spectral_radius", o.spectral_radius},
                {"structure_tolerance", o.structure_tolerance},
                {"structure_max_iterations", o.structure_max_iterations},
                {"substeps", o.substeps},
                {"structure_halvings", o.structure_halvings},
                {"rayleigh_mass", so_rayleigh_mass},
                {"rayleigh_stiffness", so_rayleigh_stiffness},
                {"drive", drive_config}};
  // The sheet's load option only with the sheet, so that a closed-body run's configuration stays.
  if (o.surface == "sheet") res.config["band_correction"] = o.band_correction;
}

// The fin's part of the coupled run (coupled_run.hpp): per step the force on the fin, the rays'
// tip excursions and the transfer mismatch; an fsi.h5 frame at every output step (the last
// output_periods, or a non-periodic motion's frames) with a flow snapshot when ParaView is asked.
class FinCase final : public CoupledCase {
 public:
  FinCase(const FinSetup& s, const FinFsiOptions& o, SurfaceFlowStructureStep& step,
          const fem::CoupledStructure& structure, const cfd::FlowSolver& flow, FsiOutput& output)
      : s_(s), o_(o), step_(step), structure_(structure), flow_(flow), output_(output), tips_(ray_tips(*s.mesh)) {}

  std::unique_ptr<FsiParaView> paraview;
  long frames = 0;  // fsi.h5 frames so far

  void after_step(long n, const StepStatistics& st) override {
    const fem::DynamicState& x = structure_.state();
    const Eigen::Index nv = s_.X0.cols();
    for (Eigen::Index i = 0; i < nv; ++i)
      if (!x.configuration.position[static_cast<std::size_t>(i)].allFinite())
        throw Error("the structure's node " + std::to_string(i) + " is not finite (blow-up)");
    const SurfaceStepRecord& rec = step_.records().back();
    for (int d = 0; d < 3; ++d) force_.push_back(rec.force(d));
    for (const int tip : tips_) tip_y_.push_back(x.configuration.position[static_cast<std::size_t>(tip)].y());
    mismatch_.push_back(rec.transfer_mismatch);
    if (n > s_.out_first && n % s_.m_sub == 0) {
      // The fin's nodes are all wet: its loads are the nodes' forces (no moments).
      Eigen::VectorXd nodal = Eigen::VectorXd::Zero(6 * nv);
      const Eigen::Matrix3Xd& loads = step_.wet_loads();
      for (Eigen::Index i = 0; i < nv; ++i) nodal.segment<3>(6 * i) = loads.col(i);
      output_.add(x, nodal, {rec.force(0), rec.force(1), rec.force(2)}, st.iterations, st.absolute_residual,
                  st.residual);
      ++frames;
      if (paraview) paraview->at_frame(frames, x.time, s_.dt, flow_);
    }
  }
  [[nodiscard]] RunHistory history() const override {
    return {{"force", force_}, {"tip_y", tip_y_}, {"transfer_mismatch", mismatch_}};
  }
  void restore_history(RunHistory h) override {
    const std::size_t n = h["transfer_mismatch"].size();
    if (h["force"].size() != 3 * n || h["tip_y"].size() != tips_.size() * n)
      throw Error("fin fsi: the checkpoint's per-step force and ray tips do not fit " + std::to_string(tips_.size()) +
                  " rays over " + std::to_string(n) + " steps");
    force_ = std::move(h["force"]);
    tip_y_ = std::move(h["tip_y"]);
    mismatch_ = std::move(h["transfer_mismatch"]);
    frames = static_cast<long>(output_.frames());
  }
  [[nodiscard]] std::string progress_line(long n, const StepStatistics& st) const override {
    const fem::DynamicState& x = structure_.state();
    const double q = 0.5 * o_.flow.rho * s_.U * s_.U * s_.area;
    double ymax = 0;  // the fin's largest lateral excursion, to see a blow-up coming
    for (const auto& p : x.configuration.position) ymax = std::max(ymax, std::abs(p.y()));
    return "fin-fsi fin: step " + std::to_string(n) + "/" + std::to_string(s_.steps) + " t " + num(x.time, "%.5f") +
           " s: " + std::to_string(st.iterations) + " it, residual " + num(st.residual, "%.2e") +
           (st.converged ? "" : " (cap)") + ", C_T " + num(-force_[force_.size() - 3] / q, "%.4f") + ", max |y| " +
           num(ymax / s_.c, "%.3f") + " c";
  }

  // The last period's (its steps') thrust, lateral force and the rays' tip excursions.
  void last_period(FinFsiResult& res) const {
    const double q = 0.5 * o_.flow.rho * s_.U * s_.U * s_.area;
    const std::size_t steps = mismatch_.size(), first = steps - static_cast<std::size_t>(s_.period_steps);
    double sx = 0, peak = -1e300, ymin = 1e300, ymax = -1e300;
    std::vector<double> lo(tips_.size(), 1e300), hi(tips_.size(), -1e300);
    for (std::size_t k = first; k < steps; ++k) {
      const double fx = force_[3 * k], fy = force_[3 * k + 1];
      sx += fx;
      peak = std::max(peak, -fx / q);
      ymin = std::min(ymin, fy / q);
      ymax = std::max(ymax, fy / q);
      for (std::size_t r = 0; r < tips_.size(); ++r) {
        lo[r] = std::min(lo[r], tip_y_[k * tips_.size() + r]);
        hi[r] = std::max(hi[r], tip_y_[k * tips_.size() + r]);
      }
    }
    res.ct_mean = -sx / static_cast<double>(steps - first) / q;
    res.ct_peak = peak;
    res.cl_amplitude = (ymax - ymin) / 2;
    if (!tips_.empty()) {
      res.te_peak_to_peak_min = 1e300;
      for (std::size_t r = 0; r < tips_.size(); ++r) {
        const double p = (hi[r] - lo[r]) / s_.c;
        res.te_peak_to_peak_mean += p / static_cast<double>(tips_.size());
        res.te_peak_to_peak_min = std::min(res.te_peak_to_peak_min, p);
        res.te_peak_to_peak_max = std::max(res.te_peak_to_peak_max, p);
      }
    }
    for (const double m : mismatch_) res.transfer_mismatch = std::max(res.transfer_mismatch, m);
  }

 private:
  const FinSetup& s_;
  const FinFsiOptions& o_;
  SurfaceFlowStructureStep& step_;
  const fem::CoupledStructure& structure_;
  const cfd::FlowSolver& flow_;
  FsiOutput& output_;
  std::vector<int> tips_;
  std::vector<double> force_, tip_y_, mismatch_;  // per step: 3, tips, 1
};

// The flow: inlet (impulsive, or ramped from rest), convective outlet, slip sides.
cfd::FlowBoundary fin_boundary(const FinFsiOptions& o, const FinSetup& s) {
  cfd::FlowBoundary b;
  b[cfd::Side::XLo].type = cfd::FlowBcType::Inlet;
  b[cfd::Side::XLo].speed = s.U;
  if (!(o.stream_ramp_periods >= 0)) throw Error("--stream-ramp-periods: expected >= 0");
  if (o.stream_ramp_periods > 0) {
    if (std::abs(s.t_start) > 1e-12 * s.T)
      throw Error("--stream-ramp-periods: the run starts at t = " + num(s.t_start) + " s; the ramp needs t = 0");
    b[cfd::Side::XLo].ramp_time = o.stream_ramp_periods * s.T;
  }
  b[cfd::Side::XHi].type = cfd::FlowBcType::ConvectiveOutlet;
  for (cfd::Side side : {cfd::Side::YLo, cfd::Side::YHi, cfd::Side::ZLo, cfd::Side::ZHi})
    b[side].type = cfd::FlowBcType::Slip;
  return b;
}

fem::CoupledStructureOptions structure_options(const FinFsiInputs& in, const FinFsiOptions& o, const FinSetup& s) {
  fem::CoupledStructureOptions so;
  so.dynamics.time_step = s.dt;
  so.dynamics.spectral_radius = o.spectral_radius;
  so.dynamics.residual_tolerance = o.structure_tolerance;
  so.dynamics.max_iterations = o.structure_max_iterations;
  so.substeps = o.substeps;
  so.max_halvings = o.structure_halvings;
  so.dynamics.increment_tolerance = 1e-3;  // the residual decides, as the pitching plate (driven root)
  so.dynamics.rayleigh_mass = o.rayleigh_mass >= 0 ? o.rayleigh_mass : in.materials.rayleigh_mass;
  so.dynamics.rayleigh_stiffness = o.rayleigh_stiffness >= 0 ? o.rayleigh_stiffness : in.materials.rayleigh_stiffness;
  so.dim = 3;
  so.start_time = s.t_start;
  return so;
}

// fsi.h5's arrays from the run's frames, with the period and the effects.
stage::Fsi fin_fsi_file(const FsiOutput& output, const FinSetup& s) {
  if (output.frames() == 0)
    throw Error("fin fsi: no output time in the run (--periods, --output-periods, --output-interval)");
  stage::Fsi f = output.to_stage();
  if (s.periodic) f.period = s.T;
  if (!s.effects.empty()) f.effects = fem::effects_to_json(s.effects).dump();
  return f;
}

}  // namespace

nlohmann::json FinFsiResult::summary() const {
  return {{"ct_mean_last_period", ct_mean},
          {"ct_peak_last_period", ct_peak},
          {"cl_amplitude_last_period", cl_amplitude},
          {"te_peak_to_peak_over_chord_mean", te_peak_to_peak_mean},
          {"te_peak_to_peak_over_chord_min", te_peak_to_peak_min},
          {"te_peak_to_peak_over_chord_max", te_peak_to_peak_max},
          {"coupling_iterations_mean", iterations_mean},
          {"coupling_iterations_max", iterations_max},
          {"steps", steps},
          {"steps_at_cap", steps_at_cap},
          {"transfer_mismatch_max", transfer_mismatch},
          {"wall_seconds", wall_seconds},
          {"h_m", h},
          {"dt_s", dt},
          {"T_s", period},
          {"frequency_hz", frequency},
          {"first_frequency_vacuum_hz", first_frequency_vacuum},
          {"first_frequency_wet_hz", first_frequency_wet},
          {"first_frequency_ratio", first_frequency_ratio},
          {"U_m_s", U},
          {"chord_m", chord},
          {"grid", grid},
          {"cells", cells},
          {"config", config}};
}

// The fin's first natural frequency in water against the flapping frequency: materials the coupled
// run cannot carry are refused here, in one line, before any step (issue 50; the threshold's
// measurements: docs/studies/default_case.md, "The soft corner").
void check_frequency(const FinFsiInputs& in, const FinFsiOptions& o, FinSetup& s) {
  if (!(o.min_frequency_ratio >= 0)) throw Error("--min-frequency-ratio: expected >= 0");
  // A motion without a period (attribute T) has no flapping frequency: its frames' span stands in
  // for T elsewhere, but a ratio to it would mean nothing.
  const bool flapping = in.drive.has_value() || s.periodic;
  if (!flapping && o.min_frequency_ratio > 0)
    throw Error("--min-frequency-ratio: " + in.motion_name + " is not periodic (no attribute T), so it has no flapping "
                "frequency to compare with; give 0");
  FinFrequencies f;
  try {
    f = fin_frequencies(s.model, s.area, s.c, o.flow.rho, 1 / s.T);
  } catch (const std::exception& e) {
    // Without a refusal asked for, the frequencies only inform: the run goes on without them.
    if (o.min_frequency_ratio > 0) throw Error(in.materials_name + ": the fin's first natural frequency: " + e.what());
    return;
  }
  FinFsiResult& res = s.result;
  res.first_frequency_vacuum = f.vacuum_hz;
  res.first_frequency_wet = f.wet_hz;
  res.first_frequency_ratio = flapping ? f.ratio : 0;
  if (f.ratio < o.min_frequency_ratio)
    throw Error(in.materials_name + ": the fin's first natural frequency in water, about " + num(f.wet_hz) +
                " Hz (" + num(f.vacuum_hz) + " Hz in vacuo), is " + num(f.ratio) + " times the flapping frequency " +
                num(1 / s.T) + " Hz; the coupled run fails below " + num(o.min_frequency_ratio) +
                " (docs/studies/default_case.md, \"The soft corner\"); --min-frequency-ratio 0 runs it anyway");
}

FinFsiResult run_fin_fsi(const FinFsiInputs& in, const FinFsiOptions& o) {
  const auto wall0 = std::chrono::steady_clock::now();
  FinSetup s;
  read_mesh_and_scales(in, o, s);
  drive_structure(in, o, s);
  check_frequency(in, o, s);
  grid_time_and_config(in, o, s);
  const cfd::io::FinFlowOptions& fo = o.flow;
  const Eigen::Index nv = s.X0.cols();

  // Set up: flow, structure, the coupled step around the fin's mid-surface, the coupling.
  const cfd::ThinBody body =
      cfd::build_thin_body(s.mid, static_cast<int>(nv), o.thickness_cells * s.h, in.mesh_name + " (fsi thin body)");
  cfd::FlowOptions fopt;
  fopt.nu = s.nu;
  fopt.dt = s.dt;
  fopt.cfl_limit = fo.cfl_limit;
  fopt.helmholtz_rtol = 1e-8;
  fopt.poisson.rtol = fo.poisson_rtol;
  fopt.cut_cell_continuity_3d = fo.cut_cells;
  cfd::FlowSolver flow;
  flow.setup(s.grid, fin_boundary(o, s), fopt);
  std::vector<int> wet(static_cast<std::size_t>(nv));
  for (int j = 0; j < nv; ++j) wet[static_cast<std::size_t>(j)] = j;
  fem::CoupledStructure structure(s.model, structure_options(in, o, s), wet);
  structure.save();
  SurfaceFlowStructureStep step(flow, structure, body, s.mid, s.X0, fo.rho, s.dt, Eigen::Vector3d::Zero(), s.c);
  if (o.surface != "closed" && o.surface != "sheet")
    throw Error("--surface: '" + o.surface + "', expected closed or sheet");
  std::optional<cfd::SheetForcingOptions> sheet;
  if (o.surface == "sheet") {
    sheet.emplace();
    sheet->kernel = cfd::delta_kernel_from_name(fo.kernel);
    sheet->spacing = fo.marker_spacing;
    sheet->band_correction = o.band_correction;
  }
  try {
    step.immerse(s.X0, sheet);
    const double U0 = o.stream_ramp_periods > 0 ? 0.0 : s.U;  // a ramped stream starts from rest
    flow.initialise([U0](double, double, double, double) { return std::array<double, 3>{U0, 0, 0}; }, {}, s.t_start);
  } catch (const std::exception& e) {
    throw Error("fin fsi: setting up the body in the " + std::to_string(s.grid.nx()) + " x " +
                std::to_string(s.grid.ny()) + " x " + std::to_string(s.grid.nz()) + " grid: " + e.what());
  }
  const CouplingOptions co =
      immersed_coupling_options(o.tolerance, o.absolute_tolerance * s.c, o.max_iterations, o.strict);
  const InterfaceLayout layout = step.layout();
  ImplicitCoupling coupling(layout, Eigen::VectorXd::Zero(layout.size()),
                            make_acceleration(o.acceleration, layout, o.omega), co, s.t_start);

  // The run: restart, steps, checkpoints (coupled_run.hpp).
  std::vector<Eigen::Vector3d> reference(static_cast<std::size_t>(nv));
  for (Eigen::Index i = 0; i < nv; ++i) reference[static_cast<std::size_t>(i)] = s.X0.col(i);
  FsiOutput output(reference, {}, fo.rho, s.U, s.area);
  CoupledRunOptions ro;
  ro.name = "fin fsi";
  ro.steps = s.steps;
  ro.dt = s.dt;
  ro.checkpoint = o.checkpoint;
  ro.checkpoint_every = o.checkpoint_every;
  ro.restart = o.restart;
  // A stopped or failed run may continue with other iteration settings (the state does not depend
  // on them); the model, the grid and the step may not change.
  ro.may_differ = {"acceleration",       "omega0",  "relative_tolerance",  "absolute_tolerance_c",
                   "max_iterations",     "strict",  "structure_tolerance", "structure_max_iterations",
                   "structure_halvings", "substeps"};
  ro.progress = o.progress;
  ro.warm_start_repeats = !o.cold_repeats;
  FinFsiResult& res = s.result;
  CoupledRun run(flow, structure, step, coupling, output, res.config, ro);
  FinCase fin(s, o, step, structure, flow, output);
  const long first = run.restart(fin);
  if (!o.paraview_dir.empty())
    fin.paraview = std::make_unique<FsiParaView>(o.paraview_dir, o.paraview_every, first > 0);
  if (o.progress)
    o.progress("fin-fsi fin: grid " + std::to_string(s.grid.nx()) + " x " + std::to_string(s.grid.ny()) + " x " +
               std::to_string(s.grid.nz()) + " (h = c/" + num(s.c / s.h) + "), " + std::to_string(nv) +
               " nodes, T = " + num(s.T) + " s, dt = T/" + std::to_string(s.period_steps) + ", " +
               std::to_string(s.steps) + " steps, U = " + num(s.U) + " m/s" +
               (first > 0 ? ", restarted after step " + std::to_string(first) : ""));
  run.run(fin);

  // Results: the last period, the coupling's statistics, fsi.h5, the structure's ParaView series.
  res.steps = s.steps;
  double it_sum = 0;
  for (const StepStatistics& st : run.statistics()) {
    it_sum += st.iterations;
    res.iterations_max = std::max(res.iterations_max, st.iterations);
    res.steps_at_cap += st.converged ? 0 : 1;
  }
  res.iterations_mean = it_sum / static_cast<double>(s.steps);
  fin.last_period(res);
  res.fsi = fin_fsi_file(output, s);
  if (fin.paraview) {
    std::vector<std::int32_t> tri;
    for (const auto& t : s.mid) tri.insert(tri.end(), t.begin(), t.end());
    fin.paraview->write_structure(NdArray<std::int32_t>({s.mid.size(), 3}, tri), reference, output);
  }
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return res;
}

}  // namespace finverse::fsi
