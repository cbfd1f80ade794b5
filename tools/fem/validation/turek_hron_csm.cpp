// Turek-Hron CSM1/CSM2 (static) and CSM3 (dynamic) with the Q9 SVK plane-strain solid (see
// turek_hron_csm.hpp).
#include "fem/validation/turek_hron_csm.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "fem/errors.hpp"
#include "fem/generalized_alpha.hpp"
#include "fem/model.hpp"
#include "fem/static_solver.hpp"
#include "fem/structured_mesh.hpp"

namespace finverse::fem::validation {

namespace {

const char* kSourcePrefix = "Turek & Hron 2006, LNCSE 53, table of CSM results (turek_hron.json ";

nlohmann::json read_reference_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InvalidInput("cannot open reference file " + path.string());
  try {
    return nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw InvalidInput("reference file " + path.string() + " is not valid JSON: " + e.what());
  }
}

// Value at a JSON pointer ("/cases/CSM1/E"), with a one-line error naming file and key.
const nlohmann::json& at(const nlohmann::json& j, const std::string& pointer,
                         const std::filesystem::path& path) {
  const nlohmann::json::json_pointer p(pointer);
  if (!j.contains(p)) throw InvalidInput(path.string() + ": missing " + pointer);
  return j.at(p);
}
double number(const nlohmann::json& j, const std::string& pointer, const std::filesystem::path& path) {
  const auto& v = at(j, pointer, path);
  if (!v.is_number()) throw InvalidInput(path.string() + ": " + pointer + " is not a number");
  return v.get<double>();
}
std::pair<double, double> pair_of(const nlohmann::json& j, const std::string& pointer,
                                  const std::filesystem::path& path) {
  const auto& v = at(j, pointer, path);
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
    throw InvalidInput(path.string() + ": " + pointer + " must be [mean, amplitude]");
  return {v[0].get<double>(), v[1].get<double>()};
}

// The benchmark's flag and solid, from turek_hron.json.
struct Flag {
  double xc = 0, yc = 0, radius = 0, length = 0, thickness = 0, xa = 0, ya = 0;
  double rho = 0, E = 0, nu = 0, g = 0;

  Flag(const nlohmann::json& j, const std::string& csm, const std::filesystem::path& path) {
    xc = number(j, "/geometry/cylinder_centre/0", path);
    yc = number(j, "/geometry/cylinder_centre/1", path);
    radius = number(j, "/geometry/cylinder_radius", path);
    length = number(j, "/geometry/flag_length", path);
    thickness = number(j, "/geometry/flag_thickness", path);
    xa = number(j, "/geometry/point_A/0", path);
    ya = number(j, "/geometry/point_A/1", path);
    nu = number(j, "/solid/nu_s", path);
    rho = number(j, "/cases/" + csm + "/rho_s", path);
    E = number(j, "/cases/" + csm + "/E", path);
    g = number(j, "/cases/" + csm + "/g", path);
    if (!(thickness < 2 * radius) || std::abs(xa - (xc + radius + length)) > 1e-9 ||
        std::abs(ya - yc) > 1e-12)
      throw InvalidInput(path.string() +
                         ": geometry inconsistent (point A must be the tip centre of a flag "
                         "starting at the cylinder's rear, thickness < diameter)");
  }
};

// Builds the meshed, clamped flag (turek_hron_flag.hpp). Gravity enters as the model's gravity
// (applied at once: dynamics) or, with `gravity_as_load`, as nodal loads scaled by the load factor
// (statics with load stepping: Model applies its own gravity at full value for every load factor).
TurekHronFlag build_flag(const Flag& flag, const FlagMesh& mesh, bool straight_clamp,
                         bool gravity_as_load) {
  TurekHronFlagSpec spec;
  spec.xc = flag.xc;
  spec.yc = flag.yc;
  spec.radius = flag.radius;
  spec.x_tip = flag.xa;
  spec.thickness = flag.thickness;
  spec.youngs_modulus = flag.E;
  spec.poisson_ratio = flag.nu;
  spec.density = flag.rho;
  spec.gravity = flag.g;
  spec.gravity_as_load = gravity_as_load;
  spec.mesh = mesh;
  spec.straight_clamp = straight_clamp;
  return build_turek_hron_flag(spec);
}

std::string mesh_name(const FlagMesh& m) {
  return std::to_string(m.nx) + "x" + std::to_string(m.ny);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Richardson extrapolation from three solutions on meshes refined by a constant ratio r.
struct Richardson {
  double order = NAN, extrapolated = NAN;
};
Richardson richardson(double f1, double f2, double f3, double r) {
  Richardson out;
  const double d12 = f2 - f1, d23 = f3 - f2;
  if (d12 == 0 || d23 == 0 || d12 * d23 < 0) return out;  // not in the asymptotic range
  out.order = std::log(d12 / d23) / std::log(r);
  out.extrapolated = f3 + d23 / (std::pow(r, out.order) - 1);
  return out;
}

// Refined extremum: vertex of the parabola through samples k-1, k, k+1 (equal spacing).
double parabola_peak(const std::vector<double>& s, std::size_t k) {
  if (k == 0 || k + 1 >= s.size()) return s[k];
  const double a = s[k - 1], b = s[k], c = s[k + 1];
  const double den = a - 2 * b + c;
  if (den == 0) return b;
  const double d = 0.5 * (a - c) / den;  // offset of the vertex, in samples
  if (std::abs(d) > 1) return b;
  return b - 0.25 * (a - c) * d;
}

}  // namespace

LastPeriod last_period(const std::vector<double>& time, const std::vector<double>& signal) {
  if (time.size() != signal.size() || time.size() < 3)
    throw InvalidInput("last_period: need matching time and signal with at least 3 samples");
  const auto [lo, hi] = std::minmax_element(signal.begin(), signal.end());
  const double mid = 0.5 * (*lo + *hi), half = 0.5 * (*hi - *lo);
  std::vector<double> up;  // times of accepted upward crossings
  bool armed = signal[0] < mid - 0.25 * half;
  for (std::size_t k = 1; k < signal.size(); ++k) {
    if (signal[k] < mid - 0.25 * half) armed = true;
    if (armed && signal[k - 1] < mid && signal[k] >= mid) {
      const double w = (mid - signal[k - 1]) / (signal[k] - signal[k - 1]);
      up.push_back(time[k - 1] + w * (time[k] - time[k - 1]));
      armed = false;
    }
  }
  if (up.size() < 2)
    throw NotConverged("last_period: fewer than two periods in the signal; simulate longer");
  LastPeriod p;
  p.periods = static_cast<int>(up.size()) - 1;
  p.t_begin = up[up.size() - 2];
  p.t_end = up.back();
  p.frequency = 1.0 / (p.t_end - p.t_begin);
  // The first period carries the start-up transient of the higher modes; average the others.
  const std::size_t first = up.size() > 2 ? 1 : 0;
  p.mean_frequency = (up.size() - 1 - first) / (up.back() - up[first]);
  return p;
}

MeanAmplitude mean_amplitude(const std::vector<double>& time, const std::vector<double>& signal,
                             double t_begin, double t_end) {
  std::size_t kmax = 0, kmin = 0;
  bool any = false;
  for (std::size_t k = 0; k < time.size(); ++k) {
    if (time[k] < t_begin || time[k] > t_end) continue;
    if (!any || signal[k] > signal[kmax]) kmax = k;
    if (!any || signal[k] < signal[kmin]) kmin = k;
    any = true;
  }
  if (!any) throw InvalidInput("mean_amplitude: no samples in the window");
  const double mx = parabola_peak(signal, kmax), mn = parabola_peak(signal, kmin);
  return {0.5 * (mx + mn), 0.5 * (mx - mn)};
}

Summary run_turek_hron_csm_static(const CsmStaticOptions& opt) {
  if (opt.case_number != 1 && opt.case_number != 2)
    throw InvalidInput("turek_hron_csm: case number must be 1 or 2, got " +
                       std::to_string(opt.case_number));
  const std::string csm = "CSM" + std::to_string(opt.case_number);
  const nlohmann::json ref = read_reference_json(opt.reference);
  const Flag flag(ref, csm, opt.reference);
  const double ux_ref = number(ref, "/cases/" + csm + "/ux_A", opt.reference);
  const double uy_ref = number(ref, "/cases/" + csm + "/uy_A", opt.reference);
  const std::string source = kSourcePrefix + std::string("cases/") + csm + ")";

  std::vector<FlagMesh> meshes = opt.meshes;
  if (meshes.empty()) {
    if (opt.coarse)
      meshes = {{5, 1, 3.0}, {10, 1, 3.0}, {20, 2, 3.0}};
    else
      meshes = {{5, 1, 3.0}, {10, 1, 3.0}, {20, 2, 3.0}, {40, 4, 3.0}, {80, 8, 3.0}};
  }

  Summary report(
      "validation", "turek_hron_csm" + std::to_string(opt.case_number),
      "Turek-Hron " + csm +
      ": static deflection of the elastic flag under gravity, St. Venant-Kirchhoff plane strain, "
      "Q9 total-Lagrangian elements, load-controlled Newton; tip (point A) displacement with a "
      "mesh convergence study");
  nlohmann::json study = nlohmann::json::array();

  std::vector<double> ux, uy;
  for (const FlagMesh& mesh : meshes) {
    const auto t0 = std::chrono::steady_clock::now();
    const TurekHronFlag fm = build_flag(flag, mesh, opt.straight_clamp, true);
    StaticOptions so;
    so.steps = opt.load_steps;
    so.backend = opt.backend;
    StaticSolver solver(fm.model, so);
    NodalState state = fm.model.reference_state();
    const StaticResult r = solver.solve(state, 0.0, 1.0);
    const Vec3 u = state.position[fm.point_a] - fm.model.reference_positions()[fm.point_a];
    ux.push_back(u.x());
    uy.push_back(u.y());
    double reaction_y = 0;
    for (int g = 1; g < r.reaction.size(); g += kDofsPerNode) reaction_y += r.reaction(g);
    const double wall = seconds_since(t0);
    study.push_back({{"mesh", mesh_name(mesh)},
                     {"nx", mesh.nx},
                     {"ny", mesh.ny},
                     {"grading", mesh.grading},
                     {"free_dofs", solver.dofs().free()},
                     {"ux_A_m", u.x()},
                     {"uy_A_m", u.y()},
                     {"newton_iterations", r.total_iterations},
                     {"reaction_y_over_weight", reaction_y / (fm.mass * flag.g)},
                     {"wall_s", wall}});
    const std::string tag = "_" + mesh_name(mesh);
    report.info("ux_A" + tag, u.x(), "m");
    report.info("uy_A" + tag, u.y(), "m");
    report.info("free_dofs" + tag, solver.dofs().free());
    // Equilibrium of the whole flag: the clamp carries the weight, up to the Newton residual.
    report.info("reaction_over_weight" + tag, reaction_y / (fm.mass * flag.g));
  }

  const std::size_t n = meshes.size();
  report.relative("ux_A", ux.back(), ux_ref, opt.tolerance, source, "m");
  report.relative("uy_A", uy.back(), uy_ref, opt.tolerance, source, "m");
  if (n >= 3 && meshes[n - 1].nx == 2 * meshes[n - 2].nx && meshes[n - 2].nx == 2 * meshes[n - 3].nx) {
    const Richardson rx = richardson(ux[n - 3], ux[n - 2], ux[n - 1], 2.0);
    const Richardson ry = richardson(uy[n - 3], uy[n - 2], uy[n - 1], 2.0);
    report.info("ux_A_observed_order", rx.order);
    report.info("uy_A_observed_order", ry.order);
    report.info("ux_A_extrapolated", rx.extrapolated, "m");
    report.info("uy_A_extrapolated", ry.extrapolated, "m");
  }
  if (n >= 2) {
    report.info("ux_A_change_last_refinement", std::abs(ux[n - 1] - ux[n - 2]) / std::abs(ux[n - 1]));
    report.info("uy_A_change_last_refinement", std::abs(uy[n - 1] - uy[n - 2]) / std::abs(uy[n - 1]));
  }
  report.parameters() = {{"case", csm},
                         {"youngs_modulus_Pa", flag.E},
                         {"poisson_ratio", flag.nu},
                         {"density_kg_m3", flag.rho},
                         {"gravity_m_s2", flag.g},
                         {"element", "plane_strain_q9 (St. Venant-Kirchhoff, total Lagrangian, 3x3 Gauss)"},
                         {"clamp", opt.straight_clamp ? "straight at x = xc + sqrt(r^2 - (h/2)^2)"
                                                      : "cylinder arc"},
                         {"coarse", opt.coarse},
                         {"load_steps", opt.load_steps},
                         {"solver", to_string(opt.backend)},
                         {"reference", opt.reference.string()},
                         {"mesh_study", study}};
  return report;
}

namespace {

struct Csm3Run {
  std::vector<double> t, ux, uy;
  int free_dofs = 0;
  long iterations = 0;
  long steps = 0;
  double energy_drift = 0;  // max |H(t) - H(0)| / max strain energy, H = T + U - f_g . u
  double wall = 0;
};

Csm3Run simulate_csm3(const Flag& flag, const FlagMesh& mesh, double dt, const Csm3Options& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  const TurekHronFlag fm = build_flag(flag, mesh, opt.straight_clamp, false);
  DynamicOptions dyn;
  dyn.time_step = dt;
  dyn.spectral_radius = opt.spectral_radius;
  dyn.residual_tolerance = opt.residual_tolerance;
  dyn.backend = opt.backend;
  GeneralizedAlpha integrator(fm.model, dyn);
  DynamicState s = integrator.reference_state(0.0);
  integrator.initialize(s);
  const Eigen::VectorXd fg = fm.model.gravity_load();
  const auto& X = fm.model.reference_positions();
  auto potential = [&](const DynamicState& st) {
    double w = 0;
    for (int i = 0; i < st.configuration.node_count(); ++i)
      w += fg.segment<3>(kDofsPerNode * i).dot(st.configuration.position[i] - X[i]);
    return -w;
  };
  const double h0 = integrator.kinetic_energy(s) + integrator.strain_energy(s) + potential(s);
  Csm3Run run;
  run.free_dofs = integrator.dofs().free();
  const long steps = std::lround(opt.end_time / dt);
  run.t.reserve(steps + 1);
  run.ux.reserve(steps + 1);
  run.uy.reserve(steps + 1);
  auto record = [&] {
    const Vec3 u = s.configuration.position[fm.point_a] - X[fm.point_a];
    run.t.push_back(s.time);
    run.ux.push_back(u.x());
    run.uy.push_back(u.y());
  };
  record();
  double drift = 0, u_max = 0;
  for (long k = 0; k < steps; ++k) {
    run.iterations += integrator.step(s).iterations;
    record();
    const double U = integrator.strain_energy(s);
    const double H = integrator.kinetic_energy(s) + U + potential(s);
    drift = std::max(drift, std::abs(H - h0));
    u_max = std::max(u_max, U);
  }
  run.steps = steps;
  run.energy_drift = u_max > 0 ? drift / u_max : 0;
  run.wall = seconds_since(t0);
  return run;
}

struct Csm3Result {
  MeanAmplitude ux, uy;
  LastPeriod period;
};
Csm3Result evaluate(const Csm3Run& run) {
  Csm3Result r;
  r.period = last_period(run.t, run.uy);
  r.ux = mean_amplitude(run.t, run.ux, r.period.t_begin, r.period.t_end);
  r.uy = mean_amplitude(run.t, run.uy, r.period.t_begin, r.period.t_end);
  return r;
}

std::string dt_name(double dt) {
  std::ostringstream os;
  os << dt;
  return os.str();
}

}  // namespace

Summary run_turek_hron_csm3(const Csm3Options& opt) {
  const std::string csm = "CSM3";
  const nlohmann::json ref = read_reference_json(opt.reference);
  const Flag flag(ref, csm, opt.reference);
  const auto [ux_mean_ref, ux_amp_ref] = pair_of(ref, "/cases/CSM3/ux_A", opt.reference);
  const auto [uy_mean_ref, uy_amp_ref] = pair_of(ref, "/cases/CSM3/uy_A", opt.reference);
  const double f_ref = number(ref, "/cases/CSM3/freq", opt.reference);
  const std::string source = kSourcePrefix + std::string("cases/CSM3, mean +- amplitude)");
  if (!(opt.end_time > 0)) throw InvalidInput("turek_hron_csm3: end time must be > 0");

  FlagMesh mesh = opt.mesh;
  std::vector<double> dts = opt.time_steps;
  if (opt.coarse) {
    mesh = {10, 1, 3.0};
    if (dts.empty()) dts = {0.01};
  } else if (dts.empty()) {
    dts = {0.01, 0.005, 0.0025, 0.00125};
  }
  for (double dt : dts)
    if (!(dt > 0)) throw InvalidInput("turek_hron_csm3: time steps must be > 0");

  Summary report(
      "validation", "turek_hron_csm3",
      "Turek-Hron CSM3: the elastic flag released from rest under gravity, undamped; St. "
      "Venant-Kirchhoff plane strain, Q9 total-Lagrangian elements, generalized-alpha with "
      "consistent mass; mean, amplitude and frequency of the tip (point A) displacement over the "
      "last period, with a time-step study");
  nlohmann::json study = nlohmann::json::array();
  auto add_study = [&](const FlagMesh& m, double dt, const Csm3Run& run, const Csm3Result& r) {
    study.push_back({{"mesh", mesh_name(m)},
                     {"dt_s", dt},
                     {"free_dofs", run.free_dofs},
                     {"ux_A_mean_m", r.ux.mean},
                     {"ux_A_amplitude_m", r.ux.amplitude},
                     {"uy_A_mean_m", r.uy.mean},
                     {"uy_A_amplitude_m", r.uy.amplitude},
                     {"frequency_last_period_Hz", r.period.frequency},
                     {"frequency_mean_Hz", r.period.mean_frequency},
                     {"periods", r.period.periods},
                     {"newton_iterations_per_step", static_cast<double>(run.iterations) / run.steps},
                     {"energy_drift_over_max_strain_energy", run.energy_drift},
                     {"wall_s", run.wall}});
    const std::string tag = "_" + mesh_name(m) + "_dt" + dt_name(dt);
    report.info("ux_A_mean" + tag, r.ux.mean, "m");
    report.info("ux_A_amplitude" + tag, r.ux.amplitude, "m");
    report.info("uy_A_mean" + tag, r.uy.mean, "m");
    report.info("uy_A_amplitude" + tag, r.uy.amplitude, "m");
    report.info("frequency" + tag, r.period.frequency, "Hz");
    report.info("energy_drift" + tag, run.energy_drift);
  };

  Csm3Result graded;
  Csm3Run graded_run;
  for (double dt : dts) {
    Csm3Run run = simulate_csm3(flag, mesh, dt, opt);
    const Csm3Result r = evaluate(run);
    add_study(mesh, dt, run, r);
    graded = r;
    graded_run = std::move(run);
  }
  for (const FlagMesh& m : opt.coarse ? std::vector<FlagMesh>{} : opt.check_meshes) {
    const Csm3Run run = simulate_csm3(flag, m, dts.back(), opt);
    add_study(m, dts.back(), run, evaluate(run));
  }

  report.relative("ux_A_mean", graded.ux.mean, ux_mean_ref, opt.tolerance, source, "m");
  report.relative("ux_A_amplitude", graded.ux.amplitude, ux_amp_ref, opt.tolerance, source, "m");
  report.relative("uy_A_mean", graded.uy.mean, uy_mean_ref, opt.tolerance, source, "m");
  report.relative("uy_A_amplitude", graded.uy.amplitude, uy_amp_ref, opt.tolerance, source, "m");
  report.relative("frequency", graded.period.frequency, f_ref, opt.tolerance, source, "Hz");
  report.info("frequency_mean_all_periods", graded.period.mean_frequency, "Hz");
  report.info("last_period_begin", graded.period.t_begin, "s");
  report.info("last_period_end", graded.period.t_end, "s");
  report.info("energy_drift", graded_run.energy_drift);
  report.info("free_dofs", graded_run.free_dofs);
  report.info("newton_iterations_per_step",
              static_cast<double>(graded_run.iterations) / graded_run.steps);

  report.parameters() = {{"case", csm},
                         {"youngs_modulus_Pa", flag.E},
                         {"poisson_ratio", flag.nu},
                         {"density_kg_m3", flag.rho},
                         {"gravity_m_s2", flag.g},
                         {"element", "plane_strain_q9 (St. Venant-Kirchhoff, total Lagrangian, 3x3 Gauss)"},
                         {"mesh", mesh_name(mesh)},
                         {"grading", mesh.grading},
                         {"time_steps_s", dts},
                         {"graded_time_step_s", dts.back()},
                         {"spectral_radius", opt.spectral_radius},
                         {"newton_residual_tolerance", opt.residual_tolerance},
                         {"end_time_s", opt.end_time},
                         {"clamp", opt.straight_clamp ? "straight at x = xc + sqrt(r^2 - (h/2)^2)"
                                                      : "cylinder arc"},
                         {"coarse", opt.coarse},
                         {"solver", to_string(opt.backend)},
                         {"reference", opt.reference.string()},
                         {"study", study}};
  return report;
}

}  // namespace finverse::fem::validation
