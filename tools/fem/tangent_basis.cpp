// The tangent as stored element matrices in a modulus-Poisson basis (see tangent_basis.hpp).
#include "fem/tangent_basis.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <sstream>

#include "fem/errors.hpp"

namespace finverse::fem {

namespace {

constexpr int kFunctions = TangentBasis::kPoissonModels;

// The Poisson functions of the basis: 1, nu, 1/(1 - nu^2), nu/(1 - nu^2).
std::array<double, kFunctions> poisson_weights(double nu) {
  const double d = 1.0 / (1.0 - nu * nu);
  return {1.0, nu, d, nu * d};
}

// Element e's block of a buffer laid out by offsets, divided by the element's modulus.
void divide_by_moduli(const Model& model, double time, const std::vector<double>& in,
                      const std::function<int(int)>& offset, std::vector<double>& out) {
  out = in;
  const int ne = static_cast<int>(model.elements().size());
  for (int e = 0; e < ne; ++e) {
    const double E = model.element_youngs_modulus(e, time);
    for (int o = offset(e); o < offset(e + 1); ++o) out[o] /= E;
  }
}

}  // namespace

TangentBasis::TangentBasis(const std::vector<const Model*>& models, const std::vector<double>& nus,
                           const NodalState& state, double time, const Eigen::VectorXd* product)
    : state_(state), time_(time), basis_count_(static_cast<int>(models.size())), has_product_(product != nullptr) {
  if (models.size() != nus.size() || (models.size() != 1 && models.size() != kFunctions))
    throw InvalidInput("tangent basis: expected one model or four at distinct Poisson ratios, got " +
                       std::to_string(models.size()) + " models and " + std::to_string(nus.size()) + " ratios");
  for (const Model* m : models)
    if (!m || m->node_count() != models[0]->node_count() || m->elements().size() != models[0]->elements().size())
      throw InvalidInput("tangent basis: the models differ in nodes or elements");
  for (size_t i = 0; i < nus.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (nus[i] == nus[j]) throw InvalidInput("tangent basis: the Poisson ratios must differ");
  fixed_nu_ = nus[0];
  dofs_ = std::make_unique<DofMap>(*models[0]);
  assembler_ = std::make_unique<Assembler>(*models[0], *dofs_);
  // Element tangents (and K_e v_e) of each model, per unit modulus.
  std::vector<std::vector<double>> k(models.size()), kv(models.size());
  for (size_t i = 0; i < models.size(); ++i) {
    std::unique_ptr<DofMap> own_dofs;
    std::unique_ptr<Assembler> own;
    Assembler* a = assembler_.get();
    if (i > 0) {
      own_dofs = std::make_unique<DofMap>(*models[i]);
      own = std::make_unique<Assembler>(*models[i], *own_dofs);
      a = own.get();
    }
    AssemblyRequest req;
    req.matrix = true;
    req.stiffness_times = product;
    req.time = time;
    a->assemble(state, req);
    divide_by_moduli(
        *models[i], time, a->element_stiffness(), [&](int e) { return a->matrix_offset(e); }, k[i]);
    if (product)
      divide_by_moduli(
          *models[i], time, a->element_stiffness_product(), [&](int e) { return a->vector_offset(e); }, kv[i]);
  }

  if (basis_count_ == 1) {
    matrices_ = {std::move(k[0])};
    if (product) products_ = {std::move(kv[0])};
    return;
  }
  // B_b = sum_i inv(W)(b, i) k_i with W(i, b) = poisson_weights(nu_i)[b].
  Eigen::Matrix4d W;
  for (int i = 0; i < kFunctions; ++i) {
    const auto w = poisson_weights(nus[i]);
    for (int b = 0; b < kFunctions; ++b) W(i, b) = w[b];
  }
  const Eigen::Matrix4d inv = W.fullPivLu().inverse();
  const auto solve = [&](const std::vector<std::vector<double>>& in, std::vector<std::vector<double>>& out) {
    out.assign(kFunctions, std::vector<double>(in[0].size()));
    for (size_t o = 0; o < in[0].size(); ++o)
      for (int b = 0; b < kFunctions; ++b) {
        double v = 0;
        for (int i = 0; i < kFunctions; ++i) v += inv(b, i) * in[i][o];
        out[b][o] = v;
      }
  };
  solve(k, matrices_);
  if (product) solve(kv, products_);
}

void TangentBasis::combine(const std::vector<double>& element_moduli, double nu, Assembler::SparseMatrix& matrix,
                           Eigen::VectorXd* kv, Scratch& scratch) const {
  const Model& model = assembler_->model();
  const int ne = static_cast<int>(model.elements().size());
  if (static_cast<int>(element_moduli.size()) != ne)
    throw InvalidInput("tangent basis: " + std::to_string(element_moduli.size()) + " element moduli for " +
                       std::to_string(ne) + " elements");
  if (basis_count_ == 1 && std::abs(nu - fixed_nu_) > 1e-12 * std::max(1.0, std::abs(fixed_nu_))) {
    std::ostringstream os;
    os << "tangent basis: built for the one Poisson ratio " << fixed_nu_ << ", asked for " << nu;
    throw InvalidInput(os.str());
  }
  const auto w = poisson_weights(nu);
  // Weighted element blocks, then the assembler's gather (its order: deterministic).
  const auto weigh = [&](const std::vector<std::vector<double>>& basis, std::vector<double>& out, bool matrix_layout) {
    out.resize(basis[0].size());
    for (int e = 0; e < ne; ++e) {
      const int o0 = matrix_layout ? assembler_->matrix_offset(e) : assembler_->vector_offset(e);
      const int o1 = matrix_layout ? assembler_->matrix_offset(e + 1) : assembler_->vector_offset(e + 1);
      const double E = element_moduli[e];
      if (basis_count_ == 1) {
        for (int o = o0; o < o1; ++o) out[o] = E * basis[0][o];
      } else {
        const double c0 = E * w[0], c1 = E * w[1], c2 = E * w[2], c3 = E * w[3];
        for (int o = o0; o < o1; ++o)
          out[o] = c0 * basis[0][o] + c1 * basis[1][o] + c2 * basis[2][o] + c3 * basis[3][o];
      }
    }
  };
  weigh(matrices_, scratch.matrix, true);
  assembler_->gather_matrix(scratch.matrix, matrix);
  if (kv) {
    if (!has_product_) throw InvalidInput("tangent basis: built without a product vector");
    weigh(products_, scratch.vector, false);
    assembler_->gather_vector(scratch.vector, *kv);
  }
}

double TangentBasis::form_error(const Model& model, double nu) const {
  DofMap dofs(model);
  Assembler direct(model, dofs);
  AssemblyRequest req;
  req.matrix = true;
  req.time = time_;
  direct.assemble(state_, req);
  std::vector<double> moduli(model.elements().size());
  for (size_t e = 0; e < moduli.size(); ++e) moduli[e] = model.element_youngs_modulus(static_cast<int>(e), time_);
  Assembler::SparseMatrix k;
  Scratch scratch;
  combine(moduli, nu, k, nullptr, scratch);
  const auto& ref = direct.matrix();
  if (ref.nonZeros() != k.nonZeros()) throw InvalidInput("tangent basis: the model's pattern differs");
  double diff = 0, scale = 0;
  for (Eigen::Index i = 0; i < ref.nonZeros(); ++i) {
    diff = std::max(diff, std::abs(ref.valuePtr()[i] - k.valuePtr()[i]));
    scale = std::max(scale, std::abs(ref.valuePtr()[i]));
  }
  return diff / std::max(scale, 1e-300);
}

}  // namespace finverse::fem
