// The fin's coupled flow-structure run; see fin_fsi_run.hpp.
#include "fsi/fin_fsi_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>

#include "cfd/flow/flow_solver.hpp"
#include "cfd/immersed/thin_body.hpp"
#include "cfd/immersed/time_spline.hpp"
#include "core/error.hpp"
#include "core/flow_scales.hpp"
#include "fem/coupled_structure.hpp"
#include "fem/io/fin_layout.hpp"
#include "fem/io/fin_model.hpp"
#include "fem/root_drive.hpp"
#include "fsi/acceleration_factory.hpp"
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
          {"U_m_s", U},
          {"chord_m", chord},
          {"grid", grid},
          {"cells", cells},
          {"config", config}};
}

FinFsiResult run_fin_fsi(const FinFsiInputs& in, const FinFsiOptions& o) {
  const auto wall0 = std::chrono::steady_clock::now();
  if (in.drive.has_value() == in.motion.has_value())
    throw Error("fin fsi: expected exactly one of --root-drive and --motion");
  const std::string& mn = in.mesh_name;
  fem::io::Effects effects;
  fem::FinLayout effect_layout;
  stage::Mesh shaped;  // the rest shape with the rest-shape effects
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
  const stage::Mesh& mesh = effects.empty() ? in.mesh : shaped;
  if (mesh.points.rank() != 2 || mesh.points.dim(1) != 3 || mesh.points.dim(0) < 3)
    throw Error(mn + ": /points: expected [nv, 3] with nv >= 3");
  const auto nv = static_cast<Eigen::Index>(mesh.points.dim(0));
  Eigen::Matrix3Xd X0(3, nv);
  for (Eigen::Index i = 0; i < nv; ++i)
    for (int d = 0; d < 3; ++d) X0(d, i) = mesh.points(static_cast<std::size_t>(i), static_cast<std::size_t>(d));
  std::vector<std::array<int, 3>> mid;
  for (std::size_t e = 0; e < (mesh.triangles.shape.empty() ? 0 : mesh.triangles.dim(0)); ++e)
    mid.push_back({mesh.triangles(e, 0), mesh.triangles(e, 1), mesh.triangles(e, 2)});
  double area = 0;
  for (const auto& t : mid) {
    for (int a : t)
      if (a < 0 || a >= nv) throw Error(mn + ": /triangles names node " + std::to_string(a) + " outside the mesh");
    area += 0.5 * (X0.col(t[1]) - X0.col(t[0])).cross(X0.col(t[2]) - X0.col(t[0])).norm();
  }
  if (!(area > 0)) throw Error(mn + ": /triangles: the mid-surface has no area");

  // Flow scales (as fin-cfd fin).
  const cfd::io::FinFlowOptions& fo = o.flow;
  double c = fo.chord > 0 ? fo.chord : mesh.chord.value_or(0.0);
  if (!(c > 0)) c = X0.row(0).maxCoeff() - X0.row(0).minCoeff();
  if (!(c > 0)) throw Error("fin fsi: chord: not given and the rest mesh has no x extent");
  if (!(fo.reynolds > 0)) throw Error("--reynolds: " + num(fo.reynolds) + ", expected > 0");
  if (!(fo.rho > 0)) throw Error("--rho: " + num(fo.rho) + ", expected > 0");
  const double U = fo.speed > 0 ? fo.speed : free_stream_speed(fo.reynolds, c, fo.viscosity);
  if (!(U > 0)) throw Error("--speed / --viscosity: free-stream speed " + num(U) + " m/s, expected > 0");
  const double nu = U * c / fo.reynolds;
  const double h = c / (fo.cells_per_chord > 0 ? fo.cells_per_chord : 16.0);
  if (!(o.thickness_cells > 0)) throw Error("--thickness-cells: expected > 0");
  if (!(fo.periods >= 1)) throw Error("--periods: " + num(fo.periods) + ", expected >= 1");
  if (!(fo.output_periods >= 0 && fo.output_periods <= fo.periods))
    throw Error("--output-periods: " + num(fo.output_periods) + ", expected 0 .. --periods");
  if (o.max_iterations < 1) throw Error("--max-iterations: expected >= 1");

  // Structure and root drive.
  fem::Model model;
  try {
    model = in.build_model ? in.build_model() : std::move(fem::io::build_fin_model(mesh, in.materials, mn).model);
  } catch (const std::exception& e) {
    throw Error(std::string("fin fsi: building the structure: ") + e.what());
  }
  if (model.node_count() != nv) throw Error("fin fsi: the structure has another node count than " + mn);
  double T = 0, t_start = 0, t_end = 0, t_first_output = 0, interval = fo.output_interval;
  bool periodic = true;
  Envelope env = empty_envelope();
  for (Eigen::Index i = 0; i < nv; ++i) env.add(X0.col(i));
  nlohmann::json drive_config;
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
    const stage::Motion& m = *in.motion;
    if (m.points.rank() != 3 || m.points.dim(1) != static_cast<std::size_t>(nv) || m.time.size() < 2 ||
        m.time.size() != m.points.dim(0))
      throw Error(in.motion_name + ": /points: expected [frames >= 2, " + std::to_string(nv) + ", 3] (the mesh's nodes)");
    if (m.period && !(*m.period > 0)) throw Error(in.motion_name + ": attribute T: expected > 0");
    // Without T (a motion shorter than a period, e.g. the tiny case's), the frames' span stands in
    // for the period of the ramp and of the last-period measures.
    T = m.period.value_or(m.time.data.back() - m.time(0));
    double spacing = std::numeric_limits<double>::infinity();
    for (std::size_t k = 1; k < m.time.size(); ++k) spacing = std::min(spacing, m.time(k) - m.time(k - 1));
    const cfd::PeriodicLayout layout = cfd::periodic_layout(m.time.data, m.period);
    periodic = layout.wrap.has_value();
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

  // Grid, time step, outputs.
  const cfd::StretchedGrid grid = cfd::io::fin_flow_grid(env.lo, env.hi, c, h, fo);
  if (!(fo.cfl > 0)) throw Error("--cfl: expected > 0");
  const double dt_cfl = fo.cfl * h / (U + 2 * env.max_speed);
  const long m_sub = std::max(1L, static_cast<long>(std::ceil(interval / dt_cfl - 1e-9)));
  const double dt = interval / static_cast<double>(m_sub);
  const long steps = std::lround((t_end - t_start) / dt);
  if (steps < 1) throw Error("fin fsi: the run is shorter than one time step");
  // Outputs at steps n > out_first (multiples of m_sub): the last output_periods periods, or a
  // non-periodic motion's frames.
  const long out_first = periodic ? steps - (fo.output_periods > 0 ? std::lround(fo.output_periods * T / dt) : steps)
                                  : std::lround((t_first_output - t_start) / dt) - 1;
  const long period_steps = std::min(steps, std::lround(T / dt));

  const double so_rayleigh_mass = o.rayleigh_mass >= 0 ? o.rayleigh_mass : in.materials.rayleigh_mass;
  const double so_rayleigh_stiffness = o.rayleigh_stiffness >= 0 ? o.rayleigh_stiffness : in.materials.rayleigh_stiffness;
  FinFsiResult res;
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
                {"rayleigh_mass", so_rayleigh_mass},
                {"rayleigh_stiffness", so_rayleigh_stiffness},
                {"drive", drive_config}};

  const cfd::ThinBody body = cfd::build_thin_body(mid, static_cast<int>(nv), o.thickness_cells * h, mn + " (fsi thin body)");
  cfd::FlowBoundary b;
  b[cfd::Side::XLo].type = cfd::FlowBcType::Inlet;
  b[cfd::Side::XLo].speed = U;
  if (!(o.stream_ramp_periods >= 0)) throw Error("--stream-ramp-periods: expected >= 0");
  if (o.stream_ramp_periods > 0) {
    if (std::abs(t_start) > 1e-12 * T)
      throw Error("--stream-ramp-periods: the run starts at t = " + num(t_start) + " s; the ramp needs t = 0");
    b[cfd::Side::XLo].ramp_time = o.stream_ramp_periods * T;
  }
  b[cfd::Side::XHi].type = cfd::FlowBcType::ConvectiveOutlet;
  for (cfd::Side s : {cfd::Side::YLo, cfd::Side::YHi, cfd::Side::ZLo, cfd::Side::ZHi}) b[s].type = cfd::FlowBcType::Slip;
  cfd::FlowOptions fopt;
  fopt.nu = nu;
  fopt.dt = dt;
  fopt.cfl_limit = fo.cfl_limit;
  fopt.helmholtz_rtol = 1e-8;
  fopt.poisson.rtol = fo.poisson_rtol;
  fopt.cut_cell_continuity_3d = fo.cut_cells;
  cfd::FlowSolver flow;
  flow.setup(grid, b, fopt);

  fem::CoupledStructureOptions so;
  so.dynamics.time_step = dt;
  so.dynamics.spectral_radius = o.spectral_radius;
  so.dynamics.residual_tolerance = o.structure_tolerance;
  so.dynamics.max_iterations = o.structure_max_iterations;
  so.substeps = o.substeps;
  so.dynamics.increment_tolerance = 1e-3;  // the residual decides, as the pitching plate (driven root)
  so.dynamics.rayleigh_mass = o.rayleigh_mass >= 0 ? o.rayleigh_mass : in.materials.rayleigh_mass;
  so.dynamics.rayleigh_stiffness = o.rayleigh_stiffness >= 0 ? o.rayleigh_stiffness : in.materials.rayleigh_stiffness;
  so.dim = 3;
  so.start_time = t_start;
  std::vector<int> wet(static_cast<std::size_t>(nv));
  for (int j = 0; j < nv; ++j) wet[static_cast<std::size_t>(j)] = j;
  fem::CoupledStructure structure(model, so, wet);
  structure.save();
  SurfaceFlowStructureStep step(flow, structure, body, mid, X0, fo.rho, dt, Eigen::Vector3d::Zero(), c);
  if (o.surface != "closed" && o.surface != "sheet")
    throw Error("--surface: '" + o.surface + "', expected closed or sheet");
  std::optional<cfd::SheetForcingOptions> sheet;
  if (o.surface == "sheet") {
    sheet.emplace();
    sheet->kernel = cfd::delta_kernel_from_name(fo.kernel);
    sheet->spacing = fo.marker_spacing;
  }
  try {
    step.immerse(X0, sheet);
    const double U0 = o.stream_ramp_periods > 0 ? 0.0 : U;  // a ramped stream starts from rest
    flow.initialise([U0](double, double, double, double) { return std::array<double, 3>{U0, 0, 0}; }, {}, t_start);
  } catch (const std::exception& e) {
    throw Error("fin fsi: setting up the body in the " + std::to_string(grid.nx()) + " x " + std::to_string(grid.ny()) +
                " x " + std::to_string(grid.nz()) + " grid: " + e.what());
  }

  CouplingOptions co;
  co.convergence.relative_tolerance = o.tolerance;
  co.convergence.absolute_tolerance = o.absolute_tolerance * c;
  co.max_iterations = o.max_iterations;
  co.divergence_iterations = 0;
  co.accept_at_cap = !o.strict;
  const InterfaceLayout layout = step.layout();
  ImplicitCoupling coupling(layout, Eigen::VectorXd::Zero(layout.size()), make_acceleration(o.acceleration, layout, o.omega),
                            co, t_start);

  if (o.progress)
    o.progress("fin-fsi fin: grid " + std::to_string(grid.nx()) + " x " + std::to_string(grid.ny()) + " x " +
               std::to_string(grid.nz()) + " (h = c/" + num(c / h) + "), " + std::to_string(nv) + " nodes, T = " +
               num(T) + " s, dt = T/" + std::to_string(period_steps) + ", " + std::to_string(steps) + " steps, U = " +
               num(U) + " m/s");
  const std::vector<int> tips = ray_tips(mesh);
  std::vector<double> fx, fy, tip_lo(tips.size(), 1e300), tip_hi(tips.size(), -1e300);
  std::vector<double> time, points, velocity, nodal, total, residual, relative;
  std::vector<std::int32_t> iterations;
  double it_sum = 0;
  const long every = std::max(1L, steps / 100);
  for (long n = 1; n <= steps; ++n) {
    StepStatistics st;
    try {
      st = coupling.advance(step, dt);
    } catch (const std::exception& e) {
      throw Error("fin fsi: step " + std::to_string(n) + " of " + std::to_string(steps) + " (t = " +
                  num(t_start + static_cast<double>(n) * dt) + " s): " + e.what());
    }
    const fem::DynamicState& s = structure.state();
    for (Eigen::Index i = 0; i < nv; ++i)
      if (!s.configuration.position[static_cast<std::size_t>(i)].allFinite())
        throw Error("fin fsi: step " + std::to_string(n) + ": the structure's node " + std::to_string(i) +
                    " is not finite (blow-up)");
    const SurfaceStepRecord& rec = step.records().back();
    res.transfer_mismatch = std::max(res.transfer_mismatch, rec.transfer_mismatch);
    it_sum += st.iterations;
    res.iterations_max = std::max(res.iterations_max, st.iterations);
    res.steps_at_cap += st.converged ? 0 : 1;
    if (n > steps - period_steps) {
      fx.push_back(rec.force.x());
      fy.push_back(rec.force.y());
      for (std::size_t k = 0; k < tips.size(); ++k) {
        const double y = s.configuration.position[static_cast<std::size_t>(tips[k])].y();
        tip_lo[k] = std::min(tip_lo[k], y);
        tip_hi[k] = std::max(tip_hi[k], y);
      }
    }
    if (n > out_first && n % m_sub == 0) {
      time.push_back(s.time);
      const Eigen::Matrix3Xd& loads = step.wet_loads();
      for (Eigen::Index i = 0; i < nv; ++i)
        for (int d = 0; d < 3; ++d) {
          points.push_back(s.configuration.position[static_cast<std::size_t>(i)](d));
          velocity.push_back(s.velocity(6 * i + d));
          nodal.push_back(loads(d, i));
        }
      for (int d = 0; d < 3; ++d) total.push_back(rec.force(d));
      iterations.push_back(st.iterations);
      residual.push_back(st.absolute_residual);
      relative.push_back(st.residual);
    }
    if (o.progress && (n % every == 0 || n == steps)) {
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
      const double q = 0.5 * fo.rho * U * U * area;
      double ymax = 0;  // the fin's largest lateral excursion, to see a blow-up coming
      for (Eigen::Index i = 0; i < nv; ++i)
        ymax = std::max(ymax, std::abs(s.configuration.position[static_cast<std::size_t>(i)].y()));
      o.progress("fin-fsi fin: step " + std::to_string(n) + "/" + std::to_string(steps) + " t " +
                 num(s.time, "%.5f") + " s: " + std::to_string(st.iterations) + " it, residual " +
                 num(st.residual, "%.2e") + (st.converged ? "" : " (cap)") + ", C_T " + num(-rec.force.x() / q, "%.4f") +
                 ", max |y| " + num(ymax / c, "%.3f") + " c, wall " + num(wall, "%.0f") + " s, ETA " +
                 num(wall / static_cast<double>(n) * static_cast<double>(steps - n), "%.0f") + " s");
    }
  }
  res.steps = steps;
  res.iterations_mean = it_sum / static_cast<double>(steps);

  // The last period.
  const double q = 0.5 * fo.rho * U * U * area;
  double sx = 0, peak = -1e300, ymin = 1e300, ymax = -1e300;
  for (std::size_t k = 0; k < fx.size(); ++k) {
    sx += fx[k];
    peak = std::max(peak, -fx[k] / q);
    ymin = std::min(ymin, fy[k] / q);
    ymax = std::max(ymax, fy[k] / q);
  }
  res.ct_mean = -sx / static_cast<double>(fx.size()) / q;
  res.ct_peak = peak;
  res.cl_amplitude = (ymax - ymin) / 2;
  if (!tips.empty()) {
    res.te_peak_to_peak_min = 1e300;
    for (std::size_t k = 0; k < tips.size(); ++k) {
      const double p = (tip_hi[k] - tip_lo[k]) / c;
      res.te_peak_to_peak_mean += p / static_cast<double>(tips.size());
      res.te_peak_to_peak_min = std::min(res.te_peak_to_peak_min, p);
      res.te_peak_to_peak_max = std::max(res.te_peak_to_peak_max, p);
    }
  }

  // fsi.h5.
  const std::size_t nt = time.size(), N = static_cast<std::size_t>(nv);
  if (nt == 0) throw Error("fin fsi: no output time in the run (--periods, --output-periods, --output-interval)");
  stage::Fsi& f = res.fsi;
  f.time = NdArray<double>({nt}, time);
  f.points = NdArray<double>({nt, N, 3}, points);
  f.velocity = NdArray<double>({nt, N, 3}, velocity);
  f.nodal_force = NdArray<double>({nt, N, 3}, nodal);
  f.force_total = NdArray<double>({nt, 3}, total);
  f.thrust = NdArray<double>({nt});
  f.lateral = NdArray<double>({nt});
  f.vertical = NdArray<double>({nt});
  for (std::size_t k = 0; k < nt; ++k) {
    f.thrust.data[k] = -total[3 * k] / q;
    f.lateral.data[k] = total[3 * k + 1] / q;
    f.vertical.data[k] = total[3 * k + 2] / q;
  }
  f.coupling_iterations = NdArray<std::int32_t>({nt}, iterations);
  f.coupling_residual = NdArray<double>({nt}, residual);
  f.coupling_relative_residual = NdArray<double>({nt}, relative);
  f.reference_points = NdArray<double>({N, 3});
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t d = 0; d < 3; ++d) f.reference_points.data[3 * i + d] = X0(static_cast<Eigen::Index>(d), static_cast<Eigen::Index>(i));
  f.rho = fo.rho;
  f.U = U;
  f.reference_area = area;
  if (periodic) f.period = T;
  if (!effects.empty()) f.effects = fem::effects_to_json(effects).dump();
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return res;
}

}  // namespace finverse::fsi
