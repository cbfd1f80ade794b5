// The flexible pitching plate: set-up, runs and grading; see pitching_plate_fsi.hpp.
#include "fsi/validation/pitching_plate_fsi.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>

#include "cfd/flow/flow_solver.hpp"
#include "cfd/validation/case_support.hpp"
#include "core/error.hpp"
#include "core/printf_format.hpp"
#include "fem/coupled_structure.hpp"
#include "fem/modal.hpp"
#include "fem/validation/hybrid_plate_model.hpp"
#include "fsi/coupled_run.hpp"
#include "fsi/surface_flow_structure_step.hpp"
#include "fsi/validation/turek_hron_fsi.hpp"

namespace finverse::fsi::validation {

namespace {

constexpr double pi = std::numbers::pi;

void check(const PitchingPlateOptions& o) {
  if (!(o.re > 0 && o.aspect > 0 && o.pitch_amplitude_deg > 0 && o.frequency > 0 && o.mass_ratio > 0 &&
        o.shell_thickness > 0 && o.poisson_ratio >= 0 && o.poisson_ratio < 0.5))
    throw Error("pitching plate: re, aspect, pitch amplitude, frequency, mass ratio, shell thickness must be > 0, "
                "0 <= nu < 0.5");
  if (o.nx < 2 || o.nz < 2 || o.nz % 2 != 0) throw Error("pitching plate: expected nx >= 2 and an even nz >= 2");
  if (o.cells_per_chord < 8 || !(o.thickness_cells > 0) || !(o.stretch_ratio >= 1))
    throw Error("pitching plate: expected cells_per_chord >= 8, thickness_cells > 0, stretch_ratio >= 1");
  if (o.steps_per_period < 8 || o.ramp_periods < 1 || o.periods <= o.ramp_periods)
    throw Error("pitching plate: expected steps_per_period >= 8, ramp_periods >= 1 and periods > ramp_periods");
  if (o.max_iterations < 1) throw Error("pitching plate: expected max_iterations >= 1");
  for (double k : o.stiffness)
    if (!(k > 0)) throw Error("pitching plate: every K must be > 0 (got " + printf_format("%g", k) + ")");
}

// alpha(t) with the ramp, and its first two derivatives.
struct Pitch {
  double a = 0, da = 0, dda = 0;
};
Pitch pitch(const PitchingPlateOptions& o, double t) {
  const double w = 2 * pi * o.frequency, a0 = o.pitch_amplitude_deg * pi / 180;
  const auto [r, dr, ddr] = cfd::validation::cosine_ramp(t, o.ramp_periods / o.frequency);
  const double s = std::sin(w * t), c = std::cos(w * t);
  return {a0 * r * s, a0 * (dr * s + r * w * c), a0 * (ddr * s + 2 * dr * w * c - r * w * w * s)};
}

int node(const PitchingPlateOptions& o, int i, int k) { return k * (o.nx + 1) + i; }

// The mid-surface triangles of build_hybrid_plate's grid (x fastest, rows along z).
std::vector<std::array<int, 3>> mid_triangles(const PitchingPlateOptions& o) {
  std::vector<std::array<int, 3>> tri;
  for (int k = 0; k < o.nz; ++k)
    for (int i = 0; i < o.nx; ++i) {
      const int a = node(o, i, k), b = node(o, i + 1, k), c = node(o, i + 1, k + 1), d = node(o, i, k + 1);
      if ((i + k) % 2 == 0) {
        tri.push_back({a, b, c});
        tri.push_back({a, c, d});
      } else {
        tri.push_back({a, b, d});
        tri.push_back({b, c, d});
      }
    }
  return tri;
}

// The shell plate with K = D / (rho_f U^2 L^3) (rho_f = U = L = 1), leading edge turned by -alpha.
fem::validation::HybridPlateModel plate_model(const PitchingPlateOptions& o, double k) {
  fem::validation::HybridPlateCase c;
  c.chord = 1;
  c.span = o.aspect;
  c.thickness = o.shell_thickness;
  const double h = o.shell_thickness, nu = o.poisson_ratio;
  c.plate = {"plate", 12 * (1 - nu * nu) * k / (h * h * h), nu, o.mass_ratio / h};
  fem::validation::HybridPlateModel m = fem::validation::build_hybrid_plate(c, o.nx, o.nz,
                                                                            fem::validation::HybridPlateLoad::none);
  for (int n : m.leading_edge) m.model.prescribe(n, 5, [o](double t) { return -pitch(o, t).a; });
  const auto& X = m.model.reference_positions();
  for (int kk = 0; kk <= o.nz; ++kk)
    for (int i = 0; i <= o.nx; ++i) {
      const fem::Vec3 p = X[static_cast<std::size_t>(node(o, i, kk))];
      if (std::abs(p.x() - static_cast<double>(i) / o.nx) > 1e-12 || std::abs(p.z() - o.aspect * (static_cast<double>(kk) / o.nz - 0.5)) > 1e-12)
        throw Error("pitching plate: the plate builder's node numbering is not the grid's (x fastest)");
    }
  return m;
}

// First Fourier coefficient of one whole period of equally spaced samples.
std::complex<double> fundamental(const std::vector<double>& v, std::size_t first, std::size_t n) {
  std::complex<double> s = 0;
  for (std::size_t q = 0; q < n; ++q)
    s += v[first + q] * std::polar(1.0, -2 * pi * static_cast<double>(q) / static_cast<double>(n));
  return 2.0 * s / static_cast<double>(n);
}

}  // namespace

PitchingPlateModes pitching_plate_modes(const PitchingPlateOptions& o) {
  check(o);
  const fem::validation::HybridPlateModel m = plate_model(o, 1.0);
  fem::ModalOptions mo;
  mo.modes = 3;
  const fem::ModalResult r = fem::modal_analysis(m.model, m.model.reference_state(), mo);
  PitchingPlateModes p;
  p.dry_per_sqrt_k = r.frequency(0);
  p.added_mass_ratio = pi * o.aspect / (4 * o.mass_ratio);
  p.wet_per_sqrt_k = p.dry_per_sqrt_k / std::sqrt(1 + p.added_mass_ratio);
  p.resonant_stiffness = std::pow(o.frequency / p.wet_per_sqrt_k, 2);
  return p;
}

namespace {

// Over the last period: the trailing edge's amplitude and phase against the rigid plate's, the
// mean thrust and the lift's fundamental.
void measure_last_period(const PitchingPlateOptions& o, long steps, const std::vector<double>& fx,
                         const std::vector<double>& fy, const std::vector<double>& rigid_te,
                         PitchingPlateCaseResult& res) {
  const auto N = static_cast<std::size_t>(o.steps_per_period), first = static_cast<std::size_t>(steps) - N;
  const auto [lo, hi] = std::minmax_element(res.te_y.begin() + static_cast<long>(first), res.te_y.end());
  res.amplitude = (*hi - *lo) / 2;
  const std::complex<double> y1 = fundamental(res.te_y, first, N), r1 = fundamental(rigid_te, first, N);
  res.phase_deg = std::arg(y1 / r1) * 180 / pi;
  const double q = 0.5 * o.aspect;  // rho U^2 L W / 2
  double mean_fx = 0;
  for (std::size_t k = first; k < first + N; ++k) mean_fx += fx[k];
  res.mean_thrust = -mean_fx / static_cast<double>(N) / q;
  res.lift_amplitude = std::abs(fundamental(fy, first, N)) / q;
}

// The rigid plate: the flow alone around the prescribed rigid motion, the force from the surface
// traction (or the sheet's markers) after every step.
void run_rigid_plate(
    const PitchingPlateOptions& o, cfd::FlowSolver& flow, SurfaceFlowStructureStep& step, long steps, double dt, int te,
    const std::string& tag,
    const std::function<void(double, Eigen::Matrix3Xd&, Eigen::Matrix3Xd&, Eigen::Matrix3Xd&)>& rigid_nodes,
    std::vector<double>& fx, std::vector<double>& fy, std::vector<double>& rigid_te, PitchingPlateCaseResult& res) {
  for (long s = 1; s <= steps; ++s) {
    const double t = static_cast<double>(s) * dt;
    Eigen::Matrix3Xd x, v, a;
    rigid_nodes(t, x, v, a);
    rigid_te.push_back(x(1, te));
    try {
      step.place(x, v, a);
      flow.step();
    } catch (const std::exception& e) {
      throw Error("pitching plate (" + tag + "), step " + std::to_string(s) + ": flow: " + e.what());
    }
    const SurfaceLoadTransfer tr = step.transfer(x);
    res.transfer_mismatch = std::max(res.transfer_mismatch, tr.mismatch(1.0));
    fx.push_back(tr.flow_force.x());
    fy.push_back(tr.flow_force.y());
    res.te_y.push_back(x(1, te));
    res.time.push_back(t);
    res.coupling_iterations_max = 1;
    if (o.progress)
      o.progress(tag + ": step " + std::to_string(s) + " t " + printf_format("%.4f", t) + ": F (" +
                 printf_format("%.4f", fx.back()) + ", " + printf_format("%.4f", fy.back()) + "), y_TE " +
                 printf_format("%.4f", res.te_y.back()));
  }
}

// The flexible plate's part of the coupled run (coupled_run.hpp): per step the force, the
// mid-span trailing edge and, for the phase, where the rigid plate's would be.
class PlateCase final : public CoupledCase {
 public:
  PlateCase(const SurfaceFlowStructureStep& step, const fem::CoupledStructure& structure, int te, double dt,
            std::string tag, std::function<double(double)> rigid_te_at)
      : step_(step),
        structure_(structure),
        te_(te),
        dt_(dt),
        tag_(std::move(tag)),
        rigid_te_at_(std::move(rigid_te_at)) {}

  std::vector<double> fx, fy, te_y, rigid_te, time;
  double mismatch = 0;

  void after_step(long n, const StepStatistics&) override {
    const SurfaceStepRecord& rec = step_.records().back();
    const double t = static_cast<double>(n) * dt_;
    fx.push_back(rec.force.x());
    fy.push_back(rec.force.y());
    te_y.push_back(structure_.state().configuration.position[static_cast<std::size_t>(te_)].y());
    rigid_te.push_back(rigid_te_at_(t));
    time.push_back(t);
    mismatch = std::max(mismatch, rec.transfer_mismatch);
  }
  [[nodiscard]] RunHistory history() const override {
    return {{"fx", fx}, {"fy", fy}, {"te_y", te_y}, {"rigid_te", rigid_te}, {"time", time}};
  }
  void restore_history(RunHistory h) override {
    fx = std::move(h["fx"]);
    fy = std::move(h["fy"]);
    te_y = std::move(h["te_y"]);
    rigid_te = std::move(h["rigid_te"]);
    time = std::move(h["time"]);
  }
  [[nodiscard]] std::string progress_line(long n, const StepStatistics& st) const override {
    return tag_ + ": step " + std::to_string(n) + " t " + printf_format("%.4f", time.back()) + ": " +
           std::to_string(st.iterations) + " it, residual " + printf_format("%.2e", st.residual) + ", F (" +
           printf_format("%.4f", fx.back()) + ", " + printf_format("%.4f", fy.back()) + "), y_TE " +
           printf_format("%.4f", te_y.back()) + " (rigid " + printf_format("%.4f", rigid_te.back()) + ")";
  }

 private:
  const SurfaceFlowStructureStep& step_;
  const fem::CoupledStructure& structure_;
  int te_;
  double dt_;
  std::string tag_;
  std::function<double(double)> rigid_te_at_;
};

}  // namespace

PitchingPlateCaseResult run_pitching_plate_case(const PitchingPlateOptions& o, double stiffness, bool rigid) {
  check(o);
  const auto wall0 = std::chrono::steady_clock::now();
  const double W = o.aspect, h = 1.0 / o.cells_per_chord, thickness = o.thickness_cells * h;
  const double T = 1 / o.frequency, dt = T / o.steps_per_period;
  const long steps = static_cast<long>(o.steps_per_period) * o.periods;

  // Mid-surface and its closed thin body.
  const std::vector<std::array<int, 3>> mid = mid_triangles(o);
  const int n = (o.nx + 1) * (o.nz + 1);
  Eigen::Matrix3Xd X0(3, n);
  for (int k = 0; k <= o.nz; ++k)
    for (int i = 0; i <= o.nx; ++i) X0.col(node(o, i, k)) = Eigen::Vector3d(static_cast<double>(i) / o.nx, 0, W * (static_cast<double>(k) / o.nz - 0.5));
  const cfd::ThinBody body = cfd::build_thin_body(mid, n, thickness, "pitching plate");

  // Flow: stream U = 1 along x; the side walls slide with it (no boundary layers of their own).
  using cfd::validation::multigrid_axis;
  const double margin = 2 * thickness + 2 * h;
  const cfd::Axis ax = multigrid_axis(-o.upstream, 1 + o.downstream, -margin, 1 + margin, h, o.stretch_ratio);
  const cfd::Axis ay = multigrid_axis(-o.half_height, o.half_height, -o.box_half_height, o.box_half_height, h,
                                      o.stretch_ratio);
  const cfd::Axis az = multigrid_axis(-o.half_width, o.half_width, -W / 2 - margin, W / 2 + margin, h,
                                      o.stretch_ratio);
  const cfd::StretchedGrid grid(ax, ay, az);
  cfd::FlowOptions fo;
  fo.nu = 1 / o.re;
  fo.dt = dt;
  fo.helmholtz_rtol = 1e-10;
  fo.poisson.rtol = 1e-9;
  fo.cut_cell_continuity_3d = true;  // as fin-cfd fin (docs/studies/cut_cell_balance.md)
  cfd::FlowBoundary b;
  b[cfd::Side::XLo].type = cfd::FlowBcType::Inlet;
  b[cfd::Side::XLo].speed = 1.0;
  b[cfd::Side::XHi].type = cfd::FlowBcType::ConvectiveOutlet;
  for (cfd::Side s : {cfd::Side::YLo, cfd::Side::YHi, cfd::Side::ZLo, cfd::Side::ZHi}) b[s].wall_velocity = {1, 0, 0};
  cfd::FlowSolver flow;
  flow.setup(grid, b, fo);
  const Eigen::Matrix3Xd zero = Eigen::Matrix3Xd::Zero(3, n);

  PitchingPlateCaseResult res;
  res.stiffness = rigid ? 0 : stiffness;
  res.rigid = rigid;
  res.flow_cells = static_cast<long>(grid.cells());
  const int te = node(o, o.nx, o.nz / 2);  // mid-span trailing edge
  std::vector<double> fx, fy, rigid_te;
  double it_sum = 0;

  // The rigid plate at alpha: rotation by -alpha about z through the leading edge.
  const auto rigid_nodes = [&](double t, Eigen::Matrix3Xd& x, Eigen::Matrix3Xd& v, Eigen::Matrix3Xd& a) {
    const Pitch p = pitch(o, t);
    const double c = std::cos(p.a), s = std::sin(p.a);
    x = X0;
    v = a = zero;
    for (int j = 0; j < n; ++j) {
      const double r = X0(0, j);
      x(0, j) = r * c;
      x(1, j) = -r * s;
      v(0, j) = -r * s * p.da;
      v(1, j) = -r * c * p.da;
      a(0, j) = -r * (c * p.da * p.da + s * p.dda);
      a(1, j) = -r * (-s * p.da * p.da + c * p.dda);
    }
  };

  // The structure (unused by the rigid run, which needs its step only to place the body).
  fem::validation::HybridPlateModel pm = plate_model(o, rigid ? 1.0 : stiffness);
  fem::CoupledStructureOptions so;
  so.dynamics.time_step = dt;
  so.dynamics.spectral_radius = o.spectral_radius;
  so.dynamics.residual_tolerance = o.structure_tolerance;
  // The residual decides: the increment test is relative to the step's increment of the free
  // DOFs, and Newton's last increments of a stiff plate carried by the prescribed rotation stall
  // at 1e-6 .. 1e-7 of it (measured, K = 50, dt = T/16) while the residual is at 1e-8.
  so.dynamics.increment_tolerance = 1e-3;
  so.dim = 3;
  std::vector<int> wet(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) wet[static_cast<std::size_t>(j)] = j;
  fem::CoupledStructure structure(pm.model, so, wet);
  structure.save();
  SurfaceFlowStructureStep step(flow, structure, body, mid, X0, 1.0, dt, Eigen::Vector3d::Zero(), 1.0);
  std::optional<cfd::SheetForcingOptions> sheet;
  if (o.surface == "sheet") {
    sheet.emplace();
    sheet->band_correction = o.band_correction;
  }
  step.immerse(X0, sheet);
  flow.initialise([](double, double, double, double) { return std::array<double, 3>{1, 0, 0}; });

  const CouplingOptions co = immersed_coupling_options(o.tolerance, o.absolute_tolerance, o.max_iterations);
  const InterfaceLayout layout = step.layout();
  ImplicitCoupling coupling(layout, Eigen::VectorXd::Zero(layout.size()),
                            make_acceleration(o.acceleration, layout, o.omega), co);
  const std::string tag = rigid ? std::string("rigid") : "K " + printf_format("%g", stiffness);
  if (rigid) {
    run_rigid_plate(o, flow, step, steps, dt, te, tag, rigid_nodes, fx, fy, rigid_te, res);
    it_sum = static_cast<double>(steps);
  } else {
    // The coupled run every case uses (coupled_run.hpp); no fsi.h5 here.
    std::vector<Eigen::Vector3d> reference(static_cast<std::size_t>(n));
    for (int j = 0; j < n; ++j) reference[static_cast<std::size_t>(j)] = X0.col(j);
    FsiOutput output(reference, {}, 1.0, 1.0, W);
    CoupledRunOptions ro;
    ro.name = "pitching plate (" + tag + ")";
    ro.steps = steps;
    ro.dt = dt;
    ro.progress = o.progress;
    CoupledRun run(flow, structure, step, coupling, output, nlohmann::json::object(), ro);
    PlateCase plate(step, structure, te, dt, tag, [&](double t) {
      Eigen::Matrix3Xd x, v, a;
      rigid_nodes(t, x, v, a);
      return x(1, te);
    });
    run.run(plate);
    for (const StepStatistics& st : run.statistics()) {
      it_sum += st.iterations;
      res.coupling_iterations_max = std::max(res.coupling_iterations_max, static_cast<double>(st.iterations));
      res.steps_at_cap += st.converged ? 0 : 1;
    }
    fx = plate.fx;
    fy = plate.fy;
    rigid_te = plate.rigid_te;
    res.te_y = plate.te_y;
    res.time = plate.time;
    res.transfer_mismatch = plate.mismatch;
  }
  res.coupling_iterations_mean = it_sum / static_cast<double>(steps);

  measure_last_period(o, steps, fx, fy, rigid_te, res);
  res.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return res;
}

PitchingPlateRun run_pitching_plate(const PitchingPlateOptions& o) {
  check(o);
  const auto wall0 = std::chrono::steady_clock::now();
  PitchingPlateRun run;
  run.modes = pitching_plate_modes(o);
  std::vector<double> ks = o.stiffness;
  std::sort(ks.begin(), ks.end());
  ks.erase(std::unique(ks.begin(), ks.end()), ks.end());
  const auto one = [&](double k, bool rigid) {
    try {
      run.cases.push_back(run_pitching_plate_case(o, k, rigid));
    } catch (const std::exception& e) {
      PitchingPlateCaseResult failed;
      failed.stiffness = rigid ? 0 : k;
      failed.rigid = rigid;
      failed.error = e.what();
      if (o.progress) o.progress("failed: " + failed.error);
      run.cases.push_back(failed);
    }
  };
  if (o.rigid) one(0, true);
  for (double k : ks) one(k, false);
  run.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();

  Summary s("validation", "fsi_pitching_plate",
            "Flexible plate pitching about its leading edge (W/L 0.54, 12 deg, f = 1, m = 0.1), coupled 3-D");
  const double rigid_amplitude = std::sin(o.pitch_amplitude_deg * pi / 180);
  const std::string kinematics = "rigid kinematics, A/L = sin(alpha0)";
  const PitchingPlateModes& m = run.modes;
  s.info("dry_frequency_per_sqrt_K", m.dry_per_sqrt_k, "f0");
  s.info("added_mass_ratio_strip", m.added_mass_ratio);
  s.info("wet_frequency_per_sqrt_K", m.wet_per_sqrt_k, "f0");
  s.info("K_resonance_predicted", m.resonant_stiffness);
  double peak = -1, k_peak = 0, mismatch = 0, it_mean = 0;
  std::size_t i_peak = 0;
  std::vector<double> swept;
  long failed = 0;
  for (const PitchingPlateCaseResult& c : run.cases) {
    const std::string tag = c.rigid ? std::string("rigid") : "K" + printf_format("%g", c.stiffness);
    if (!c.error.empty()) {
      ++failed;
      s.parameters()["errors"][tag] = c.error;
      continue;
    }
    // The stiff limit: the stiffest K, when its wet frequency is at least 5 f0 (quasi-static, the
    // bending then within a few per cent of the rigid motion).
    const bool stiff = !c.rigid && c.stiffness == ks.back() && m.wet_per_sqrt_k * std::sqrt(c.stiffness) >= 5 * o.frequency;
    if (c.rigid || stiff)
      s.relative("A_over_L_" + tag, c.amplitude, rigid_amplitude, 0.02, kinematics);
    else
      s.info("A_over_L_" + tag, c.amplitude);
    s.info("phase_deg_" + tag, c.phase_deg, "deg");
    s.info("CT_mean_" + tag, c.mean_thrust);
    s.info("CL_amplitude_" + tag, c.lift_amplitude);
    s.info("coupling_iterations_mean_" + tag, c.coupling_iterations_mean);
    s.info("steps_at_cap_" + tag, static_cast<double>(c.steps_at_cap));
    s.info("wall_seconds_per_period_" + tag, c.wall_seconds / o.periods, "s");
    if (!c.rigid) {
      s.info("frequency_ratio_" + tag, m.wet_per_sqrt_k * std::sqrt(c.stiffness) / o.frequency);
      swept.push_back(c.stiffness);
      if (c.amplitude > peak) {
        peak = c.amplitude;
        k_peak = c.stiffness;
        i_peak = swept.size() - 1;
      }
    }
    mismatch = std::max(mismatch, c.transfer_mismatch);
    it_mean += c.coupling_iterations_mean / static_cast<double>(run.cases.size());
  }
  if (swept.size() >= 3) {
    // The peak's neighbours in the sweep must bracket the predicted resonance (the sweep's resolution).
    const double lo = i_peak > 0 ? swept[i_peak - 1] : 0.0;
    const double hi = i_peak + 1 < swept.size() ? swept[i_peak + 1] : 1e300;
    s.info("K_amplitude_peak", k_peak);
    s.info("A_over_L_peak", peak);
    s.at_most("resonance_outside_peak_bracket", (m.resonant_stiffness > lo && m.resonant_stiffness < hi) ? 0.0 : 1.0,
              0.0, "wet first natural frequency (modal analysis + strip added mass) = f0");
  }
  s.at_most("failed_runs", static_cast<double>(failed), 0.0, "every run completes (errors: parameters/errors)");
  s.info("transfer_mismatch_max", mismatch);
  s.info("coupling_iterations_mean", it_mean);
  if (!run.cases.empty()) s.info("flow_cells", static_cast<double>(run.cases.front().flow_cells));
  nlohmann::json errors = s.parameters().value("errors", nlohmann::json::object());
  s.parameters() = {{"re", o.re},
                    {"aspect", o.aspect},
                    {"pitch_amplitude_deg", o.pitch_amplitude_deg},
                    {"frequency", o.frequency},
                    {"mass_ratio", o.mass_ratio},
                    {"K_definition", "D / (rho_f U^2 L^3), D = E h^3 / (12 (1 - nu^2))"},
                    {"stiffness", ks},
                    {"rigid", o.rigid},
                    {"poisson_ratio", o.poisson_ratio},
                    {"shell_thickness", o.shell_thickness},
                    {"shell_grid", {o.nx, o.nz}},
                    {"cells_per_chord", o.cells_per_chord},
                    {"thin_body_thickness", o.thickness_cells / o.cells_per_chord},
                    {"surface", o.surface},
                    {"band_correction", o.band_correction},
                    {"stretch_ratio", o.stretch_ratio},
                    {"domain", {-o.upstream, 1 + o.downstream, o.half_height, o.half_width}},
                    {"steps_per_period", o.steps_per_period},
                    {"periods", o.periods},
                    {"ramp_periods", o.ramp_periods},
                    {"acceleration", o.acceleration},
                    {"omega0", o.omega},
                    {"relative_tolerance", o.tolerance},
                    {"absolute_tolerance", o.absolute_tolerance},
                    {"max_iterations", o.max_iterations},
                    {"spectral_radius", o.spectral_radius},
                    {"structure_tolerance", o.structure_tolerance},
                    {"added_mass", "strip theory across the span: pi rho_f W^2 / 4 per unit length (Newman 1977)"}};
  if (!errors.empty()) s.parameters()["errors"] = errors;
  run.summary = s;
  return run;
}

}  // namespace finverse::fsi::validation
