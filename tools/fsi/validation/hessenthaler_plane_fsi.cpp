// The plane version of the Hessenthaler (2017) Phase I flow; see hessenthaler_plane_fsi.hpp.
#include "fsi/validation/hessenthaler_plane_fsi.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

#include "cfd/validation/cylinder_channel.hpp"
#include "cfd/validation/turek_hron_cfd.hpp"
#include "core/error.hpp"
#include "fem/coupled_structure.hpp"
#include "fem/static_solver.hpp"
#include "fem/validation/hessenthaler_flap.hpp"
#include "fsi/acceleration_factory.hpp"
#include "fsi/coupled_run.hpp"
#include "fsi/implicit_coupling.hpp"
#include "fsi/validation/flag_flow_body.hpp"
#include "fsi/validation/flow_structure_step.hpp"

namespace finverse::fsi::validation {

namespace {

double number(const nlohmann::json& j, const char* pointer, const std::filesystem::path& path) {
  const nlohmann::json::json_pointer p(pointer);
  if (!j.contains(p) || !j[p].is_number()) throw Error(path.string() + ": expected a number at " + pointer);
  return j[p].get<double>();
}

}  // namespace

namespace {

// The last fifth of the run (of what ran): mean and range of the tip, and the flow's mean load per
// station.
struct LastFifth {
  double t0 = 0, mean = 0, lo = 0, hi = 0;
  Eigen::Matrix2Xd mean_load;
  std::vector<double> along, transverse, edges;
};
LastFifth last_fifth(const std::vector<double>& time, const std::vector<double>& tip,
                     const std::vector<Eigen::Matrix2Xd>& binned_loads, int bins, double length) {
  LastFifth r;
  const double t0 = r.t0 = 0.8 * time.back();
  double sum = 0, lo = 1e300, hi = -1e300;
  int count = 0;
  for (std::size_t k = 0; k < time.size(); ++k)
    if (time[k] >= t0) sum += tip[k], lo = std::min(lo, tip[k]), hi = std::max(hi, tip[k]), ++count;
  r.mean = sum / std::max(count, 1);
  r.lo = lo;
  r.hi = hi;
  Eigen::Matrix2Xd& mean_load = r.mean_load;
  mean_load = Eigen::Matrix2Xd::Zero(2, bins);
  for (std::size_t k = 0; k < time.size(); ++k)
    if (time[k] >= t0) mean_load += binned_loads[k];
  mean_load /= std::max(count, 1);
  // Per unit length of the flap and unit depth [N/m^2]: times the 3-D flap's width, a load per length.
  const double station = length / bins;
  for (int b = 0; b <= bins; ++b) r.edges.push_back(b * station);
  for (int b = 0; b < bins; ++b)
    r.along.push_back(mean_load(0, b) / station), r.transverse.push_back(mean_load(1, b) / station);
  return r;
}

// The plane-strain strip's static buoyancy deflection, no flow.
double static_buoyancy_tip(fem::validation::TurekHronFlagSpec spec) {
  spec.gravity_as_load = true;
  const fem::validation::TurekHronFlag f = fem::validation::build_turek_hron_flag(spec);
  fem::StaticOptions so;
  so.steps = 8;
  fem::StaticSolver solver(f.model, so);
  fem::NodalState state = f.model.reference_state();
  solver.solve(state, 0.0, 1.0);
  const auto a = static_cast<std::size_t>(f.point_a);
  return state.position[a].y() - f.model.reference_positions()[a].y();
}

// The two inlet pipes as parabolic slots of half-width `half` on the channel's inlet (centres,
// peaks: lower, upper), ramped over ramp_time; a convective outlet.
cfd::FlowBoundary slot_inflow(double ramp_time, double half, std::array<double, 2> centre, std::array<double, 2> peak) {
  cfd::FlowBoundary b;
  b[cfd::Side::XLo].type = cfd::FlowBcType::Inlet;
  b[cfd::Side::XLo].profile = cfd::InletProfile::Function;
  b[cfd::Side::XLo].ramp_time = ramp_time;
  b[cfd::Side::XLo].function = [=](double, double y, double, double) -> std::array<double, 3> {
    const auto slot = [&](double c, double u) {
      const double s = (y - c) / half;
      return std::abs(s) < 1 ? u * (1 - s * s) : 0.0;
    };
    return {slot(centre[1], peak[1]) + slot(centre[0], peak[0]), 0, 0};
  };
  b[cfd::Side::XHi].type = cfd::FlowBcType::ConvectiveOutlet;
  return b;
}

// Each wet node's station: `bins` equal stations along the flap by reference x from the clamp.
std::vector<int> stations(const Eigen::Matrix2Xd& wet_reference, double clamp, double length, int bins) {
  std::vector<int> bin_of(static_cast<std::size_t>(wet_reference.cols()));
  for (Eigen::Index k = 0; k < wet_reference.cols(); ++k)
    bin_of[static_cast<std::size_t>(k)] =
        std::clamp(static_cast<int>(std::floor((wet_reference(0, k) - clamp) / length * bins)), 0, bins - 1);
  return bin_of;
}

// The flap's part of the coupled run (coupled_run.hpp): per step the tip's deflection and the
// flow's load summed over equal stations along the flap; every 50th step a progress line.
class FlapCase final : public CoupledCase {
 public:
  FlapCase(const FlowStructureStep& step, const fem::CoupledStructure& structure, int tip_node, double tip_y0,
           std::vector<int> bin_of, int bins, double dt, long steps, std::function<void(const std::string&)> progress)
      : step_(step),
        structure_(structure),
        tip_node_(tip_node),
        tip_y0_(tip_y0),
        bin_of_(std::move(bin_of)),
        bins_(bins),
        dt_(dt),
        steps_(steps),
        progress_(std::move(progress)) {}

  std::vector<Eigen::Matrix2Xd> binned_loads;
  std::vector<double> time, tip;
  nlohmann::json tip_history = nlohmann::json::array();

  void after_step(long n, const StepStatistics& st) override {
    const double uy = structure_.state().configuration.position[static_cast<std::size_t>(tip_node_)].y() - tip_y0_;
    time.push_back(static_cast<double>(n) * dt_);
    tip.push_back(uy);
    Eigen::Matrix2Xd per_bin = Eigen::Matrix2Xd::Zero(2, bins_);
    for (std::size_t k = 0; k < bin_of_.size(); ++k)
      per_bin.col(bin_of_[k]) += step_.wet_loads().col(static_cast<Eigen::Index>(k));
    binned_loads.push_back(per_bin);
    if (n % 50 == 0 || n == steps_) {
      tip_history.push_back({static_cast<double>(n) * dt_, uy});
      if (progress_) {
        char line[160];
        std::snprintf(line, sizeof line, "step %ld/%ld t %.4f s: tip %.3f mm, %d it", n, steps_,
                      static_cast<double>(n) * dt_, uy * 1e3, st.iterations);
        progress_(line);
      }
    }
  }
  // No checkpoints in this case: its series are not kept.
  [[nodiscard]] RunHistory history() const override { return {}; }
  void restore_history(RunHistory) override {}
  [[nodiscard]] std::string progress_line(long, const StepStatistics&) const override { return {}; }

 private:
  const FlowStructureStep& step_;
  const fem::CoupledStructure& structure_;
  int tip_node_;
  double tip_y0_;
  std::vector<int> bin_of_;
  int bins_;
  double dt_;
  long steps_;
  std::function<void(const std::string&)> progress_;
};

constexpr double kGravity = 9.81;  // [m/s^2]

// The rig's numbers from the reference file [SI].
struct Rig {
  double d_in = 0, offset = 0, H = 0;  // inlet pipes' diameter and centres' offset, outlet diameter
  double u_upper = 0, u_lower = 0;     // Phase I peak inflow speeds
  double rho = 0, mu = 0;
};

Rig read_rig(const std::filesystem::path& reference) {
  std::ifstream in(reference);
  const nlohmann::json j = nlohmann::json::parse(in);
  const double mm = 1e-3;
  Rig r;
  r.d_in = number(j, "/geometry/inlet_pipes/diameter_mm", reference) * mm;
  r.offset = std::abs(number(j, "/geometry/inlet_pipes/centre_offsets_mm/0", reference)) * mm;
  r.H = number(j, "/geometry/outlet_pipe_diameter_mm", reference) * mm;
  r.u_upper = number(j, "/phase_I_steady_inflow/peak_velocity_m_s/upper", reference);
  r.u_lower = number(j, "/phase_I_steady_inflow/peak_velocity_m_s/lower", reference);
  r.rho = number(j, "/fluid/density", reference);
  r.mu = number(j, "/fluid/dynamic_viscosity", reference);
  return r;
}

// The structure: the strip behind a small nose, clamped straight where the nose meets its faces,
// buoyant (the net of gravity and buoyancy as a body force).
fem::validation::TurekHronFlagSpec flap_spec(const fem::validation::HessenthalerFlap& flap,
                                             const HessenthalerPlaneOptions& o, double yc) {
  const double mm = 1e-3;
  fem::validation::TurekHronFlagSpec spec;
  spec.radius = 1.2 * mm;
  // The nose's image points must stay among the cell centres: its upstream side 4 cells off the inlet.
  spec.xc = std::max(2 * mm, spec.radius + 4 * o.h);
  spec.yc = yc;
  spec.thickness = flap.thickness;
  const double clamp = spec.xc + std::sqrt(spec.radius * spec.radius - 0.25 * spec.thickness * spec.thickness);
  spec.x_tip = clamp + flap.length;
  spec.youngs_modulus = o.youngs_modulus;
  spec.poisson_ratio = flap.poisson_ratio;
  spec.density = flap.solid_density;
  spec.gravity = -(flap.fluid_density - flap.solid_density) / flap.solid_density * kGravity;  // upward net
  spec.mesh = o.mesh;
  spec.straight_clamp = true;
  return spec;
}

}  // namespace

Summary run_hessenthaler_plane_fsi(const HessenthalerPlaneOptions& o) {
  const auto wall0 = std::chrono::steady_clock::now();
  if (!(o.youngs_modulus > 0)) throw Error("hessenthaler_plane: --youngs-modulus must be positive");
  if (!(o.h > 0) || !(o.t_end > 0) || !(o.cfl > 0))
    throw Error("hessenthaler_plane: h, t_end and cfl must be positive");
  const fem::validation::HessenthalerFlap flap = fem::validation::read_hessenthaler_flap(o.reference);
  const Rig rig = read_rig(o.reference);
  const double d_in = rig.d_in, offset = rig.offset, H = rig.H, u_upper = rig.u_upper, u_lower = rig.u_lower;
  const double rho = rig.rho, mu = rig.mu, yc = 0.5 * H;
  const fem::validation::TurekHronFlagSpec spec = flap_spec(flap, o, yc);
  const double clamp = spec.xc + std::sqrt(spec.radius * spec.radius - 0.25 * spec.thickness * spec.thickness);

  const double static_tip = static_buoyancy_tip(spec);  // no flow

  const fem::validation::TurekHronFlag flag = fem::validation::build_turek_hron_flag(spec);
  const auto& X0 = flag.model.reference_positions();
  const int n_wet = static_cast<int>(flag.wet_nodes.size());
  Eigen::Matrix2Xd wet_reference(2, n_wet);
  for (int k = 0; k < n_wet; ++k)
    wet_reference.col(k) = X0[static_cast<std::size_t>(flag.wet_nodes[static_cast<std::size_t>(k)])].head<2>();

  // Flow.
  cfd::TurekHronGeometry g;
  g.length = o.outlet_length;
  g.height = H;
  g.xc = spec.xc;
  g.yc = yc;
  g.radius = spec.radius;
  g.flag_thickness = spec.thickness;
  g.flag_length = spec.x_tip - spec.xc - spec.radius;
  const cfd::StretchedGrid grid = cfd::channel_grid({.length = g.length,
                                                     .height = H,
                                                     .box_x0 = 0,
                                                     .box_x1 = std::min(spec.x_tip + 0.02, 0.8 * g.length),
                                                     .box_y0 = 0,
                                                     .box_y1 = H,
                                                     .h = o.h,
                                                     .ratio = o.stretch_ratio});
  const double u_max = std::max(u_upper, u_lower);
  const double dt = o.cfl * o.h / u_max;
  cfd::FlowOptions flow_options = cfd::channel_benchmark_options(mu / rho, o.cfl, o.h, u_max);
  flow_options.dt = dt;
  const double lo_c = yc - offset, hi_c = yc + offset;
  const cfd::FlowBoundary b = slot_inflow(o.ramp_time, 0.5 * d_in, {lo_c, hi_c}, {u_lower, u_upper});
  cfd::FlowSolver flow;
  flow.setup(grid, b, flow_options);
  const FlagFlowBody body(g, 256, wet_reference);
  const Eigen::Matrix2Xd zero = Eigen::Matrix2Xd::Zero(2, n_wet);
  flow.immerse_deforming(body.state(wet_reference, zero, zero));
  flow.initialise({});

  fem::CoupledStructureOptions so;
  so.dynamics.time_step = dt;
  so.dynamics.spectral_radius = 0.8;
  so.dim = 2;
  fem::CoupledStructure structure(flag.model, so, flag.wet_nodes);
  structure.save();
  FlowStructureStep step(flow, structure, body, rho, dt);
  const InterfaceLayout layout = step.layout();
  ImplicitCoupling coupling(layout, Eigen::VectorXd::Zero(layout.size()), make_acceleration("iqn-ils", layout, 0.1),
                            immersed_coupling_options(o.tolerance, o.absolute_tolerance, o.max_iterations));

  const auto steps = static_cast<long>(std::ceil(o.t_end / dt - 1e-9));
  // The flow's load on the flap per step, summed over the wet nodes of each of load_bins equal
  // stations along the flap (by reference x from the clamp; the end face's nodes in the first
  // and last): the time mean of the last fifth is the "measured" flow load of fin-loop flap.
  const int bins = std::max(o.load_bins, 1);
  const std::vector<int> bin_of = stations(wet_reference, clamp, flap.length, bins);
  // A step that fails (the flow blowing up) ends the run with what it has: the summary flags it.
  FsiOutput output(std::vector<Eigen::Vector3d>(X0.begin(), X0.end()), {}, rho, 1.0, 1.0);
  CoupledRunOptions ro;
  ro.name = "hessenthaler_plane";
  ro.steps = steps;
  ro.dt = dt;
  CoupledRun run(flow, structure, step, coupling, output, nlohmann::json::object(), ro);
  FlapCase flap_case(step, structure, flag.point_a, X0[static_cast<std::size_t>(flag.point_a)].y(), bin_of, bins, dt,
                     steps, o.progress);
  std::string failure;
  double failed_at = 0;
  try {
    run.run(flap_case);
  } catch (const std::exception& e) {
    failure = e.what();
    failed_at = static_cast<double>(flap_case.time.size() + 1) * dt;
    if (o.progress) o.progress("FAILED at " + failure);
  }
  long iterations = 0, at_cap = 0;
  for (const StepStatistics& st : run.statistics()) {
    iterations += st.iterations;
    at_cap += st.converged ? 0 : 1;
  }
  const std::vector<double>& time = flap_case.time;
  const std::vector<double>& tip = flap_case.tip;
  const std::vector<Eigen::Matrix2Xd>& binned_loads = flap_case.binned_loads;
  const nlohmann::json& history = flap_case.tip_history;

  if (time.empty()) throw Error("hessenthaler_plane: the first step failed: " + failure);
  const LastFifth last = last_fifth(time, tip, binned_loads, bins, flap.length);
  const double t0 = last.t0, mean = last.mean, lo = last.lo, hi = last.hi;
  const Eigen::Matrix2Xd& mean_load = last.mean_load;
  const std::vector<double>&along = last.along, &transverse = last.transverse, &edges = last.edges;

  Summary s("validation", "loop_hessenthaler_phase_I_plane",
            "PLANE VERSION of the Hessenthaler 2017 Phase I flow (2-D section: the flap spans the depth and "
            "separates the two jets; not the 3-D experiment): tip deflection against the measured 16.41 mm");
  s.absolute("phase_I_plane_tip_mean_last_fifth", mean, flap.tip_deflection_phase_I, 1e-3,
             "Hessenthaler et al. 2017 Phase I measured steady tip (3-D experiment; this is a plane model)", "m");
  s.at_most("run_failed", failure.empty() ? 0.0 : 1.0, 0.0, failure.empty() ? "ran to t_end" : failure);
  if (!failure.empty()) s.info("failed_at_time", failed_at, "s");
  s.info("phase_I_plane_tip_min_last_fifth", lo, "m");
  s.info("phase_I_plane_tip_max_last_fifth", hi, "m");
  s.info("phase_I_plane_tip_final", tip.back(), "m");
  s.info("phase_I_plane_residual", mean - flap.tip_deflection_phase_I, "m");
  s.info("plane_strain_static_tip_no_flow", static_tip, "m");
  s.info("phase_I_plane_mean_flow_force_transverse", mean_load.row(1).sum(), "N/m");
  s.info("phase_I_plane_mean_flow_force_along", mean_load.row(0).sum(), "N/m");
  s.info("coupling_iterations_mean", static_cast<double>(iterations) / static_cast<double>(steps));
  s.info("steps_at_cap", static_cast<double>(at_cap));
  s.info("flow_cells", static_cast<double>(grid.cells()));
  s.info("wall_seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count(), "s");
  s.parameters() = {{"reference", o.reference.string()},
                    {"youngs_modulus_Pa", o.youngs_modulus},
                    {"poisson_ratio", flap.poisson_ratio},
                    {"h_m", o.h},
                    {"dt_s", dt},
                    {"t_end_s", o.t_end},
                    {"ramp_time_s", o.ramp_time},
                    {"cfl", o.cfl},
                    {"outlet_length_m", o.outlet_length},
                    {"channel_height_m", H},
                    {"slots", {{"width_m", d_in}, {"centres_m", {lo_c, hi_c}}, {"peaks_m_s", {u_lower, u_upper}}}},
                    {"nose_radius_m", spec.radius},
                    {"clamp_x_m", clamp},
                    {"flag_mesh", {o.mesh.nx, o.mesh.ny, o.mesh.grading}},
                    {"buoyancy_body_force_N_m3", (flap.fluid_density - flap.solid_density) * kGravity},
                    {"tip_history_t_s_uy_m", history},
                    {"mean_flow_load_last_fifth",
                     {{"note",
                       "flow's load on the flap per unit length and unit depth, time mean over the last fifth, "
                       "piecewise constant on stations from the clamp (no hydrostatics; buoyancy excluded)"},
                      {"window_s", {t0, time.back()}},
                      {"station_edges_m", edges},
                      {"along_N_m2", along},
                      {"transverse_N_m2", transverse}}}};
  return s;
}

}  // namespace finverse::fsi::validation
