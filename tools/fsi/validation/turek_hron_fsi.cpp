// The Turek-Hron FSI1/FSI2/FSI3 driver and its grading; see turek_hron_fsi.hpp.
#include "fsi/validation/turek_hron_fsi.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <set>

#include "cfd/validation/cylinder_channel.hpp"
#include "cfd/validation/turek_hron_cfd.hpp"
#include "core/error.hpp"
#include "core/printf_format.hpp"
#include "core/sha256.hpp"
#include "fem/coupled_structure.hpp"
#include "fem/errors.hpp"
#include "fem/validation/turek_hron_csm.hpp"
#include "fsi/aitken.hpp"
#include "fsi/constant_relaxation.hpp"
#include "fsi/coupled_run.hpp"
#include "fsi/fsi_checkpoint.hpp"
#include "fsi/fsi_output.hpp"
#include "fsi/fsi_paraview.hpp"
#include "fsi/iqn_ils.hpp"
#include "fsi/validation/flag_flow_body.hpp"
#include "fsi/validation/sheet_flag_step.hpp"

namespace finverse::fsi::validation {

namespace {

constexpr double kRho = 1000, kNu = 1e-3;

nlohmann::json read_case(const std::filesystem::path& reference, const std::string& name) {
  std::ifstream in(reference);
  if (!in) throw Error("turek_hron_fsi: cannot read the reference file " + reference.string());
  nlohmann::json j;
  try {
    in >> j;
  } catch (const std::exception& e) {
    throw Error("turek_hron_fsi: " + reference.string() + " is not JSON: " + e.what());
  }
  if (!j.contains("cases") || !j["cases"].contains(name) || !j["cases"][name].contains("Ubar"))
    throw Error("turek_hron_fsi: " + reference.string() + " has no /cases/" + name + "/Ubar");
  return j["cases"][name];
}

// (mean, amplitude) of a reference entry [mean, amplitude].
std::array<double, 2> pair_of(const nlohmann::json& c, const char* key, const std::string& name) {
  if (!c.contains(key) || !c[key].is_array() || c[key].size() != 2)
    throw Error("turek_hron_fsi: /cases/" + name + "/" + key + " must be [mean, amplitude]");
  return {c[key][0].get<double>(), c[key][1].get<double>()};
}

}  // namespace

namespace {

// The run's options as stored in fsi.h5, summary.json and checkpoints (compared on restart).
nlohmann::json run_config(const TurekHronFsiOptions& opt, double h, double hc, double dt, double t_end) {
  nlohmann::json c = {{"case", opt.case_name},
                      {"acceleration", opt.acceleration},
                      {"omega0", opt.omega},
                      {"relative_tolerance", opt.tolerance},
                      {"absolute_tolerance", opt.absolute_tolerance},
                      {"max_iterations", opt.max_iterations},
                      {"divergence_iterations", opt.divergence_iterations},
                      {"accept_at_cap", opt.accept_at_cap},
                      {"cells_per_diameter", opt.cells_per_diameter},
                      {"h", h},
                      {"core_cells_per_diameter", opt.core_cells_per_diameter},
                      {"core_wake", opt.core_wake},
                      {"wake_box", opt.wake_box},
                      {"h_core", hc},
                      {"dt", dt},
                      {"t_end", t_end},
                      {"ramp_time", opt.ramp_time},
                      {"flag_mesh", {opt.mesh.nx, opt.mesh.ny}},
                      {"spectral_radius", opt.spectral_radius},
                      {"structure_substeps", opt.structure_substeps},
                      {"circle_vertices", opt.circle_vertices},
                      {"channel_length", opt.channel_length},
                      {"stretch_ratio", opt.stretch_ratio},
                      {"wall_stretch_ratio", opt.wall_stretch_ratio},
                      {"output_every", opt.output_every},
                      {"reference_sha256", sha256_file(opt.reference)},
                      {"wall_acceleration", "(V^{n+1} - V^n) / dt"}};
  if (opt.surface != "closed") {  // (the closed flag's checkpoints predate the key)
    c["surface"] = opt.surface;
    c["band_correction"] = opt.band_correction;
    c["subtract_enclosed_fluid"] = opt.subtract_enclosed_fluid;
  }
  return c;
}

// Validation 4 (issue 32): over the whole steps inside [t0, t1] (the last period of u_y(A)) the
// interface work W_I (coupled_structure.hpp: the displacement increments times the load the
// integrator balanced) against the flag's energy change dE = d(T + U). Nothing is subtracted for
// the generalized-alpha scheme's own dissipation: with rho_inf < 1 the remainder W_I - dE is that
// dissipation (plus f_int's second-order error for the nonlinear solid), reported as such and
// graded against the gross work sum |W_I,step| over the period (goal 1 %); with rho_inf = 1 the
// scheme conserves and the remainder is the nonlinear error alone.
void grade_energy_balance(Summary& s, const std::vector<double>& t, const TurekHronFsiRun& run, double t0, double t1) {
  std::size_t k0 = t.size(), k1 = 0;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (t[k] >= t0 - 1e-12 && t[k] <= t1 + 1e-12) {
      k0 = std::min(k0, k);
      k1 = k;
    }
  if (k0 >= k1) return;
  double work = 0, gross = 0;
  for (std::size_t k = k0 + 1; k <= k1; ++k) {
    work += run.records[k].interface_work;
    gross += std::abs(run.records[k].interface_work);
  }
  const double change = run.energy[k1] - run.energy[k0];
  s.info("interface_work_last_period", work, "J/m");
  s.info("structure_energy_change_last_period", change, "J/m");
  s.info("interface_work_gross_last_period", gross, "J/m");
  s.info("integrator_dissipation_last_period", work - change, "J/m");
  s.at_most("energy_balance_last_period", std::abs(work - change) / std::max(gross, 1e-300), 0.01,
            "|W_I - dE| / sum |W_I,step| over the last period (issue 32, validation 4)");
}

// The flag's part of the coupled run (coupled_run.hpp): per step the forces, point A and the
// flag's energy; fsi.h5 frames every output_every steps (and the last); flow snapshots.
class FlagCase final : public CoupledCase {
 public:
  FlagCase(TurekHronFsiRun& run, FlagCoupledStep& step, fem::CoupledStructure& structure, FsiOutput& output,
           const fem::validation::TurekHronFlag& flag, const std::vector<fem::Vec3>& reference, double dt, int every)
      : run_(run),
        step_(step),
        structure_(structure),
        output_(output),
        flag_(flag),
        reference_(reference),
        dt_(dt),
        every_(every) {}

  std::unique_ptr<FsiParaView> paraview;
  const cfd::FlowSolver* flow = nullptr;

  void after_step(long n, const StepStatistics& st) override {
    const StepRecord& rec = step_.records().back();
    run_.records.push_back(rec);
    const auto a = static_cast<std::size_t>(flag_.point_a);
    const fem::Vec3 ua = structure_.state().configuration.position[a] - reference_[a];
    run_.ux_a.push_back(ua.x());
    run_.uy_a.push_back(ua.y());
    run_.energy.push_back(structure_.kinetic_energy() + structure_.strain_energy());
    last_ = st;
    if (n % every_ == 0) add_frame(st);
    output_.add_probes(structure_.state());
    if (paraview && n % every_ == 0) paraview->at_frame(n / every_, rec.time, dt_, *flow);
  }
  // The last step's frame off the interval comes after the checkpoint, which holds the frames of
  // the uninterrupted run only.
  void after_last_step(long n) override {
    if (n % every_ != 0) add_frame(last_);
  }
  [[nodiscard]] RunHistory history() const override {
    std::vector<double> records;
    for (const StepRecord& r : run_.records)
      records.insert(records.end(), {static_cast<double>(r.step), r.time, r.force[0], r.force[1], r.flag_force[0],
                                     r.flag_force[1], r.power, r.interface_work, r.transfer_mismatch});
    return {{"records", records}, {"ux_a", run_.ux_a}, {"uy_a", run_.uy_a}, {"energy", run_.energy}};
  }
  void restore_history(RunHistory h) override {
    const std::vector<double>& records = h["records"];
    const std::size_t n = h["ux_a"].size();
    if (records.size() != 9 * n || h["uy_a"].size() != n || h["energy"].size() != n)
      throw Error("turek_hron_fsi: the checkpoint's per-step records and probe history do not fit one another");
    for (std::size_t k = 0; k < records.size(); k += 9) {
      const double* r = records.data() + k;
      run_.records.push_back({static_cast<long>(r[0]), r[1], {r[2], r[3]}, {r[4], r[5]}, r[6], r[7], r[8]});
    }
    run_.ux_a = std::move(h["ux_a"]);
    run_.uy_a = std::move(h["uy_a"]);
    run_.energy = std::move(h["energy"]);
  }
  [[nodiscard]] std::string progress_line(long n, const StepStatistics& st) const override {
    const StepRecord& rec = run_.records.back();
    return "step " + std::to_string(n) + " t " + printf_format("%.4f", rec.time) + ": " +
           std::to_string(st.iterations) + " it" + (st.converged ? "" : " (cap: best iterate)") + ", residual " +
           printf_format("%.2e", st.residual) + ", drag " + printf_format("%.4f", rec.force[0]) + " lift " +
           printf_format("%.4f", rec.force[1]) + " N/m, A (" + printf_format("%.4e", run_.ux_a.back()) + ", " +
           printf_format("%.4e", run_.uy_a.back()) + ") m, power " + printf_format("%.3e", rec.power) + " W/m";
  }

 private:
  void add_frame(const StepStatistics& st) {
    const StepRecord& rec = run_.records.back();
    const auto n_wet = static_cast<Eigen::Index>(flag_.wet_nodes.size());
    const Eigen::VectorXd load = Eigen::Map<const Eigen::VectorXd>(step_.wet_loads().data(), 2 * n_wet);
    output_.add(structure_.state(), structure_.scatter(load), {rec.force[0], rec.force[1], 0.0}, st.iterations,
                st.absolute_residual, st.residual);
  }

  TurekHronFsiRun& run_;
  FlagCoupledStep& step_;
  fem::CoupledStructure& structure_;
  FsiOutput& output_;
  const fem::validation::TurekHronFlag& flag_;
  const std::vector<fem::Vec3>& reference_;
  double dt_;
  int every_;
  StepStatistics last_;
};

// Grading against Turek & Hron (2006) and the run's own measures (coupling, energy, cost): the
// summary of a finished run.
struct RunFacts {
  double D = 0, ubar = 0, t_end = 0, loop_seconds = 0, structure_energy = 0;
  long steps = 0, flow_cells = 0;
};

Summary grade_turek_hron(const TurekHronFsiOptions& opt, const nlohmann::json& ref, const TurekHronFsiRun& run,
                         const nlohmann::json& config, const RunFacts& f) {
  const std::string& name = opt.case_name;
  const double D = f.D, ubar = f.ubar, t_end = f.t_end, loop_seconds = f.loop_seconds;
  const long steps = f.steps;
  const std::string source = "Turek & Hron 2006 (" + opt.reference.filename().string() + ", /cases/" + name + ")";
  Summary s("validation",
            "fsi_turek_hron_" +
                std::string(name == "FSI1"   ? "fsi1"
                            : name == "FSI2" ? "fsi2"
                                             : "fsi3") +
                (opt.surface == "sheet" ? "_sheet" : ""),
            "Turek-Hron " + name + ": elastic flag behind a cylinder" +
                (opt.surface == "sheet" ? " as a zero-thickness sheet" : "") + ", implicit partitioned coupling (" +
                opt.acceleration + ")");
  std::vector<double> t, drag, lift;
  for (const StepRecord& r : run.records) {
    t.push_back(r.time);
    drag.push_back(r.force[0]);
    lift.push_back(r.force[1]);
  }
  if (name == "FSI1") {
    // Steady: the means over the last second. The forces carry one-step impulses whenever a cell
    // changes kind as the flag settles (measured: lift 0.64-1.34 N/m over the last second at D/32),
    // so the last sample alone is not the steady value.
    const double t0 = t.back() - std::min(1.0, 0.5 * t.back());
    const auto window = [&](const std::vector<double>& v, double& lo, double& hi) {
      double sum = 0;
      long n = 0;
      lo = 1e300;
      hi = -1e300;
      for (std::size_t k = 0; k < t.size(); ++k)
        if (t[k] >= t0 - 1e-12) {
          sum += v[k];
          ++n;
          lo = std::min(lo, v[k]);
          hi = std::max(hi, v[k]);
        }
      return sum / static_cast<double>(n);
    };
    double lo = 0, hi = 0;
    s.relative("ux_A", window(run.ux_a, lo, hi), ref["ux_A"].get<double>(), 0.01, source, "m");
    s.relative("uy_A", window(run.uy_a, lo, hi), ref["uy_A"].get<double>(), 0.01, source, "m");
    s.info("uy_A_range_last_second", hi - lo, "m");
    s.relative("drag", window(drag, lo, hi), ref["drag"].get<double>(), 0.01, source, "N/m");
    s.info("drag_range_last_second", hi - lo, "N/m");
    s.relative("lift", window(lift, lo, hi), ref["lift"].get<double>(), 0.01, source, "N/m");
    s.info("lift_range_last_second", hi - lo, "N/m");
    s.info("ux_A_final", run.ux_a.back(), "m");
    s.info("uy_A_final", run.uy_a.back(), "m");
    s.info("lift_final", lift.back(), "N/m");
  } else {
    int periods = 0;
    try {
      if (t.size() < 3) throw fem::NotConverged("fewer than 3 steps");  // nothing to grade
      const fem::validation::LastPeriod p = fem::validation::last_period(t, run.uy_a);
      periods = p.periods;
      const auto ux = fem::validation::mean_amplitude(t, run.ux_a, p.t_begin, p.t_end);
      const auto uy = fem::validation::mean_amplitude(t, run.uy_a, p.t_begin, p.t_end);
      const auto fd = fem::validation::mean_amplitude(t, drag, p.t_begin, p.t_end);
      const auto fl = fem::validation::mean_amplitude(t, lift, p.t_begin, p.t_end);
      const auto rux = pair_of(ref, "ux_A", name), ruy = pair_of(ref, "uy_A", name);
      const auto rd = pair_of(ref, "drag", name), rl = pair_of(ref, "lift", name);
      s.relative("uy_A_amplitude", uy.amplitude, ruy[1], 0.03, source, "m");
      s.relative("uy_A_frequency", p.frequency, ref["uy_freq"].get<double>(), 0.03, source, "Hz");
      s.relative("ux_A_mean", ux.mean, rux[0], 0.05, source, "m");
      s.relative("ux_A_amplitude", ux.amplitude, rux[1], 0.05, source, "m");
      s.relative("drag_mean", fd.mean, rd[0], 0.02, source, "N/m");
      s.relative("lift_amplitude", fl.amplitude, rl[1], 0.10, source, "N/m");
      s.info("uy_A_mean", uy.mean, "m");
      s.info("drag_amplitude", fd.amplitude, "N/m");
      s.info("lift_mean", fl.mean, "N/m");
      // The seed's Table 1 quantities: A_m / D (peak |u_y|), St = f D / Ubar, C_D = drag / (rho Ubar^2 D / 2).
      s.info("Am_over_D_peak", (std::abs(uy.mean) + uy.amplitude) / D);
      s.info("St", p.frequency * D / ubar);
      s.info("CD_mean", fd.mean / (0.5 * kRho * ubar * ubar * D));
      s.info("last_period_begin", p.t_begin, "s");
      s.info("last_period_end", p.t_end, "s");
      grade_energy_balance(s, t, run, p.t_begin, p.t_end);
    } catch (const fem::NotConverged&) {
      periods = 0;  // fewer than two upward crossings: nothing to grade
    }
    s.at_most("missing_periods", periods >= 1 ? 0.0 : 1.0, 0.0, "a full period of u_y(A) is needed to grade");
    s.info("uy_A_final", run.uy_a.back(), "m");
    s.info("drag_final", drag.back(), "N/m");
    s.info("lift_final", lift.back(), "N/m");
  }
  double mean_it = 0, max_it = 0, mismatch = 0, mean_ramped = 0;
  long ramped = 0, at_cap = 0;
  for (std::size_t k = 0; k < run.statistics.size(); ++k) {
    const double it = run.statistics[k].iterations;
    at_cap += run.statistics[k].converged ? 0 : 1;
    mean_it += it;
    max_it = std::max(max_it, it);
    mismatch = std::max(mismatch, run.records[k].transfer_mismatch);
    if (run.records[k].time > opt.ramp_time) {
      mean_ramped += it;
      ++ramped;
    }
  }
  mean_it /= static_cast<double>(run.statistics.size());
  s.info("coupling_iterations_mean", mean_it);
  s.info("coupling_iterations_max", max_it);
  if (ramped > 0) s.info("coupling_iterations_mean_after_ramp", mean_ramped / static_cast<double>(ramped));
  s.info("transfer_mismatch_max", mismatch);
  s.info("steps_at_cap", static_cast<double>(at_cap));
  // Energy from rest: the work the fluid did on the flag against its energy at the end; with
  // rho_inf < 1 the integrator dissipates part of it (graded over the last period above).
  double work = 0;
  for (const StepRecord& r : run.records) work += r.interface_work;
  const double energy = f.structure_energy;
  s.info("interface_work_total", work, "J/m");
  s.info("structure_energy_final", energy, "J/m");
  s.info("steps", static_cast<double>(steps));
  // This run's own steps (after a restart: those since the checkpoint), for the benchmark.
  double it_run = 0, it_run_max = 0;
  for (std::size_t k = static_cast<std::size_t>(run.first_step); k < run.statistics.size(); ++k) {
    it_run += run.statistics[k].iterations;
    it_run_max = std::max(it_run_max, static_cast<double>(run.statistics[k].iterations));
  }
  const auto steps_run = static_cast<double>(steps - run.first_step);
  s.info("steps_this_run", steps_run);
  s.info("coupling_iterations_mean_this_run", it_run / steps_run);
  s.info("coupling_iterations_max_this_run", it_run_max);
  s.info("wall_seconds_per_step", loop_seconds / steps_run, "s");
  s.info("wall_seconds_per_simulated_second", run.wall_seconds / t_end, "s");
  s.info("flow_cells", static_cast<double>(f.flow_cells));
  s.parameters() = config;
  s.parameters().erase("reference_sha256");
  s.parameters()["forces"] = "raw per step, no filter (graded: mean and half range over the last period)";
  if (!opt.restart.empty()) {
    s.parameters()["restart"] = opt.restart.string();
    s.parameters()["restart_step"] = run.first_step;
  }
  return s;
}

}  // namespace

// The flag's structure; with subtract_enclosed_fluid its density less the fluid's.
fem::validation::TurekHronFlag build_flag(const TurekHronFsiOptions& opt) {
  fem::validation::TurekHronFlagSpec spec = fem::validation::turek_hron_flag_spec(opt.reference, opt.case_name);
  spec.mesh = opt.mesh;
  if (opt.subtract_enclosed_fluid) {
    if (opt.surface != "sheet") throw Error("turek_hron_fsi: subtract_enclosed_fluid needs the sheet flag");
    if (!(spec.density > kRho))
      throw Error("turek_hron_fsi: subtract_enclosed_fluid needs rho_s > rho_f (" + opt.case_name +
                  ": rho_s = " + printf_format("%g", spec.density) + " kg/m^3)");
    spec.density -= kRho;
  }
  return fem::validation::build_turek_hron_flag(spec);
}

// The channel's grid: a uniform box of h around cylinder, flag and wake, a core of h_core
// (0: none) inside it, stretched outside.
cfd::StretchedGrid flag_channel_grid(const TurekHronFsiOptions& opt, const cfd::TurekHronGeometry& g, double h,
                                     double h_core) {
  const double D = 2 * g.radius;
  if (h_core > 0 && !(opt.core_wake > 0 && opt.core_wake < opt.wake_box))
    throw Error("turek_hron_fsi: core_wake must be > 0 and end inside the uniform box (wake_box)");
  if (!(g.tip_x() + opt.wake_box * D < g.length))
    throw Error("turek_hron_fsi: the wake box must end before the outlet (wake_box, channel_length)");
  return cfd::channel_grid({.length = g.length,
                            .height = g.height,
                            .box_x0 = g.xc - D,
                            .box_x1 = g.tip_x() + opt.wake_box * D,
                            .box_y0 = g.yc - D,
                            .box_y1 = g.yc + D,
                            .h = h,
                            .core_x0 = g.xc - 0.75 * D,
                            .core_x1 = g.tip_x() + opt.core_wake * D,
                            .core_y0 = g.yc - 0.75 * D,
                            .core_y1 = g.yc + 0.75 * D,
                            .h_core = h_core,
                            .ratio = opt.stretch_ratio,
                            .wall_ratio = opt.wall_stretch_ratio});
}

// The flag in the flow and the coupled step: part of the closed ghost-cell body, or its wet surface
// as a sheet beside the fixed ghost-cell cylinder; then the flow's initial field.
std::unique_ptr<FlagCoupledStep> immerse_flag(const TurekHronFsiOptions& opt, cfd::FlowSolver& flow,
                                              fem::CoupledStructure& structure, const cfd::TurekHronGeometry& g,
                                              const FlagFlowBody& body, double dt) {
  const Eigen::Matrix2Xd& wet = body.wet_reference();
  if (opt.surface == "closed") {
    const Eigen::Matrix2Xd zero = Eigen::Matrix2Xd::Zero(2, wet.cols());
    flow.immerse_deforming(body.state(wet, zero, zero));
    flow.initialise({});
    return std::make_unique<FlowStructureStep>(flow, structure, body, kRho, dt);
  }
  if (opt.surface != "sheet") throw Error("turek_hron_fsi: surface '" + opt.surface + "': expected closed or sheet");
  if (opt.hold_flag_rigid) throw Error("turek_hron_fsi: hold_flag_rigid needs the closed flag");
  std::vector<std::array<double, 2>> circle;
  for (int k = 0; k < opt.circle_vertices; ++k) {
    const double th = 2 * std::numbers::pi * k / opt.circle_vertices;
    circle.push_back({g.xc + g.radius * std::cos(th), g.yc + g.radius * std::sin(th)});
  }
  const cfd::Polygon cylinder(std::move(circle));
  flow.immerse(cylinder);
  cfd::SheetTopology topology{2, static_cast<std::size_t>(wet.cols()), {}};
  std::vector<cfd::Vec3> rest;
  for (Eigen::Index k = 0; k < wet.cols(); ++k) {
    rest.push_back({wet(0, k), wet(1, k), 0.0});
    if (k + 1 < wet.cols()) topology.elements.push_back({static_cast<int>(k), static_cast<int>(k) + 1, -1});
  }
  cfd::SheetForcingOptions sheet;
  sheet.band_correction = opt.band_correction;
  flow.immerse_sheet(topology, rest, sheet);
  flow.initialise({});
  return std::make_unique<SheetFlagStep>(flow, structure, g, cylinder, wet, kRho, kNu, dt);
}

TurekHronFsiRun run_turek_hron_fsi(const TurekHronFsiOptions& opt) {
  const auto wall0 = std::chrono::steady_clock::now();
  const std::string& name = opt.case_name;
  if (name != "FSI1" && name != "FSI2" && name != "FSI3")
    throw Error("turek_hron_fsi: case '" + name + "': expected FSI1, FSI2 or FSI3");
  if (opt.cells_per_diameter < 8) throw Error("turek_hron_fsi: expected cells_per_diameter >= 8");
  if (opt.output_every < 1) throw Error("turek_hron_fsi: expected output_every >= 1");
  const nlohmann::json ref = read_case(opt.reference, name);
  const double ubar = ref["Ubar"].get<double>(), um = 1.5 * ubar;

  const fem::validation::TurekHronFlag flag = build_flag(opt);
  const auto& X0 = flag.model.reference_positions();
  const int n_wet = static_cast<int>(flag.wet_nodes.size());
  Eigen::Matrix2Xd wet_reference(2, n_wet);
  for (int k = 0; k < n_wet; ++k)
    wet_reference.col(k) = X0[static_cast<std::size_t>(flag.wet_nodes[static_cast<std::size_t>(k)])].head<2>();

  // Flow: the channel and grid of turek_hron_cfd.cpp.
  cfd::TurekHronGeometry g;
  g.length = opt.channel_length;
  const double D = 2 * g.radius, h = D / opt.cells_per_diameter;
  const bool core = opt.core_cells_per_diameter > opt.cells_per_diameter;
  const double hc = core ? D / opt.core_cells_per_diameter : h;
  const cfd::StretchedGrid grid = flag_channel_grid(opt, g, h, core ? hc : 0);
  const double dt = opt.dt > 0 ? opt.dt : opt.cfl * hc / um;
  const double t_end = opt.t_end > 0 ? opt.t_end : (name == "FSI1" ? 6.0 : 10.0);
  cfd::FlowOptions flow_options = cfd::channel_benchmark_options(kNu, opt.cfl, hc, um);
  flow_options.dt = dt;
  cfd::FlowSolver flow;
  flow.setup(grid, cfd::channel_benchmark_boundary(um, opt.ramp_time), flow_options);
  fem::CoupledStructureOptions so;
  so.dynamics.time_step = dt;
  so.dynamics.spectral_radius = opt.spectral_radius;
  so.substeps = opt.structure_substeps;
  so.dim = 2;
  fem::CoupledStructure structure(flag.model, so, flag.wet_nodes);
  structure.save();
  const FlagFlowBody body(g, opt.circle_vertices, wet_reference);
  const Eigen::Matrix2Xd zero = Eigen::Matrix2Xd::Zero(2, n_wet);
  const std::unique_ptr<FlagCoupledStep> flag_step = immerse_flag(opt, flow, structure, g, body, dt);
  FlagCoupledStep& step = *flag_step;
  CouplingOptions co;
  co.convergence.relative_tolerance = opt.tolerance;
  co.convergence.absolute_tolerance = opt.absolute_tolerance;
  co.max_iterations = opt.max_iterations;
  co.divergence_iterations = opt.divergence_iterations;
  co.accept_at_cap = opt.accept_at_cap;
  const InterfaceLayout layout = step.layout();
  ImplicitCoupling coupling(layout, Eigen::VectorXd::Zero(layout.size()),
                            make_acceleration(opt.acceleration, layout, opt.omega), co);
  if (opt.progress && opt.progress_iterations)
    coupling.set_progress([&](const IterationReport& r) {
      opt.progress("  " + progress_line(r) + ", |x_out - x_in| " + printf_format("%.2e", r.absolute) + " m");
    });

  FsiOutput output(X0, {flag.point_a}, kRho, ubar, D * 1.0);
  TurekHronFsiRun run;
  const auto steps = static_cast<long>(std::ceil(t_end / dt - 1e-9));
  if (steps < 1) throw Error("turek_hron_fsi: t_end must be at least one time step");
  if (opt.checkpoint_every < 0) throw Error("turek_hron_fsi: expected checkpoint_every >= 0");
  const nlohmann::json config = run_config(opt, h, hc, dt, t_end);
  CoupledRunOptions ro;
  ro.name = "fsi";
  ro.steps = steps;
  ro.dt = dt;
  ro.checkpoint = opt.checkpoint;
  ro.checkpoint_every = opt.checkpoint_every;
  ro.restart = opt.restart;
  ro.may_differ = {"t_end"};
  if (opt.restart_new_coupling)
    ro.may_differ.insert({"acceleration", "omega0", "relative_tolerance", "absolute_tolerance", "max_iterations",
                          "accept_at_cap", "divergence_iterations"});
  ro.progress = opt.progress;
  ro.warm_start_repeats = !opt.cold_repeats;
  CoupledRun coupled(flow, structure, step, coupling, output, config, ro);
  FlagCase flag_case(run, step, structure, output, flag, X0, dt, opt.output_every);
  run.first_step = coupled.restart(flag_case);
  if (opt.hold_flag_rigid) {
    // The benchmark's reference cost: the same flow with the flag frozen in its current shape.
    const Eigen::VectorXd xs = structure.wet_positions();
    const Eigen::Matrix2Xd frozen = Eigen::Map<const Eigen::Matrix2Xd>(xs.data(), 2, n_wet);
    const auto rigid0 = std::chrono::steady_clock::now();
    for (long n = run.first_step + 1; n <= steps; ++n) {
      try {
        flow.set_body_state(body.state(frozen, zero, zero));
        (void)flow.step();
      } catch (const std::exception& e) {
        throw Error("fsi: step " + std::to_string(n) + " (flag held rigid): flow: " + e.what());
      }
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - rigid0).count();
    run.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    run.summary = Summary("validation", "fsi_turek_hron_rigid_flag", "Turek-Hron " + name + " flow, flag held rigid");
    run.summary.info("steps_this_run", static_cast<double>(steps - run.first_step));
    run.summary.info("wall_seconds_per_step", wall / static_cast<double>(steps - run.first_step), "s");
    run.summary.info("flow_cells", static_cast<double>(grid.cells()));
    run.summary.parameters() = config;
    run.summary.parameters()["hold_flag_rigid"] = true;
    return run;
  }
  if (!opt.paraview_dir.empty())
    flag_case.paraview = std::make_unique<FsiParaView>(opt.paraview_dir, opt.paraview_every, !opt.restart.empty());
  flag_case.flow = &flow;
  coupled.run(flag_case);
  run.statistics = coupled.statistics();
  run.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  const double loop_seconds = coupled.loop_seconds();
  std::unique_ptr<FsiParaView>& paraview = flag_case.paraview;

  RunFacts facts;
  facts.D = D;
  facts.ubar = ubar;
  facts.t_end = t_end;
  facts.loop_seconds = loop_seconds;
  facts.structure_energy = structure.kinetic_energy() + structure.strain_energy();
  facts.steps = steps;
  facts.flow_cells = static_cast<long>(grid.cells());
  run.summary = grade_turek_hron(opt, ref, run, config, facts);
  Summary& s = run.summary;

  if (paraview) paraview->write_structure(flag.model, output);
  if (!opt.fsi_h5.empty()) {
    Provenance p{"fin-fsi", s.parameters(), {opt.reference}};
    p.config["units"] = "2-D: forces per metre depth (N/m); reference_area = D x 1 m";
    output.write(opt.fsi_h5, p);
  }
  return run;
}

}  // namespace finverse::fsi::validation
