// Eq. (2)'s increment from a reference solution on its stored tangent, Anderson-accelerated
// (see stored_tangent_increment.hpp).
#include "fem/stored_tangent_increment.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <deque>

#include "fem/dof_map.hpp"
#include "fem/errors.hpp"
#include "fem/newton_iteration.hpp"
#include "fem/static_solver.hpp"

namespace finverse::fem {

namespace {
// Identifies an increment's reference in the workspaces' caches; never reused, unlike an address.
std::atomic<std::uint64_t> next_increment_id{1};
}  // namespace

StoredTangentIncrement::StoredTangentIncrement(const std::vector<const Model*>& models, const std::vector<double>& nus,
                                               const NodalState& reference, double t_next, StoredTangentOptions options)
    : reference_(reference), id_(next_increment_id++), opt_(options) {
  if (models.empty() || !models[0]) throw InvalidInput("stored-tangent increment: no model");
  if (opt_.max_iterations < 1 || opt_.history < 0)
    throw InvalidInput("stored-tangent increment: max_iterations must be >= 1 and history >= 0");
  basis_ = std::make_unique<TangentBasis>(models, nus, reference, t_next);
  lchar_ = models[0]->characteristic_length();
}

void StoredTangentIncrement::set_reference_moduli(std::vector<double> element_moduli, double nu) {
  if (element_moduli.size() != basis_->assembler().model().elements().size())
    throw InvalidInput("stored-tangent increment: " + std::to_string(element_moduli.size()) + " reference moduli for " +
                       std::to_string(basis_->assembler().model().elements().size()) + " elements");
  reference_moduli_ = std::move(element_moduli);
  reference_nu_ = nu;
}

bool StoredTangentIncrement::near_reference(const std::vector<double>& element_moduli, double nu) const {
  if (!(opt_.reuse_within > 0) || reference_moduli_.size() != element_moduli.size()) return false;
  if (!(std::abs(nu - reference_nu_) <= opt_.reuse_nu)) return false;
  for (size_t e = 0; e < element_moduli.size(); ++e)
    if (!(std::abs(element_moduli[e] - reference_moduli_[e]) <= opt_.reuse_within * reference_moduli_[e])) return false;
  return true;
}

// The reference's tangent K(x_ref; E_ref, nu_ref), factorised once per workspace; the last few
// references are kept (one per instant of an objective).
const StoredTangentIncrement::Workspace::ReferenceFactor& StoredTangentIncrement::reference_factor(Workspace& w) const {
  for (const auto& r : w.references)
    if (r.id == id_) return r;
  constexpr size_t kKept = 8;
  if (w.references.size() >= kKept) w.references.erase(w.references.begin());
  Workspace::ReferenceFactor r;
  r.id = id_;
  r.solver = std::make_unique<SparseSolver>(w.backend);
  const DofMap& dofs = basis_->dofs();
  r.solver->set_equation_names([&dofs](int eq) { return describe_equation(dofs, eq); });
  basis_->combine(reference_moduli_, reference_nu_, w.matrix, nullptr, w.scratch);
  r.solver->factorize(w.matrix, "stored tangent at the reference solution");
  r.floor = roundoff_force_floor(w.matrix, dofs, basis_->assembler().model().position_scale());
  w.references.push_back(std::move(r));
  return w.references.back();
}

namespace {

// The relative out-of-balance force as out_of_balance (newton_iteration.hpp) measures it, from an
// internal force already assembled: |r_free| / max(|f_free|, |reaction|).
double relative_residual(const DofMap& dofs, const Eigen::VectorXd& f_int, const Eigen::VectorXd& f_target,
                         const Eigen::VectorXd& r_free, double& scale) {
  double reaction = 0;
  for (int g = 0; g < dofs.total(); ++g)
    if (dofs.is_prescribed(g)) reaction += (f_int(g) - f_target(g)) * (f_int(g) - f_target(g));
  scale = std::max({dofs.gather_free(f_target).norm(), std::sqrt(reaction), 1e-30});
  return r_free.norm() / scale;
}

// Units of the free DOFs for the mixing's least squares: translations over the model's length,
// rotations in radians, as scaled_increment_norm weighs them.
Eigen::VectorXd unit_weights(const DofMap& dofs, double lchar) {
  Eigen::VectorXd w(dofs.free());
  for (int i = 0; i < dofs.free(); ++i) w(i) = (dofs.free_to_global()[i] % kDofsPerNode) < 3 ? 1.0 / lchar : 1.0;
  return w;
}

}  // namespace

bool StoredTangentIncrement::solve(Assembler& assembler, double time, const std::vector<double>& element_moduli,
                                   double nu, const Eigen::VectorXd& f_target, NodalState& x, Workspace& w,
                                   StoredTangentInfo* info) const {
  const DofMap& dofs = basis_->dofs();
  if (assembler.dofs().free() != dofs.free() || assembler.dofs().total() != dofs.total())
    throw InvalidInput("stored-tangent increment: the model's DOFs differ from the basis's");
  StoredTangentInfo out;
  w.solver.set_equation_names([&dofs](int eq) { return describe_equation(dofs, eq); });
  // The solver of this iteration: the reference's tangent when near it, else K(x_ref; E, nu).
  const SparseSolver* solver = &w.solver;
  double floor = 0;
  if (near_reference(element_moduli, nu)) {
    const Workspace::ReferenceFactor& r = reference_factor(w);
    solver = r.solver.get();
    floor = r.floor;
    out.reused_reference = true;
  } else {
    basis_->combine(element_moduli, nu, w.matrix, nullptr, w.scratch);
    w.solver.factorize(w.matrix, "stored tangent at the reference solution");
    floor = roundoff_force_floor(w.matrix, dofs, assembler.model().position_scale());
  }
  const Eigen::VectorXd units = unit_weights(dofs, lchar_);

  x = reference_;
  // Anderson mixing on u (the free DOFs' accumulated increment) with g = K^-1 r: the columns are
  // differences of successive g and u; the step is g minus their least-squares part.
  std::deque<Eigen::VectorXd> dg, du;
  Eigen::VectorXd g_prev, step_prev;
  double r0 = 0, rn_prev = 0;
  int since_refresh = 0;
  AssemblyRequest req;
  req.time = time;
  for (int it = 0; it < opt_.max_iterations; ++it) {
    assembler.assemble(x, req);
    const Eigen::VectorXd& f_int = assembler.internal_force();
    const Eigen::VectorXd r = dofs.gather_free(f_target - f_int);
    double scale = 1;
    const double rn = relative_residual(dofs, f_int, f_target, r, scale);
    out.residual = rn;
    if (!std::isfinite(rn)) break;
    if (it == 0) r0 = rn;
    if (it > 2 && rn > 1e3 * std::max(r0, 1e-12)) break;  // diverging: leave it to Newton
    // Converging too slowly on the factorised matrix: the true tangent here (a Newton step).
    const bool balanced = rn <= opt_.residual_tolerance + floor / scale;  // only the increment test left
    if (!balanced && since_refresh >= 2 && rn > opt_.refresh_ratio * rn_prev && out.refreshes < opt_.max_refreshes) {
      AssemblyRequest with_matrix = req;
      with_matrix.matrix = true;
      assembler.assemble(x, with_matrix);
      w.solver.factorize(assembler.matrix(), "tangent stiffness");
      solver = &w.solver;
      dg.clear(), du.clear();
      since_refresh = 0;
      ++out.refreshes;
    }
    ++since_refresh;
    rn_prev = rn;
    const Eigen::VectorXd g = solver->solve(r);
    if (!g.allFinite()) break;
    Eigen::VectorXd step = g;
    if (since_refresh > 1 && opt_.history > 0) {
      dg.push_back(g - g_prev);
      du.push_back(step_prev);
      if (static_cast<int>(dg.size()) > opt_.history) dg.pop_front(), du.pop_front();
      const int m = static_cast<int>(dg.size());
      Eigen::MatrixXd G(g.size(), m);
      for (int c = 0; c < m; ++c) G.col(c) = units.cwiseProduct(dg[c]);
      const Eigen::VectorXd gamma = G.colPivHouseholderQr().solve(units.cwiseProduct(g));
      if (gamma.allFinite())
        for (int c = 0; c < m; ++c) step -= gamma(c) * (du[c] + dg[c]);
    }
    const double inc = scaled_increment_norm(dofs, step, lchar_);
    x.apply_increment(dofs.scatter_free(step));
    g_prev = g;
    step_prev = step;
    out.iterations = it + 1;
    if (balanced && inc <= opt_.increment_tolerance) {
      out.converged = true;
      break;
    }
  }
  if (info) *info = out;
  return out.converged;
}

}  // namespace finverse::fem
