// The elastica computed with a shell strip (see shell_cases.hpp): a cantilever strip under a dead
// tip force perpendicular to its undeformed plane, against the shooting solution of
// EI theta'' = -P cos(theta) in structures.json ("elastica_tip_load"). nu = 0, so that the
// strip's bending stiffness is exactly EI = E b h^3 / 12 (with nu != 0 a strip lies between that
// and the plate value EI / (1 - nu^2), depending on b^2 / (R h)); L / h = 100 keeps the axial
// strain below 2e-4 at PL^2/EI = 20, so only PL^2/EI matters.
#include <cmath>
#include <sstream>

#include "fem/static_solver.hpp"
#include "fem/validation/shell_cases.hpp"
#include "fem/validation/shell_meshes.hpp"
#include "fem/validation/shell_reference.hpp"

namespace finverse::fem::validation {

Summary run_elastica_shell(const ElasticaShellOptions& opt) {
  const ReferenceTable ref(opt.reference, "elastica_tip_load");
  const double L = 1.0, b = 0.05, h = 0.01, E = 1.0e9;
  const double EI = E * b * h * h * h / 12.0;

  const TriangleMesh mesh = rectangle_mesh(L, b, opt.nx, opt.ny);
  Model model;
  const Material material{"strip", E, 0.0, 1000.0};
  const std::vector<int> id = add_shell_mesh(model, mesh, material, h);
  std::vector<int> tip;
  for (int j = 0; j <= opt.ny; ++j) {
    model.fix_node(id[mesh.node(0, j)]);
    tip.push_back(id[mesh.node(opt.nx, j)]);
    const double share = (j == 0 || j == opt.ny ? 0.5 : 1.0) / opt.ny;
    model.add_nodal_load(tip.back(), 2, share * EI / (L * L));  // lambda = PL^2/EI
  }

  Summary report(
      "validation", "elastica_shell",
      "Cantilever under a dead tip load perpendicular to its axis (large-deflection elastica) "
      "modelled as a shell strip; corotational OPT/DKT triangles, load-controlled Newton; tip "
      "deflection, shortening and rotation against the shooting solution");
  report.parameters() = {{"length_m", L}, {"width_m", b}, {"thickness_m", h},
                         {"youngs_modulus_Pa", E}, {"poisson_ratio", 0.0},
                         {"cells_along", opt.nx}, {"cells_across", opt.ny},
                         {"triangles", mesh.triangles.size()},
                         {"load_steps_per_unit", opt.load_steps_per_unit},
                         {"solver", to_string(opt.backend)}, {"reference", opt.reference.string()}};

  StaticOptions so;
  so.backend = opt.backend;
  NodalState state = model.reference_state();
  double lam = 0;
  int iterations = 0, cuts = 0;
  for (double target : {1.0, 2.0, 5.0, 10.0, 20.0}) {
    so.steps = std::max(1, static_cast<int>(std::lround((target - lam) * opt.load_steps_per_unit)));
    StaticSolver solver(model, so);
    const StaticResult r = solver.solve(state, lam, target);
    iterations += r.total_iterations;
    cuts += r.step_cuts;
    lam = target;
    Vec3 x = Vec3::Zero(), tangent = Vec3::Zero();
    for (int n : tip) {
      x += state.position[n] / tip.size();
      tangent += state.rotation[n] * Vec3::UnitX() / tip.size();
    }
    const size_t row = ref.find_row("PL2_EI", target);
    std::ostringstream tag;
    tag << "@PL2/EI=" << target;
    report.relative("w_tip_L" + tag.str(), x.z() / L, ref.column("w_tip_L", row), opt.tolerance,
                    ref.source());
    report.relative("shortening_L" + tag.str(), (L - x.x()) / L, ref.column("shortening_L", row),
                    opt.tolerance, ref.source());
    report.relative("theta_tip" + tag.str(), std::atan2(tangent.z(), tangent.x()),
                    ref.column("theta_tip", row), opt.tolerance, ref.source(), "rad");
  }
  report.info("newton_iterations", iterations);
  report.info("step_cuts", cuts);
  return report;
}

}  // namespace finverse::fem::validation
