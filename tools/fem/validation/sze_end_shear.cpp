// Sze, Liu & Lo (2004) cantilever strip under an end shear force (see shell_cases.hpp): clamped
// at x = 0, a dead force P in +z spread uniformly over the free edge, load-controlled Newton
// through the ten reference levels.
#include <sstream>

#include "fem/static_solver.hpp"
#include "fem/validation/shell_cases.hpp"
#include "fem/validation/shell_meshes.hpp"
#include "fem/validation/shell_reference.hpp"

namespace finverse::fem::validation {

Summary run_sze_end_shear(const SzeEndShearOptions& opt) {
  const ReferenceTable ref(opt.reference, "sze_cantilever_end_shear");
  const double L = ref.scalar("L"), b = ref.scalar("b"), h = ref.scalar("h");
  const double E = ref.scalar("E"), nu = ref.scalar("nu"), P_max = ref.scalar("P_max");

  const TriangleMesh mesh = rectangle_mesh(L, b, opt.nx, opt.ny);
  Model model;
  const Material material{"strip", E, nu, 1.0};
  const std::vector<int> id = add_shell_mesh(model, mesh, material, h);
  std::vector<int> tip;
  for (int j = 0; j <= opt.ny; ++j) {
    model.fix_node(id[mesh.node(0, j)]);
    tip.push_back(id[mesh.node(opt.nx, j)]);
    // Uniform edge load: consistent nodal shares of the linear edge interpolation.
    const double share = (j == 0 || j == opt.ny ? 0.5 : 1.0) / opt.ny;
    model.add_nodal_load(tip.back(), 2, share * P_max);
  }

  Summary report(
      "validation", "sze_end_shear",
      "Cantilever strip under an end shear force (Sze, Liu & Lo 2004, sec. 3.1); corotational "
      "OPT/DKT shell triangles, load-controlled Newton; tip deflection w and shortening -u at ten "
      "load levels");
  report.parameters() = {{"L", L}, {"b", b}, {"h", h}, {"E", E}, {"nu", nu}, {"P_max", P_max},
                         {"cells_along", opt.nx}, {"cells_across", opt.ny},
                         {"triangles", mesh.triangles.size()},
                         {"steps_per_level", opt.steps_per_level},
                         {"solver", to_string(opt.backend)}, {"reference", opt.reference.string()}};

  StaticOptions so;
  so.backend = opt.backend;
  so.steps = opt.steps_per_level;
  NodalState state = model.reference_state();
  double lam = 0;
  int iterations = 0, cuts = 0;
  for (size_t k = 0; k < ref.rows("P_frac"); ++k) {
    const double target = ref.column("P_frac", k);
    StaticSolver solver(model, so);
    const StaticResult r = solver.solve(state, lam, target);
    iterations += r.total_iterations;
    cuts += r.step_cuts;
    lam = target;
    Vec3 u = Vec3::Zero();
    for (int n : tip) u += (state.position[n] - model.reference_positions()[n]) / tip.size();
    std::ostringstream tag;
    tag << "@P/Pmax=" << target;
    report.relative("w_tip" + tag.str(), u.z(), ref.column("w_tip", k), opt.tolerance,
                    ref.source());
    report.relative("minus_u_tip" + tag.str(), -u.x(), ref.column("minus_u_tip", k),
                    opt.tolerance, ref.source());
  }
  report.info("newton_iterations", iterations);
  report.info("step_cuts", cuts);
  return report;
}

}  // namespace finverse::fem::validation
