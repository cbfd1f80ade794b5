// Quasi-static increment of eq. (2) and its marching driver (see quasi_static_increment.hpp).
#include "fem/quasi_static_increment.hpp"

#include <algorithm>

namespace finverse::fem {

QuasiStaticIncrement::QuasiStaticIncrement(const Model& model, StaticOptions options)
    : solver_(model, options) {}

Eigen::VectorXd QuasiStaticIncrement::base_offset(const NodalState& base, double t,
                                                  const Eigen::VectorXd* load_change) {
  AssemblyRequest req;
  req.time = t;
  solver_.assembler().assemble(base, req);
  // Balance f_int(x) + offset = f_ext(t_next), offset = f_ext(t) - f_int(x_t) - g.
  Eigen::VectorXd offset = solver_.model().external_load(t) - solver_.assembler().internal_force();
  if (load_change) offset -= *load_change;
  return offset;
}

NodalState QuasiStaticIncrement::solve(const NodalState& base, double t, double t_next, QuasiStaticInfo* info,
                                       const Eigen::VectorXd* load_change) {
  const Model& model = solver_.model();
  const Eigen::VectorXd offset = base_offset(base, t, load_change);
  NodalState x = base;
  const StaticResult r = solver_.solve(x, t, t_next, &offset);
  if (info) {
    const DofMap& dofs = solver_.dofs();
    Eigen::VectorXd change = model.external_load(t_next) - model.external_load(t);
    if (load_change) change += *load_change;
    const double df = dofs.gather_free(change).norm();
    info->iterations = r.total_iterations;
    info->step_cuts = r.step_cuts;
    info->base_imbalance = dofs.gather_free(offset).norm() / std::max(df, 1e-300);
  }
  return x;
}

std::vector<Vec3> QuasiStaticIncrement::displacement_increment(const NodalState& base, double t, double t_next,
                                                               QuasiStaticInfo* info,
                                                               const Eigen::VectorXd* load_change) {
  const NodalState x = solve(base, t, t_next, info, load_change);
  std::vector<Vec3> dx(x.position.size());
  for (size_t i = 0; i < dx.size(); ++i) dx[i] = x.position[i] - base.position[i];
  return dx;
}

std::vector<NodalState> march_quasi_static(QuasiStaticIncrement& increment, const NodalState& start,
                                           const std::vector<double>& times,
                                           const std::function<void(int, const NodalState&)>& on_frame) {
  std::vector<NodalState> states;
  states.reserve(times.size());
  states.push_back(start);
  for (size_t k = 1; k < times.size(); ++k) {
    states.push_back(increment.solve(states.back(), times[k - 1], times[k]));
    if (on_frame) on_frame(static_cast<int>(k), states.back());
  }
  return states;
}

}  // namespace finverse::fem
