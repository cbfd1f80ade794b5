// Moment balance of a base state with its positions held (see rotation_relaxation.hpp).
#include "fit/rotation_relaxation.hpp"

#include <cmath>
#include <memory>

#include "fit/errors.hpp"

namespace finverse::fit {

RotationRelaxation::RotationRelaxation(fem::Model& model, const std::vector<double>& instants,
                                       const std::vector<fem::NodalState>& bases, fem::StaticOptions options) {
  if (instants.empty() || instants.size() != bases.size())
    throw InvalidInput("rotation relaxation: one base per instant expected");
  const int nn = model.node_count();
  std::vector<char> held(static_cast<size_t>(fem::kDofsPerNode * nn), 0);
  for (const auto& p : model.prescribed()) held[static_cast<size_t>(fem::kDofsPerNode * p.node + p.dof)] = 1;
  // Displacements per instant, shared by the prescribed functions of one node.
  auto table = std::make_shared<std::vector<std::vector<fem::Vec3>>>();
  const auto& X = model.reference_positions();
  for (const auto& b : bases) {
    if (b.node_count() != nn) throw InvalidInput("rotation relaxation: a base has the wrong node count");
    std::vector<fem::Vec3> u(static_cast<size_t>(nn));
    for (int n = 0; n < nn; ++n) u[static_cast<size_t>(n)] = b.position[n] - X[n];
    table->push_back(std::move(u));
  }
  auto times = std::make_shared<const std::vector<double>>(instants);
  for (int n = 0; n < nn; ++n)
    for (int d = 0; d < 3; ++d)
      if (!held[static_cast<size_t>(fem::kDofsPerNode * n + d)])
        model.prescribe(n, d, [table, times, n, d](double t) {
          size_t best = 0;
          for (size_t j = 1; j < times->size(); ++j)
            if (std::abs((*times)[j] - t) < std::abs((*times)[best] - t)) best = j;
          return (*table)[best][static_cast<size_t>(n)](d);
        });
  solver_ = std::make_unique<fem::StaticSolver>(model, options);
}

fem::NodalState RotationRelaxation::relax(const fem::NodalState& base, double t) {
  // A static step over a vanishing load interval: the translations stay where they are held, the
  // root's rotations move by the drive's change over 1e-9 s only, and Newton balances the moments
  // at the free rotations.
  fem::NodalState relaxed = base;
  solver_->solve(relaxed, t, t + 1e-9 * std::max(1.0, std::abs(t)));
  for (int n = 0; n < relaxed.node_count(); ++n) relaxed.position[n] = base.position[n];
  return relaxed;
}

fem::NodalState relax_rotations(fem::Model& model, const fem::NodalState& base, double t,
                                const fem::StaticOptions& options) {
  RotationRelaxation r(model, {t}, {base}, options);
  return r.relax(base, t);
}

}  // namespace finverse::fit
