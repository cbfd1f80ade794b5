// Hybrid plate against CalculiX, static and dynamic (see hybrid_plate.hpp).
#include "fem/validation/hybrid_plate.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <utility>

#include <nlohmann/json.hpp>

#include "fem/errors.hpp"
#include "fem/generalized_alpha.hpp"
#include "fem/static_solver.hpp"
#include "fem/validation/hybrid_plate_model.hpp"

namespace finverse::fem::validation {
namespace {

nlohmann::json read_reference(const std::filesystem::path& path, const char* analysis) {
  std::ifstream in(path);
  if (!in) throw InvalidInput("cannot open CalculiX reference " + path.string());
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw InvalidInput("CalculiX reference " + path.string() + " is not valid JSON: " + e.what());
  }
  if (!j.contains(analysis) || !j[analysis].is_object() || !j[analysis].contains("tips_y"))
    throw InvalidInput(path.string() + ": missing object '" + std::string(analysis) +
                       "' with 'tips_y' (write it with calculix_hybrid_plate.py --reference-out)");
  return j;
}

std::string source_of(const nlohmann::json& ref, const char* analysis) {
  const auto& a = ref[analysis];
  const std::string method =
      a.value("method", std::string("")) == "modal"
          ? " modal superposition of " + std::to_string(a.value("modes", 0)) + " modes (linear) "
          : " NLGEOM ";
  return ref.value("peer", std::string("CalculiX")) + " S8R/B32R" + method +
         std::to_string(a.value("nx", 0)) + "x" + std::to_string(a.value("nz", 0)) + ", " +
         ref.value("date", std::string("?"));
}

// Complex amplitude of v(t) at frequency f by projection over [0, t_end] (trapezoidal rule on
// the given samples); t_end spans whole periods of the drive, so the drive component separates
// from the mean. Returns {amplitude, phase} of v ~ amplitude cos(2 pi f t - phase).
std::pair<double, double> harmonic(const std::vector<double>& t, const std::vector<double>& v,
                                   double f) {
  double c = 0, s = 0;
  for (size_t k = 1; k < t.size(); ++k) {
    const double h = 0.5 * (t[k] - t[k - 1]);
    const double a0 = 2 * std::numbers::pi * f * t[k - 1], a1 = 2 * std::numbers::pi * f * t[k];
    c += h * (v[k - 1] * std::cos(a0) + v[k] * std::cos(a1));
    s += h * (v[k - 1] * std::sin(a0) + v[k] * std::sin(a1));
  }
  const double span = t.back() - t.front();
  return {2 * std::hypot(c, s) / span, std::atan2(s, c)};
}

void common_parameters(Summary& r, const HybridPlateOptions& o, const HybridPlateModel& hp,
                       const nlohmann::json& ref) {
  r.parameters() = {{"case", o.case_file.string()}, {"reference", o.reference.string()},
                    {"cells_chord", o.nx}, {"cells_span", o.nz},
                    {"shell_triangles", hp.shell_elements}, {"beam_elements", hp.beam_elements},
                    {"nodes", hp.model.node_count()}, {"solver", to_string(o.backend)},
                    {"calculix_command", ref.value("command", std::string())},
                    {"calculix_version", ref.value("peer", std::string())}};
}

}  // namespace

Summary run_hybrid_plate_static(const HybridPlateOptions& opt) {
  const HybridPlateCase c = read_hybrid_plate_case(opt.case_file);
  const nlohmann::json ref = read_reference(opt.reference, "static");
  HybridPlateModel hp = build_hybrid_plate(c, opt.nx, opt.nz, HybridPlateLoad::pressure);

  Summary report(
      "validation", "hybrid_plate_static",
      "Hybrid plate (seed paper sec. 3.4, data/cases/hybrid_plate.json): square shell plate with "
      "three beams of different moduli on shared nodes, dead uniform pressure, leading edge "
      "clamped; beam-tip deflections against CalculiX NLGEOM (S8R + B32R, converged mesh)");
  common_parameters(report, opt, hp, ref);
  report.parameters()["pressure"] = c.pressure;

  StaticOptions so;
  so.backend = opt.backend;
  so.steps = c.load_steps;
  NodalState state = hp.model.reference_state();
  StaticSolver solver(hp.model, so);
  const StaticResult r = solver.solve(state, 0.0, 1.0);
  const std::string source = source_of(ref, "static");
  for (size_t b = 0; b < c.beams.size(); ++b) {
    const auto& name = c.beams[b].name;
    if (!ref["static"]["tips_y"].contains(name))
      throw InvalidInput(opt.reference.string() + ": static.tips_y lacks beam " + name);
    const int n = hp.tips[b];
    const double uy = state.position[n].y() - hp.model.reference_positions()[n].y();
    report.relative("tip_uy_" + name, uy, ref["static"]["tips_y"][name].get<double>(),
                    opt.tolerance, source);
  }
  report.info("newton_iterations", r.total_iterations);
  report.info("step_cuts", r.step_cuts);
  return report;
}

Summary run_hybrid_plate_dynamic(const HybridPlateOptions& opt) {
  const HybridPlateCase c = read_hybrid_plate_case(opt.case_file);
  const nlohmann::json ref = read_reference(opt.reference, "dynamic");
  HybridPlateModel hp = build_hybrid_plate(c, opt.nx, opt.nz, HybridPlateLoad::heave);
  const auto& rd = ref["dynamic"];
  if (!rd.contains("time") || !rd["time"].is_array() || rd["time"].empty())
    throw InvalidInput(opt.reference.string() + ": dynamic.time must be a non-empty array");
  const std::vector<double> t_ref = rd["time"].get<std::vector<double>>();
  // The reference holds one heave; comparing another case's histories against it is meaningless.
  for (const auto& [key, value] : {std::pair<const char*, double>{"heave_amplitude", c.heave_amplitude},
                                   std::pair<const char*, double>{"frequency", c.frequency}})
    if (rd.contains(key) && std::abs(rd[key].get<double>() - value) > 1e-12 * std::abs(value))
      throw InvalidInput(opt.reference.string() + ": dynamic." + key + " = " +
                         std::to_string(rd[key].get<double>()) + " differs from the case's " +
                         std::to_string(value) + " (" + opt.case_file.string() + ")");

  Summary report(
      "validation", "hybrid_plate_dynamic",
      "Hybrid plate (seed paper sec. 3.4) heaved at the leading edge in vacuo from rest, "
      "generalized-alpha rho_inf = 1; tip deflection relative to the leading edge, "
      "w = u_y,tip - y_LE, over the history against CalculiX (S8R + B32R, finest mesh of its study; "
      "the reference is exact in time: ccx's eigenmodes superposed analytically, see "
      "tools/scripts/calculix_hybrid_plate.py): max history error, peak-to-peak range, and "
      "amplitude and phase of the component at the drive frequency");
  common_parameters(report, opt, hp, ref);
  const double periods = opt.periods > 0 ? std::min(opt.periods, c.periods) : c.periods;
  const double t_end = periods / c.frequency;
  const double dt = opt.time_step > 0 ? opt.time_step : c.time_step;
  report.parameters()["time_step"] = dt;
  report.parameters()["periods"] = periods;
  report.parameters()["heave_amplitude"] = c.heave_amplitude;
  report.parameters()["frequency"] = c.frequency;
  report.parameters()["spectral_radius"] = 1.0;

  DynamicOptions dyn;
  dyn.time_step = dt;
  dyn.spectral_radius = 1.0;
  dyn.backend = opt.backend;
  GeneralizedAlpha integrator(hp.model, dyn);
  DynamicState s = integrator.reference_state(0.0);
  integrator.initialize(s);
  const int steps = static_cast<int>(std::lround(t_end / dt));
  const size_t nb = c.beams.size();
  std::vector<double> time{0.0};
  std::vector<std::vector<double>> w(nb, std::vector<double>{0.0});
  int iterations = 0;
  for (int k = 0; k < steps; ++k) {
    iterations += integrator.step(s).iterations;
    time.push_back(s.time);
    for (size_t b = 0; b < nb; ++b) {
      const int n = hp.tips[b];
      w[b].push_back(s.configuration.position[n].y() - hp.model.reference_positions()[n].y() -
                     c.heave(s.time));
    }
  }
  // Linear interpolation of our history at CalculiX's output times (the same steps when the
  // time steps agree).
  auto ours_at = [&](const std::vector<double>& v, double t) {
    const auto it = std::upper_bound(time.begin(), time.end(), t);
    if (it == time.begin()) return v.front();
    if (it == time.end()) return v.back();
    const size_t i = static_cast<size_t>(it - time.begin());
    const double a = (t - time[i - 1]) / (time[i] - time[i - 1]);
    return (1 - a) * v[i - 1] + a * v[i];
  };

  const std::string source = source_of(ref, "dynamic");
  std::vector<double> t_cmp;  // CalculiX's output times within our history
  for (double t : t_ref)
    if (t <= t_end * (1 + 1e-9)) t_cmp.push_back(t);
  if (t_cmp.size() < 2)
    throw InvalidInput(opt.reference.string() + ": fewer than two dynamic.time values within the "
                       "simulated " + std::to_string(t_end) + " s");
  std::vector<std::vector<double>> w_ours(nb), w_ccx(nb);
  for (size_t b = 0; b < nb; ++b) {
    const auto& name = c.beams[b].name;
    if (!rd["tips_y"].contains(name))
      throw InvalidInput(opt.reference.string() + ": dynamic.tips_y lacks beam " + name);
    const std::vector<double> u_ref = rd["tips_y"][name].get<std::vector<double>>();
    if (u_ref.size() != t_ref.size())
      throw InvalidInput(opt.reference.string() + ": dynamic.tips_y." + name +
                         " and dynamic.time differ in length");
    for (size_t k = 0; k < t_cmp.size(); ++k) {
      w_ccx[b].push_back(u_ref[k] - c.heave(t_cmp[k]));
      w_ours[b].push_back(ours_at(w[b], t_cmp[k]));
    }
    const auto [ref_min, ref_max] = std::minmax_element(w_ccx[b].begin(), w_ccx[b].end());
    const auto [our_min, our_max] = std::minmax_element(w_ours[b].begin(), w_ours[b].end());
    const double range_ref = *ref_max - *ref_min, range_ours = *our_max - *our_min;
    double max_error = 0;
    for (size_t k = 0; k < t_cmp.size(); ++k)
      max_error = std::max(max_error, std::abs(w_ours[b][k] - w_ccx[b][k]));
    report.at_most("tip_deflection_history_error_" + name, max_error / range_ref, opt.tolerance,
                   "max over the history of |w - w_ccx| / (max w_ccx - min w_ccx), " + source);
    report.relative("tip_deflection_range_" + name, range_ours, range_ref, opt.tolerance, source);
    // Both start from rest, w(0) = 0: the projection runs from t = 0 (whole drive periods).
    std::vector<double> t0, ours0, ccx0;
    if (t_cmp.front() > 0) t0 = ours0 = ccx0 = {0.0};
    t0.insert(t0.end(), t_cmp.begin(), t_cmp.end());
    ours0.insert(ours0.end(), w_ours[b].begin(), w_ours[b].end());
    ccx0.insert(ccx0.end(), w_ccx[b].begin(), w_ccx[b].end());
    const auto [amp_ours, phase_ours] = harmonic(t0, ours0, c.frequency);
    const auto [amp_ref, phase_ref] = harmonic(t0, ccx0, c.frequency);
    report.relative("tip_drive_amplitude_" + name, amp_ours, amp_ref, opt.tolerance, source);
    // Phase difference wrapped to (-pi, pi], graded as a fraction of the drive period.
    const double dphi = std::remainder(phase_ours - phase_ref, 2 * std::numbers::pi);
    report.at_most("tip_drive_phase_error_" + name, std::abs(dphi) / (2 * std::numbers::pi),
                   opt.tolerance, "|phase - phase_ccx| / 2 pi at the drive frequency, " + source);
  }
  if (!opt.history.empty()) {
    const std::filesystem::path tmp = opt.history.string() + ".tmp";
    {
      std::ofstream out(tmp);
      if (!out) throw InvalidInput("cannot write --history " + opt.history.string());
      out << "t";
      for (const auto& b : c.beams) out << ",w_" << b.name << ",w_ccx_" << b.name;
      out << "\n";
      out.precision(10);
      for (size_t k = 0; k < t_cmp.size(); ++k) {
        out << t_cmp[k];
        for (size_t b = 0; b < nb; ++b) out << "," << w_ours[b][k] << "," << w_ccx[b][k];
        out << "\n";
      }
      if (!out) throw InvalidInput("cannot write --history " + opt.history.string());
    }
    std::filesystem::rename(tmp, opt.history);
  }
  report.info("time_steps", steps);
  report.info("newton_iterations", iterations);
  return report;
}

}  // namespace finverse::fem::validation
