// Equation numbering (see dof_map.hpp).
#include "fem/dof_map.hpp"

namespace finverse::fem {

DofMap::DofMap(const Model& model) {
  const int n = kDofsPerNode * model.node_count();
  equation_.assign(n, -1);
  prescribed_.assign(n, false);
  active_.assign(n, false);
  for (const auto& e : model.elements())
    for (int node : e->nodes())
      for (int d : e->active_dofs()) active_[kDofsPerNode * node + d] = true;
  for (const auto& p : model.prescribed()) prescribed_[kDofsPerNode * p.node + p.dof] = true;
  for (int g = 0; g < n; ++g)
    if (active_[g] && !prescribed_[g]) {
      equation_[g] = static_cast<int>(free_to_global_.size());
      free_to_global_.push_back(g);
    }
}

Eigen::VectorXd DofMap::gather_free(const Eigen::VectorXd& full) const {
  Eigen::VectorXd v(free());
  for (int i = 0; i < free(); ++i) v(i) = full(free_to_global_[i]);
  return v;
}

Eigen::VectorXd DofMap::scatter_free(const Eigen::VectorXd& v) const {
  Eigen::VectorXd full = Eigen::VectorXd::Zero(total());
  for (int i = 0; i < free(); ++i) full(free_to_global_[i]) = v(i);
  return full;
}

}  // namespace finverse::fem
