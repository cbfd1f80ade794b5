// Deterministic two-phase assembly (see assembly.hpp).
#include "fem/assembly.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <exception>
#include <numeric>
#include <tuple>

#include <omp.h>

namespace finverse::fem {

namespace {
// Global DOF of local index i of element e.
inline int global_dof(const Element& e, int i) {
  const auto dofs = e.active_dofs();
  const int nd = static_cast<int>(dofs.size());
  return kDofsPerNode * e.nodes()[i / nd] + dofs[i % nd];
}

// Runs body(e) for every element in parallel; rethrows the exception of the lowest-numbered
// failing element so that the error message does not depend on the thread count either.
template <class Body>
void for_each_element(int n, Body&& body) {
  std::exception_ptr error;
  int error_element = n;
#pragma omp parallel for schedule(dynamic, 32) if (n > 64)
  for (int e = 0; e < n; ++e) {
    try {
      body(e);
    } catch (...) {
#pragma omp critical(finverse_fem_assembly_error)
      if (e < error_element) {
        error_element = e;
        error = std::current_exception();
      }
    }
  }
  if (error) std::rethrow_exception(error);
}
}  // namespace

Assembler::Assembler(const Model& model, const DofMap& dofs, bool full_matrix)
    : model_(model), dofs_(dofs), full_(full_matrix) {
  const auto& elems = model.elements();
  const int ne = static_cast<int>(elems.size());
  vec_offset_.resize(ne + 1);
  mat_offset_.resize(ne + 1);
  vec_offset_[0] = mat_offset_[0] = 0;
  for (int e = 0; e < ne; ++e) {
    const int n = elems[e]->size();
    vec_offset_[e + 1] = vec_offset_[e] + n;
    mat_offset_[e + 1] = mat_offset_[e] + n * n;
  }
  fe_.assign(vec_offset_[ne], 0.0);

  // Vector gather lists (counting sort by global dof keeps element order).
  const int nt = dofs.total();
  vec_ptr_.assign(nt + 1, 0);
  for (int e = 0; e < ne; ++e)
    for (int i = 0; i < elems[e]->size(); ++i) ++vec_ptr_[global_dof(*elems[e], i) + 1];
  std::partial_sum(vec_ptr_.begin(), vec_ptr_.end(), vec_ptr_.begin());
  vec_src_.resize(vec_ptr_[nt]);
  {
    std::vector<int> fill(vec_ptr_.begin(), vec_ptr_.end() - 1);
    for (int e = 0; e < ne; ++e)
      for (int i = 0; i < elems[e]->size(); ++i)
        vec_src_[fill[global_dof(*elems[e], i)]++] = vec_offset_[e] + i;
  }

  // Matrix pattern: upper triangle (row <= col; all rows if full_) of the free block, CSC order,
  // then element order.
  struct Entry {
    int col, row, src;
  };
  std::vector<Entry> entries;
  for (int e = 0; e < ne; ++e) {
    const int n = elems[e]->size();
    for (int b = 0; b < n; ++b) {
      const int j = dofs.equation(global_dof(*elems[e], b));
      if (j < 0) continue;
      for (int a = 0; a < n; ++a) {
        const int i = dofs.equation(global_dof(*elems[e], a));
        if (i < 0 || (!full_ && i > j)) continue;
        entries.push_back({j, i, mat_offset_[e] + a + b * n});
      }
    }
  }
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& x, const Entry& y) {
    return std::tie(x.col, x.row) < std::tie(y.col, y.row);
  });
  std::vector<Eigen::Triplet<double, int>> pattern;
  mat_ptr_.clear();
  mat_src_.resize(entries.size());
  for (size_t k = 0; k < entries.size(); ++k) {
    if (k == 0 || entries[k].col != entries[k - 1].col || entries[k].row != entries[k - 1].row) {
      mat_ptr_.push_back(static_cast<int>(k));
      pattern.emplace_back(entries[k].row, entries[k].col, 0.0);
    }
    mat_src_[k] = entries[k].src;
  }
  mat_ptr_.push_back(static_cast<int>(entries.size()));
  matrix_.resize(dofs.free(), dofs.free());
  matrix_.setFromTriplets(pattern.begin(), pattern.end());
  matrix_.makeCompressed();
  // setFromTriplets orders rows ascending within a column, as our sort did.
}

void Assembler::gather_vector(const std::vector<double>& buffer, Eigen::VectorXd& out) const {
  const int nt = dofs_.total();
  out.resize(nt);
#pragma omp parallel for schedule(static) if (nt > 4096)
  for (int g = 0; g < nt; ++g) {
    double s = 0;
    for (int k = vec_ptr_[g]; k < vec_ptr_[g + 1]; ++k) s += buffer[vec_src_[k]];
    out(g) = s;
  }
}

void Assembler::gather_matrix(const std::vector<double>& buffer, SparseMatrix& out) const {
  if (out.nonZeros() != matrix_.nonZeros() || out.rows() != matrix_.rows()) out = matrix_;
  const int nnz = static_cast<int>(matrix_.nonZeros());
  double* values = out.valuePtr();
#pragma omp parallel for schedule(static) if (nnz > 16384)
  for (int k = 0; k < nnz; ++k) {
    double s = 0;
    for (int c = mat_ptr_[k]; c < mat_ptr_[k + 1]; ++c) s += buffer[mat_src_[c]];
    values[k] = s;
  }
}

void Assembler::assemble(const NodalState& state, const AssemblyRequest& req) {
  const auto& elems = model_.elements();
  const int ne = static_cast<int>(elems.size());
  const bool need_k = req.matrix || req.stiffness_times;
  const bool need_m = (req.matrix && req.mass_coefficient != 0) || req.mass_times;
  if (need_k) ke_.resize(mat_offset_[ne]);
  if (need_m) me_.resize(mat_offset_[ne]);
  if (req.mass_times) fm_.resize(vec_offset_[ne]);
  if (req.stiffness_times) fk_.resize(vec_offset_[ne]);
  const bool need_c = req.matrix && req.viscous_velocity && req.damping_coefficient != 0;
  if (req.viscous_velocity) fd_.resize(vec_offset_[ne]);
  if (need_c) ce_.resize(mat_offset_[ne]);

  const StiffnessField& field = model_.stiffness_field();
  for_each_element(ne, [&](int e) {
    const Element& el = *elems[e];
    const int n = el.size();
    // Forces and tangent are linear in E (stiffness_field.hpp).
    const double scale = field.uniform() ? 1.0 : field.scale(e, req.time);
    Eigen::Map<Eigen::VectorXd> f(fe_.data() + vec_offset_[e], n);
    if (need_k) {
      Eigen::Map<Eigen::MatrixXd> K(ke_.data() + mat_offset_[e], n, n);
      Element::MatrixRef Kr(K);
      el.internal_force(state, f, &Kr);
      if (!full_)
        for (int b = 0; b < n; ++b)
          for (int a = 0; a < b; ++a) K(a, b) = K(b, a) = 0.5 * (K(a, b) + K(b, a));
      if (scale != 1.0) K *= scale;
    } else {
      el.internal_force(state, f, nullptr);
    }
    if (scale != 1.0) f *= scale;
    if (need_m) {
      Eigen::Map<Eigen::MatrixXd> M(me_.data() + mat_offset_[e], n, n);
      el.mass_matrix(state, M);
      if (const double mf = model_.element_mass_factor(e); mf != 1.0) M *= mf;
    }
    if (req.viscous_velocity) {
      Eigen::VectorXd ve(n);
      for (int i = 0; i < n; ++i) ve(i) = (*req.viscous_velocity)(global_dof(el, i));
      Eigen::Map<Eigen::VectorXd> fd(fd_.data() + vec_offset_[e], n);
      if (need_c) {
        Eigen::Map<Eigen::MatrixXd> C(ce_.data() + mat_offset_[e], n, n);
        Element::MatrixRef Cr(C);
        el.viscous_force(state, ve, req.viscosity, fd, &Cr);
        if (scale != 1.0) C *= scale;
      } else {
        el.viscous_force(state, ve, req.viscosity, fd, nullptr);
      }
      if (scale != 1.0) fd *= scale;
    }
    if (req.mass_times || req.stiffness_times) {
      Eigen::VectorXd xe(n);
      if (req.mass_times) {
        for (int i = 0; i < n; ++i) xe(i) = (*req.mass_times)(global_dof(el, i));
        Eigen::Map<Eigen::MatrixXd> M(me_.data() + mat_offset_[e], n, n);
        Eigen::Map<Eigen::VectorXd>(fm_.data() + vec_offset_[e], n) = M * xe;
      }
      if (req.stiffness_times) {
        for (int i = 0; i < n; ++i) xe(i) = (*req.stiffness_times)(global_dof(el, i));
        Eigen::Map<Eigen::MatrixXd> K(ke_.data() + mat_offset_[e], n, n);
        Eigen::Map<Eigen::VectorXd>(fk_.data() + vec_offset_[e], n) = K * xe;
      }
    }
  });

  gather_vector(fe_, f_int_);
  if (req.mass_times) gather_vector(fm_, f_mass_);
  if (req.stiffness_times) gather_vector(fk_, f_stiff_);
  if (req.viscous_velocity) gather_vector(fd_, f_visc_);

  if (req.matrix) {
    const double ck = req.stiffness_coefficient;
    const double cm = need_m ? req.mass_coefficient : 0.0;
    const int nnz = static_cast<int>(matrix_.nonZeros());
    double* values = matrix_.valuePtr();
    const double* K = ke_.data();
    const double* M = need_m ? me_.data() : nullptr;
    const double cc = need_c ? req.damping_coefficient : 0.0;
    const double* C = need_c ? ce_.data() : nullptr;
#pragma omp parallel for schedule(static) if (nnz > 16384)
    for (int k = 0; k < nnz; ++k) {
      double s = 0;
      for (int c = mat_ptr_[k]; c < mat_ptr_[k + 1]; ++c) {
        const int o = mat_src_[c];
        s += ck * K[o] + (M ? cm * M[o] : 0.0) + (C ? cc * C[o] : 0.0);
      }
      values[k] = s;
    }
  }
}

double Assembler::strain_energy(const NodalState& state, double time) const {
  const auto& elems = model_.elements();
  const int ne = static_cast<int>(elems.size());
  std::vector<double> u(ne);
  const StiffnessField& field = model_.stiffness_field();
  for_each_element(ne, [&](int e) { u[e] = field.scale(e, time) * elems[e]->strain_energy(state); });
  return std::accumulate(u.begin(), u.end(), 0.0);  // fixed order
}

double Assembler::kinetic_energy(const NodalState& state, const Eigen::VectorXd& velocity) {
  const auto& elems = model_.elements();
  const int ne = static_cast<int>(elems.size());
  std::vector<double> t(ne);
  for_each_element(ne, [&](int e) {
    const Element& el = *elems[e];
    const int n = el.size();
    Eigen::MatrixXd M(n, n);
    el.mass_matrix(state, M);
    M *= model_.element_mass_factor(e);
    Eigen::VectorXd v(n);
    for (int i = 0; i < n; ++i) v(i) = velocity(global_dof(el, i));
    t[e] = 0.5 * v.dot(M * v);
  });
  return std::accumulate(t.begin(), t.end(), 0.0);
}

double roundoff_force_floor(const Assembler::SparseMatrix& A, const DofMap& dofs,
                            double position_scale) {
  double ktt = 0, krr = 0;
  for (int j = 0; j < A.outerSize(); ++j)
    for (Assembler::SparseMatrix::InnerIterator it(A, j); it; ++it)
      if (it.row() == j) {
        const double v = std::abs(it.value());
        if (dofs.free_to_global()[j] % kDofsPerNode < 3)
          ktt = std::max(ktt, v);
        else
          krr = std::max(krr, v);
      }
  // Safety factor 10: errors of neighbouring DOFs add up through the off-diagonal entries.
  return 10 * std::numeric_limits<double>::epsilon() * std::sqrt(static_cast<double>(dofs.free())) *
         std::max(ktt * position_scale, krr);
}

}  // namespace finverse::fem
