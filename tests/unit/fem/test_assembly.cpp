// Assembly: bit-identical results for any thread count, and agreement with a naive serial
// assembly of the symmetrised element tangents.
#include <cstring>
#include <random>

#include <gtest/gtest.h>
#include <omp.h>

#include "fem/assembly.hpp"
#include "fem_test_models.hpp"

using namespace finverse::fem;

namespace {
NodalState deformed(const Model& m, unsigned seed) {
  NodalState s = m.reference_state();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int n = 0; n < m.node_count(); ++n) {
    s.position[n] += 1e-3 * Vec3(U(rng), U(rng), U(rng));
    s.rotation[n] = exp_so3(0.2 * Vec3(U(rng), U(rng), U(rng)));
  }
  return s;
}

struct Snapshot {
  Eigen::VectorXd f, mv;
  std::vector<double> values;
};

Snapshot assemble_with(int threads, const Model& m, const DofMap& dofs, const NodalState& s,
                       const Eigen::VectorXd& v) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  Assembler a(m, dofs);
  AssemblyRequest req;
  req.matrix = true;
  req.stiffness_coefficient = 0.7;
  req.mass_coefficient = 3.0e4;
  req.mass_times = &v;
  a.assemble(s, req);
  omp_set_num_threads(saved);
  const auto& K = a.matrix();
  return {a.internal_force(), a.mass_product(),
          std::vector<double>(K.valuePtr(), K.valuePtr() + K.nonZeros())};
}
}  // namespace

TEST(Assembly, BitIdenticalForAnyThreadCount) {
  const Model m = test::lattice(12);  // 264 beams: above the serial cut-off
  const DofMap dofs(m);
  const NodalState s = deformed(m, 99);
  Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(dofs.total(), -1.0, 2.0);
  const Snapshot one = assemble_with(1, m, dofs, s, v);
  for (int threads : {2, 3, 4}) {
    const Snapshot many = assemble_with(threads, m, dofs, s, v);
    ASSERT_EQ(one.values.size(), many.values.size());
    EXPECT_EQ(0, std::memcmp(one.f.data(), many.f.data(), sizeof(double) * one.f.size()))
        << threads << " threads";
    EXPECT_EQ(0, std::memcmp(one.mv.data(), many.mv.data(), sizeof(double) * one.mv.size()));
    EXPECT_EQ(0, std::memcmp(one.values.data(), many.values.data(), sizeof(double) * one.values.size()));
  }
}

TEST(Assembly, MatchesNaiveSerialAssembly) {
  const Model m = test::lattice(5);
  const DofMap dofs(m);
  const NodalState s = deformed(m, 5);
  Assembler a(m, dofs);
  AssemblyRequest req;
  req.matrix = true;
  a.assemble(s, req);
  const int n = dofs.total();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
  for (const auto& e : m.elements()) {
    Eigen::VectorXd fe(12);
    Eigen::MatrixXd Ke(12, 12);
    Element::MatrixRef Kr(Ke);
    e->internal_force(s, fe, &Kr);
    const auto nodes = e->nodes();
    for (int i = 0; i < 12; ++i) {
      const int gi = 6 * nodes[i / 6] + i % 6;
      f(gi) += fe(i);
      for (int j = 0; j < 12; ++j) K(gi, 6 * nodes[j / 6] + j % 6) += 0.5 * (Ke(i, j) + Ke(j, i));
    }
  }
  EXPECT_LT((f - a.internal_force()).norm(), 1e-12 * f.norm());
  const Eigen::MatrixXd Ka =
      Eigen::MatrixXd(Assembler::SparseMatrix(a.matrix().selfadjointView<Eigen::Upper>()));
  Eigen::MatrixXd Kf(dofs.free(), dofs.free());
  for (int i = 0; i < dofs.free(); ++i)
    for (int j = 0; j < dofs.free(); ++j) Kf(i, j) = K(dofs.free_to_global()[i], dofs.free_to_global()[j]);
  EXPECT_LT((Ka - Kf).norm(), 1e-12 * Kf.norm());
}
