// The static Newton iteration shared by load control and arc length (see newton_iteration.hpp).
#include "fem/newton_iteration.hpp"

#include <algorithm>
#include <cmath>

namespace finverse::fem {

NewtonOutcome newton_iterations(const NewtonTolerances& tol, const Assembler& assembler,
                                const std::function<Eigen::VectorXd(double& scale)>& residual,
                                const std::function<std::optional<double>(const Eigen::VectorXd& r)>& correct) {
  NewtonOutcome out;
  double r0 = 0, floor = 0;
  for (int it = 0; it <= tol.max_iterations; ++it) {
    double scale = 1;
    const Eigen::VectorXd r = residual(scale);
    const double rn = r.norm() / scale;
    out.residual = rn;
    if (!std::isfinite(rn)) return out;
    if (it == 0) {
      r0 = rn;
      floor = roundoff_force_floor(assembler.matrix(), assembler.dofs(), assembler.model().position_scale());
    }
    if (it > 2 && rn > 1e6 * std::max(r0, 1.0)) return out;  // diverging
    if (it == tol.max_iterations) return out;
    const std::optional<double> inc = correct(r);
    if (!inc) return out;
    if (rn <= tol.residual_tolerance + floor / scale && *inc <= tol.increment_tolerance) {
      out.iterations = it + 1;
      return out;
    }
  }
  return out;
}

Eigen::VectorXd out_of_balance(Assembler& assembler, const NodalState& state, double time,
                               const Eigen::VectorXd& f_ext, double extra_scale, double& scale) {
  AssemblyRequest req;
  req.matrix = true;
  req.time = time;
  assembler.assemble(state, req);
  const DofMap& dofs = assembler.dofs();
  const Eigen::VectorXd& f_int = assembler.internal_force();
  const Eigen::VectorXd f_ext_free = dofs.gather_free(f_ext);
  double reaction = 0;
  for (int g = 0; g < dofs.total(); ++g)
    if (dofs.is_prescribed(g)) reaction += (f_int(g) - f_ext(g)) * (f_int(g) - f_ext(g));
  scale = std::max({f_ext_free.norm(), std::sqrt(reaction), extra_scale, 1e-30});
  return f_ext_free - dofs.gather_free(f_int);
}

double scaled_increment_norm(const DofMap& dofs, const Eigen::VectorXd& du, double lchar) {
  double inc = 0;
  for (int i = 0; i < dofs.free(); ++i) {
    const int g = dofs.free_to_global()[i];
    const double v = (g % kDofsPerNode) < 3 ? du(i) / lchar : du(i);
    inc += v * v;
  }
  return std::sqrt(inc);
}

SolverBackend tangent_backend(SolverBackend backend, bool unsymmetric_tangent) {
  if (!unsymmetric_tangent) return backend;
  return backend == SolverBackend::sparse_lu ? SolverBackend::sparse_lu : SolverBackend::umfpack;
}

}  // namespace finverse::fem
