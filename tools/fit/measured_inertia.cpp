// The inertial load change of eq. (2) with inertia (see measured_inertia.hpp).
#include "fit/measured_inertia.hpp"

#include <sstream>

#include "fem/assembly.hpp"
#include "fem/dof_map.hpp"
#include "fit/errors.hpp"

namespace finverse::fit {

Eigen::VectorXd inertial_load_change(const fem::Model& model, const fem::NodalState& base, const TargetMotion& target,
                                     double t, double dt) {
  const double h = target.frame_spacing();
  const double tol = 1e-9 * h;
  if (!(h > 0) || t - h < target.times.front() - tol || t + dt + h > target.times.back() + tol) {
    std::ostringstream os;
    os << target.source << ": eq. (2) with inertia at t = " << t << " needs the frames at " << t - h << " and "
       << t + dt + h << " (the acceleration's second difference), the motion spans [" << target.times.front() << ", "
       << target.times.back() << "]";
    throw InvalidInput(os.str());
  }
  const auto acceleration = [&](double s) {
    const auto xm = target.positions_at(s - h), x0 = target.positions_at(s), xp = target.positions_at(s + h);
    std::vector<fem::Vec3> a(x0.size());
    for (size_t i = 0; i < a.size(); ++i) a[i] = (xp[i] - 2 * x0[i] + xm[i]) / (h * h);
    return a;
  };
  const auto a0 = acceleration(t), a1 = acceleration(t + dt);
  Eigen::VectorXd da = Eigen::VectorXd::Zero(fem::kDofsPerNode * model.node_count());
  for (size_t i = 0; i < a0.size(); ++i)
    da.segment<3>(fem::kDofsPerNode * static_cast<Eigen::Index>(i)) = a1[i] - a0[i];
  const fem::DofMap dofs(model);
  fem::Assembler assembler(model, dofs);
  fem::AssemblyRequest req;
  req.mass_times = &da;
  req.time = t;
  assembler.assemble(base, req);
  return -assembler.mass_product();
}

}  // namespace finverse::fit
