// Multiplicative configuration update (see nodal_state.hpp).
#include "fem/nodal_state.hpp"

namespace finverse::fem {

void NodalState::apply_increment(const Eigen::VectorXd& d) {
  const int n = node_count();
  for (int i = 0; i < n; ++i) {
    position[i] += d.segment<3>(kDofsPerNode * i);
    const Vec3 w = d.segment<3>(kDofsPerNode * i + 3);
    if (w.squaredNorm() > 0) rotation[i] = exp_so3(w) * rotation[i];
  }
}

}  // namespace finverse::fem
