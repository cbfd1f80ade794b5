// Hybrid plate against CalculiX, static and dynamic (see hybrid_plate.hpp).
#include "hybrid_plate.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

#include <nlohmann/json.hpp>

#include "fem/errors.hpp"
#include "fem/generalized_alpha.hpp"
#include "fem/static_newton.hpp"
#include "hybrid_plate_model.hpp"

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
  return ref.value("peer", std::string("CalculiX")) + " S8R/B32R NLGEOM " +
         std::to_string(a.value("nx", 0)) + "x" + std::to_string(a.value("nz", 0)) + ", " +
         ref.value("date", std::string("?"));
}

void common_parameters(Report& r, const HybridPlateOptions& o, const HybridPlateModel& hp,
                       const nlohmann::json& ref) {
  r.parameters = {{"case", o.case_file.string()}, {"reference", o.reference.string()},
                  {"cells_chord", o.nx}, {"cells_span", o.nz},
                  {"shell_triangles", hp.shell_elements}, {"beam_elements", hp.beam_elements},
                  {"nodes", hp.model.node_count()}, {"solver", to_string(o.backend)},
                  {"calculix_command", ref.value("command", std::string())},
                  {"calculix_version", ref.value("peer", std::string())}};
}

}  // namespace

Report run_hybrid_plate_static(const HybridPlateOptions& opt) {
  const HybridPlateCase c = read_hybrid_plate_case(opt.case_file);
  const nlohmann::json ref = read_reference(opt.reference, "static");
  HybridPlateModel hp = build_hybrid_plate(c, opt.nx, opt.nz, HybridPlateLoad::pressure);

  Report report;
  report.name = "hybrid_plate_static";
  report.description =
      "Hybrid plate (seed paper sec. 3.4, data/cases/hybrid_plate.json): square shell plate with "
      "three beams of different moduli on shared nodes, dead uniform pressure, leading edge "
      "clamped; beam-tip deflections against CalculiX NLGEOM (S8R + B32R, converged mesh)";
  common_parameters(report, opt, hp, ref);
  report.parameters["pressure"] = c.pressure;

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

Report run_hybrid_plate_dynamic(const HybridPlateOptions& opt) {
  const HybridPlateCase c = read_hybrid_plate_case(opt.case_file);
  const nlohmann::json ref = read_reference(opt.reference, "dynamic");
  HybridPlateModel hp = build_hybrid_plate(c, opt.nx, opt.nz, HybridPlateLoad::heave);
  const auto& rd = ref["dynamic"];
  if (!rd.contains("time") || !rd["time"].is_array() || rd["time"].empty())
    throw InvalidInput(opt.reference.string() + ": dynamic.time must be a non-empty array");
  const std::vector<double> t_ref = rd["time"].get<std::vector<double>>();

  Report report;
  report.name = "hybrid_plate_dynamic";
  report.description =
      "Hybrid plate (seed paper sec. 3.4) heaved at the leading edge in vacuo from rest, "
      "generalized-alpha rho_inf = 1 (trapezoidal, as CalculiX ALPHA = 0) with CalculiX's time "
      "step; tip deflection relative to the leading edge over the history against CalculiX "
      "NLGEOM (S8R + B32R, converged mesh)";
  common_parameters(report, opt, hp, ref);
  const double periods = opt.periods > 0 ? std::min(opt.periods, c.periods) : c.periods;
  const double t_end = periods / c.frequency;
  report.parameters["time_step"] = c.time_step;
  report.parameters["periods"] = periods;
  report.parameters["heave_amplitude"] = c.heave_amplitude;
  report.parameters["frequency"] = c.frequency;
  report.parameters["spectral_radius"] = 1.0;

  DynamicOptions dyn;
  dyn.time_step = c.time_step;
  dyn.spectral_radius = 1.0;
  dyn.backend = opt.backend;
  GeneralizedAlpha integrator(hp.model, dyn);
  DynamicState s = integrator.reference_state(0.0);
  integrator.initialize(s);
  const int steps = static_cast<int>(std::lround(t_end / c.time_step));
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
  for (size_t b = 0; b < nb; ++b) {
    const auto& name = c.beams[b].name;
    if (!rd["tips_y"].contains(name))
      throw InvalidInput(opt.reference.string() + ": dynamic.tips_y lacks beam " + name);
    const std::vector<double> u_ref = rd["tips_y"][name].get<std::vector<double>>();
    if (u_ref.size() != t_ref.size())
      throw InvalidInput(opt.reference.string() + ": dynamic.tips_y." + name +
                         " and dynamic.time differ in length");
    double amplitude = 0, max_error = 0, peak_ref = 0, peak_ours = 0;
    for (size_t k = 0; k < t_ref.size() && t_ref[k] <= t_end * (1 + 1e-9); ++k) {
      const double w_ref = u_ref[k] - c.heave(t_ref[k]);
      const double w_ours = ours_at(w[b], t_ref[k]);
      amplitude = std::max(amplitude, std::abs(w_ref));
      max_error = std::max(max_error, std::abs(w_ours - w_ref));
      if (std::abs(w_ref) > std::abs(peak_ref)) peak_ref = w_ref;
    }
    for (double v : w[b])
      if (std::abs(v) > std::abs(peak_ours)) peak_ours = v;
    report.at_most("tip_deflection_history_error_" + name, max_error / amplitude, opt.tolerance,
                   "max over the history of |w - w_ccx| / max |w_ccx|, " + source);
    report.relative("tip_deflection_peak_" + name, peak_ours, peak_ref, opt.tolerance, source);
  }
  report.info("time_steps", steps);
  report.info("newton_iterations", iterations);
  return report;
}

}  // namespace finverse::fem::validation
