// Eq. (2)'s increment solved from a stored reference solution (stored_tangent_increment.hpp), on
// the hybrid plate (shells and beams) bent well into the nonlinear range: at moduli and a Poisson
// ratio away from the reference's it converges to the increment Newton reaches from the base, to
// the solver's tolerance; near the reference it runs on the reference's own factorised tangent and
// still reaches Newton's answer; it gives up (false) when it cannot converge in the iterations
// allowed; and same_topology tells apart the models whose DOFs and patterns it can share.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>

#include "fem/errors.hpp"
#include "fem/quasi_static_increment.hpp"
#include "fem/static_solver.hpp"
#include "fem/stored_tangent_increment.hpp"
#include "pressure_plate.hpp"

using namespace finverse::fem;

namespace {

// The plate at nu with every element's modulus scaled by a seeded random factor in [lo, hi].
std::unique_ptr<Model> scaled_plate(double nu, double lo, double hi, unsigned seed) {
  auto m = test_plates::pressure_plate(nu);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> factor(lo, hi);
  for (int e = 0; e < static_cast<int>(m->elements().size()); ++e)
    m->set_element_youngs_modulus(e, m->element_youngs_modulus(e) * factor(rng));
  return m;
}

struct Setting {
  std::unique_ptr<Model> m0, m1, m2, m3;  // the basis's models (m1: the reference's)
  NodalState base;
  double t = 0.5, t_next = 0.6;
  std::unique_ptr<StoredTangentIncrement> stored;
};

Setting setting(StoredTangentOptions options = {}) {
  Setting s;
  s.m0 = test_plates::pressure_plate(0.1), s.m1 = test_plates::pressure_plate(0.3),
  s.m2 = test_plates::pressure_plate(0.4), s.m3 = test_plates::pressure_plate(0.49);
  s.base = test_plates::pressed_state(*s.m1, s.t);
  QuasiStaticIncrement newton(*s.m1);
  const NodalState reference = newton.solve(s.base, s.t, s.t_next);
  s.stored = std::make_unique<StoredTangentIncrement>(
      std::vector<const Model*>{s.m0.get(), s.m1.get(), s.m2.get(), s.m3.get()},
      std::vector<double>{0.1, 0.3, 0.4, 0.49}, reference, s.t_next, options);
  return s;
}

std::vector<double> moduli_of(const Model& model, double t) {
  std::vector<double> moduli(model.elements().size());
  for (size_t e = 0; e < moduli.size(); ++e) moduli[e] = model.element_youngs_modulus(static_cast<int>(e), t);
  return moduli;
}

// The stored solve on `model` (Poisson ratio nu): true when converged; x its state.
bool stored_solve(const Setting& s, const Model& model, double nu, NodalState& x, StoredTangentInfo& info,
                  StoredTangentIncrement::Workspace* workspace = nullptr) {
  QuasiStaticIncrement increment(model);
  const Eigen::VectorXd f_target = model.external_load(s.t_next) - increment.base_offset(s.base, s.t);
  StoredTangentIncrement::Workspace own;
  return s.stored->solve(increment.solver().assembler(), s.t_next, moduli_of(model, s.t_next), nu, f_target, x,
                         workspace ? *workspace : own, &info);
}

double max_difference(const NodalState& a, const NodalState& b, double& size, const NodalState& base) {
  double d = 0;
  size = 0;
  for (size_t i = 0; i < a.position.size(); ++i)
    d = std::max(d, (a.position[i] - b.position[i]).norm()),
    size = std::max(size, (b.position[i] - base.position[i]).norm());
  return d;
}

}  // namespace

TEST(StoredTangentIncrement, ConvergesToNewtonsIncrementAwayFromTheReference) {
  const Setting s = setting();
  // The reference's own moduli: converged at once (the reference balances).
  {
    NodalState x;
    StoredTangentInfo info;
    ASSERT_TRUE(stored_solve(s, *s.m1, 0.3, x, info));
    EXPECT_LE(info.iterations, 2);
  }
  struct Case {
    double nu, lo, hi;
    unsigned seed;
  };
  for (const Case c : {Case{0.37, 0.7, 1.4, 1}, Case{0.2, 0.4, 2.5, 2}}) {
    const auto model = scaled_plate(c.nu, c.lo, c.hi, c.seed);
    NodalState x;
    StoredTangentInfo info;
    ASSERT_TRUE(stored_solve(s, *model, c.nu, x, info)) << "nu " << c.nu << ", residual " << info.residual;
    QuasiStaticIncrement newton(*model);
    const NodalState ref = newton.solve(s.base, s.t, s.t_next);
    double size = 0;
    const double diff = max_difference(x, ref, size, s.base);
    std::printf("hybrid plate, nu %.2f, moduli x[%.1f, %.1f]: %d iterations, %d refreshes, %.2e of the increment\n",
                c.nu, c.lo, c.hi, info.iterations, info.refreshes, diff / size);
    EXPECT_GT(size, 1e-3);  // a real increment (chord 1)
    EXPECT_LT(diff, 1e-7 * size);
    // The check can fail: the reference itself is far from this answer.
    double ref_size = 0;
    EXPECT_GT(max_difference(s.stored->reference(), ref, ref_size, s.base), 1e-3 * size);
  }
}

// A polish's Jacobian column: moduli 0.1 % off the reference's. It runs on the reference's tangent
// (no new factorisation), in a few iterations, and lands on Newton's increment; a second solve on
// the workspace's cached factor gives the first answer bit for bit (the answer depends on the
// moduli and the reference, not on the workspace's history). Farther away the usual route is taken.
TEST(StoredTangentIncrement, NearTheReferenceItRunsOnTheReferenceTangent) {
  Setting s = setting();
  s.stored->set_reference_moduli(moduli_of(*s.m1, s.t_next), 0.3);
  const auto near = scaled_plate(0.3, 0.999, 1.001, 3);
  StoredTangentIncrement::Workspace w;
  NodalState x;
  StoredTangentInfo info;
  ASSERT_TRUE(stored_solve(s, *near, 0.3, x, info, &w));
  EXPECT_TRUE(info.reused_reference);
  EXPECT_EQ(info.refreshes, 0);
  EXPECT_LE(info.iterations, 6);
  EXPECT_EQ(w.references.size(), 1u);
  QuasiStaticIncrement newton(*near);
  const NodalState ref = newton.solve(s.base, s.t, s.t_next);
  double size = 0;
  const double diff = max_difference(x, ref, size, s.base);
  EXPECT_GT(size, 1e-3);
  EXPECT_LT(diff, 1e-7 * size);
  // Again: the cached factor serves.
  NodalState again;
  ASSERT_TRUE(stored_solve(s, *near, 0.3, again, info, &w));
  EXPECT_EQ(w.references.size(), 1u);
  for (size_t i = 0; i < x.position.size(); ++i) EXPECT_EQ(x.position[i], again.position[i]);
  std::printf("moduli within 0.1 %% of the reference: %d iterations on its tangent, %.2e of the increment\n",
              info.iterations, diff / size);
  // Moduli 30 % off, or nu 0.05 off: not near, the stored tangent is factorised at them.
  const auto far = scaled_plate(0.3, 1.3, 1.3, 4);
  ASSERT_TRUE(stored_solve(s, *far, 0.3, x, info, &w));
  EXPECT_FALSE(info.reused_reference);
  EXPECT_FALSE(s.stored->near_reference(moduli_of(*near, s.t_next), 0.35));
  EXPECT_THROW(s.stored->set_reference_moduli({1.0, 2.0}, 0.3), InvalidInput);
}

TEST(StoredTangentIncrement, GivesUpWhenItCannotConverge) {
  const Setting s = setting({.max_iterations = 2, .max_refreshes = 0});
  const auto model = scaled_plate(0.2, 0.3, 3.0, 5);
  NodalState x;
  StoredTangentInfo info;
  EXPECT_FALSE(stored_solve(s, *model, 0.2, x, info));
  EXPECT_FALSE(info.converged);
  EXPECT_EQ(info.iterations, 2);
  EXPECT_GT(info.residual, 1e-8);
  // Another mesh's DOFs are refused by name.
  const auto other = test_plates::pressure_plate(0.3, 6);
  QuasiStaticIncrement on_other(*other);
  const std::vector<double> moduli(other->elements().size(), 1e5);
  StoredTangentIncrement::Workspace w;
  EXPECT_THROW(
      s.stored->solve(on_other.solver().assembler(), s.t_next, moduli, 0.3, other->external_load(s.t_next), x, w),
      InvalidInput);
}

TEST(SameTopology, SharedOnlyWithTheSameElementsAndPrescriptions) {
  const auto a = test_plates::pressure_plate(0.3), b = scaled_plate(0.45, 0.5, 2.0, 7);
  EXPECT_TRUE(same_topology(*a, *b));  // moduli and Poisson ratio are not topology
  EXPECT_FALSE(same_topology(*a, *test_plates::pressure_plate(0.3, 6)));
  // One more prescribed DOF (a free corner held) changes the DofMap.
  const auto held = test_plates::pressure_plate(0.3);
  held->fix(held->node_count() - 1, 1);
  EXPECT_FALSE(same_topology(*a, *held));
}
