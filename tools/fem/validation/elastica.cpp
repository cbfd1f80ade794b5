// Elastica validation: cantilever with a dead tip load perpendicular to the undeformed axis,
// solved with corotational beams and load-controlled Newton; compared with the shooting solution
// of EI theta'' = -P cos(theta) in structures.json ("elastica_tip_load").
#include "fem/validation/cases.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "fem/errors.hpp"
#include "fem/model.hpp"
#include "fem/static_solver.hpp"

namespace finverse::fem::validation {

namespace {
nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InvalidInput("cannot open reference file " + path.string());
  try {
    return nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw InvalidInput("reference file " + path.string() + " is not valid JSON: " + e.what());
  }
}

double lookup(const nlohmann::json& table, const std::string& column, double load,
              const std::filesystem::path& path) {
  const auto& loads = table.at("PL2_EI");
  for (size_t i = 0; i < loads.size(); ++i)
    if (std::abs(loads[i].get<double>() - load) < 1e-12) return table.at(column).at(i).get<double>();
  std::ostringstream os;
  os << path.string() << ": elastica_tip_load has no entry for PL2_EI = " << load;
  throw InvalidInput(os.str());
}
}  // namespace

Summary run_elastica(const ElasticaOptions& opt) {
  const nlohmann::json ref_all = read_json(opt.reference);
  if (!ref_all.contains("elastica_tip_load"))
    throw InvalidInput(opt.reference.string() + ": missing object 'elastica_tip_load'");
  const nlohmann::json& ref = ref_all["elastica_tip_load"];
  const std::string source = "structures.json elastica_tip_load: " + ref.value("source", std::string());

  // A slender steel-like strip; only PL^2/EI matters as long as axial strain stays negligible
  // (EA L^2 / EI = 12 (L/t)^2 = 1.2e6 here).
  const double L = 1.0, width = 0.02, thickness = 0.001, E = 2.0e11, nu = 0.3, rho = 7800;
  const double EI = E * width * thickness * thickness * thickness / 12.0;
  if (opt.elements < 1) throw InvalidInput("elastica: --elements must be >= 1");

  Model model;
  const int mat = model.add_material({"strip", E, nu, rho});
  for (int i = 0; i <= opt.elements; ++i) model.add_node(Vec3(L * i / opt.elements, 0, 0));
  for (int i = 0; i < opt.elements; ++i)
    model.add_beam(i, i + 1, mat, TaperedRectangle::uniform(width, thickness), Vec3(0, 1, 0));
  model.fix_node(0);
  const int tip = opt.elements;
  // Reference load EI/L^2 in +z (bending about the thin direction): lambda = PL^2/EI.
  model.add_nodal_load(tip, 2, EI / (L * L));

  Summary report(
      "validation", "elastica_beam",
      "Cantilever under a dead tip load perpendicular to its axis (large-deflection elastica); "
      "corotational Euler-Bernoulli beams, load-controlled Newton; tip deflection, shortening and "
      "rotation against the shooting solution");
  report.parameters() = {{"length_m", L},          {"width_m", width},
                         {"thickness_m", thickness}, {"youngs_modulus_Pa", E},
                         {"elements", opt.elements}, {"load_steps_per_unit", opt.load_steps_per_unit},
                         {"solver", to_string(opt.backend)}, {"reference", opt.reference.string()}};

  StaticOptions so;
  so.backend = opt.backend;
  NodalState state = model.reference_state();
  double lam = 0;
  int iterations = 0, cuts = 0;
  for (double target : {1.0, 2.0, 5.0, 10.0, 20.0}) {
    so.steps = std::max(1, static_cast<int>(std::lround((target - lam) * opt.load_steps_per_unit)));
    StaticSolver stepper(model, so);  // the step count is a solver option
    const StaticResult r = stepper.solve(state, lam, target);
    iterations += r.total_iterations;
    cuts += r.step_cuts;
    lam = target;
    const Vec3 x = state.position[tip];
    const Vec3 tangent = state.rotation[tip] * Vec3::UnitX();
    const double w = x.z() / L, s = (L - x.x()) / L, theta = std::atan2(tangent.z(), tangent.x());
    std::ostringstream tag;
    tag << "@PL2/EI=" << target;
    report.relative("w_tip_L" + tag.str(), w, lookup(ref, "w_tip_L", target, opt.reference),
                    opt.tolerance, source);
    report.relative("shortening_L" + tag.str(), s,
                    lookup(ref, "shortening_L", target, opt.reference), opt.tolerance, source);
    report.relative("theta_tip" + tag.str(), theta,
                    lookup(ref, "theta_tip", target, opt.reference), opt.tolerance, source, "rad");
  }
  report.info("newton_iterations", iterations);
  report.info("step_cuts", cuts);
  return report;
}

}  // namespace finverse::fem::validation
