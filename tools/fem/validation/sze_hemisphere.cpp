// Sze, Liu & Lo (2004) open hemisphere (see shell_cases.hpp): R = 10, t = 0.04, 18 deg hole at
// the pole, four alternating radial point loads P at 90 deg on the equator (two outward, two
// inward), P_max = 400. Quarter model x >= 0, y >= 0 with symmetry conditions on the xz and yz
// planes; each loaded point lies on a symmetry plane, so the quarter carries half of each load:
// P/2 outward (+x) at (R, 0, 0) and P/2 inward (-y) at (0, R, 0). One z translation is fixed to
// remove the rigid motion along z (the loads have no z resultant, so it carries no reaction).
#include <sstream>

#include "fem/static_solver.hpp"
#include "fem/validation/shell_cases.hpp"
#include "fem/validation/shell_meshes.hpp"
#include "fem/validation/shell_reference.hpp"

namespace finverse::fem::validation {

Summary run_sze_hemisphere(const SzeHemisphereOptions& opt) {
  const ReferenceTable ref(opt.reference, "sze_open_hemisphere");
  const double R = ref.scalar("R"), t = ref.scalar("t"), E = ref.scalar("E");
  const double nu = ref.scalar("nu"), P_max = ref.scalar("P_max_full_model");
  constexpr double kHoleDeg = 18.0;

  const TriangleMesh mesh = quarter_hemisphere_mesh(R, kHoleDeg, opt.n_meridian,
                                                    opt.n_circumference);
  Model model;
  const Material material{"hemisphere", E, nu, 1.0};
  const std::vector<int> id = add_shell_mesh(model, mesh, material, t);
  for (int i = 0; i <= opt.n_meridian; ++i) {
    const int xz = id[mesh.node(i, 0)], yz = id[mesh.node(i, opt.n_circumference)];
    // Symmetry about y = 0: u_y = 0, no rotation about x or z; about x = 0 likewise.
    model.fix(xz, 1), model.fix(xz, 3), model.fix(xz, 5);
    model.fix(yz, 0), model.fix(yz, 4), model.fix(yz, 5);
  }
  model.fix(id[mesh.node(opt.n_meridian, 0)], 2);
  const int a = id[mesh.node(0, 0)], b = id[mesh.node(0, opt.n_circumference)];
  model.add_nodal_load(a, 0, 0.5 * P_max);
  model.add_nodal_load(b, 1, -0.5 * P_max);

  Summary report(
      "validation", "sze_hemisphere",
      "Open hemispherical shell (18 deg hole) under alternating radial point loads (Sze, Liu & "
      "Lo 2004), quarter model; corotational OPT/DKT shell triangles, load-controlled Newton; "
      "outward and inward displacement of the loaded points");
  report.parameters() = {{"R", R}, {"t", t}, {"E", E}, {"nu", nu}, {"P_max_full_model", P_max},
                         {"hole_deg", kHoleDeg}, {"cells_meridian", opt.n_meridian},
                         {"cells_circumference", opt.n_circumference},
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
    const double outward = state.position[a].x() - model.reference_positions()[a].x();
    const double inward = -(state.position[b].y() - model.reference_positions()[b].y());
    std::ostringstream tag;
    tag << "@P/Pmax=" << target;
    report.relative("outward_disp" + tag.str(), outward, ref.column("outward_disp", k),
                    opt.tolerance, ref.source());
    report.relative("inward_disp" + tag.str(), inward, ref.column("inward_disp", k),
                    opt.tolerance, ref.source());
  }
  report.info("newton_iterations", iterations);
  report.info("step_cuts", cuts);
  return report;
}

}  // namespace finverse::fem::validation
