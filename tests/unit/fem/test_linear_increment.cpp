// The stored tangent in the modulus-Poisson basis (tangent_basis.hpp) and the linearised eq. (2)
// increment built on it (linear_increment.hpp), on the hybrid plate (shells and beams): the basis
// reproduces the assembled tangent at another Poisson ratio and other element moduli in a
// deformed state, and the linear increment is the converged Newton increment to second order.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "fem/errors.hpp"
#include "fem/linear_increment.hpp"
#include "fem/quasi_static_increment.hpp"
#include "fem/static_solver.hpp"
#include "fem/tangent_basis.hpp"
#include "fem/validation/hybrid_plate_model.hpp"
#include "pressure_plate.hpp"

using namespace finverse::fem;
using namespace finverse::fem::validation;

namespace {

std::unique_ptr<Model> plate_at(double nu, HybridPlateLoad load = HybridPlateLoad::pressure) {
  return test_plates::pressure_plate(nu, 4, load);
}
NodalState deformed(const Model& m, double lambda) { return test_plates::pressed_state(m, lambda); }
HybridPlateCase plate_case(double nu) { return test_plates::pressure_plate_case(nu); }

}  // namespace

TEST(TangentBasis, ReproducesTheTangentAtAnotherPoissonRatioAndOtherModuli) {
  auto m0 = plate_at(0.1), m1 = plate_at(0.3), m2 = plate_at(0.4), m3 = plate_at(0.49);
  const NodalState x = deformed(*m1, 1.0);  // geometric stiffness in the tangent
  double deflection = 0;
  for (int i = 0; i < m1->node_count(); ++i)
    deflection = std::max(deflection, std::abs(x.position[i].y() - m1->reference_positions()[i].y()));
  EXPECT_GT(deflection, 0.05);  // chord 1: well past the linear range
  const TangentBasis basis({m0.get(), m1.get(), m2.get(), m3.get()}, {0.1, 0.3, 0.4, 0.49}, x, 1.0);
  EXPECT_TRUE(basis.varies_poisson());

  auto other = plate_at(0.37);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> factor(0.2, 5.0);
  for (int e = 0; e < static_cast<int>(other->elements().size()); ++e)
    other->set_element_youngs_modulus(e, other->element_youngs_modulus(e) * factor(rng));
  EXPECT_LT(basis.form_error(*other, 0.37), 1e-10);
  // The check can fail: the same model read at a wrong ratio is off by far more.
  EXPECT_GT(basis.form_error(*other, 0.2), 1e-4);
}

TEST(TangentBasis, OneModelHoldsItsOwnPoissonRatioOnly) {
  auto m = plate_at(0.3);
  const TangentBasis basis({m.get()}, {0.3}, m->reference_state(), 0.0);
  EXPECT_FALSE(basis.varies_poisson());
  EXPECT_LT(basis.form_error(*m, 0.3), 1e-14);
  Assembler::SparseMatrix k;
  TangentBasis::Scratch scratch;
  std::vector<double> moduli(m->elements().size(), 1e5);
  EXPECT_THROW(basis.combine(moduli, 0.31, k, nullptr, scratch), InvalidInput);
  EXPECT_THROW(TangentBasis({m.get(), m.get()}, {0.3, 0.3}, m->reference_state(), 0.0), InvalidInput);
}

TEST(LinearIncrement, IsTheNewtonIncrementToSecondOrder) {
  auto m0 = plate_at(0.1), m1 = plate_at(0.3), m2 = plate_at(0.4), m3 = plate_at(0.49);
  const double lambda = 0.5;
  const NodalState base = deformed(*m1, lambda);
  QuasiStaticIncrement newton(*m1);
  double previous = 0;
  for (double dl : {0.04, 0.02}) {
    const LinearIncrement linear({m0.get(), m1.get(), m2.get(), m3.get()}, {0.1, 0.3, 0.4, 0.49}, base, lambda,
                                 lambda + dl);
    LinearIncrement::Workspace w;
    std::vector<double> moduli(m1->elements().size());
    for (size_t e = 0; e < moduli.size(); ++e) moduli[e] = m1->element_youngs_modulus(static_cast<int>(e));
    const auto dx = linear.displacement_increment(moduli, 0.3, w);
    const auto ref = newton.displacement_increment(base, lambda, lambda + dl);
    double err = 0, size = 0;
    for (size_t i = 0; i < dx.size(); ++i)
      err = std::max(err, (dx[i] - ref[i]).norm()), size = std::max(size, ref[i].norm());
    EXPECT_LT(err, 0.05 * size) << "dlambda " << dl;
    if (previous > 0) {
      EXPECT_NEAR(previous / err, 4.0, 1.0) << "error ratio when the increment halves";
    }
    previous = err;
  }
}

TEST(LinearIncrement, CarriesThePrescribedMotionOfARigidHeave) {
  // Without loads the heave of the leading edge moves the plate rigidly: the K dp term must
  // carry every free node with it exactly (as the Newton predictor does).
  auto m = plate_at(0.3, HybridPlateLoad::heave);
  NodalState base = m->reference_state();
  const double t = 0.3, dt = 0.01;
  apply_prescribed(*m, t, t, base);
  const LinearIncrement linear({m.get()}, {0.0}, base, t, t + dt);
  LinearIncrement::Workspace w;
  std::vector<double> moduli(m->elements().size());
  for (size_t e = 0; e < moduli.size(); ++e) moduli[e] = m->element_youngs_modulus(static_cast<int>(e));
  const auto dx = linear.displacement_increment(moduli, 0.0, w);
  const double dy = plate_case(0.3).heave(t + dt) - plate_case(0.3).heave(t);
  ASSERT_GT(std::abs(dy), 0.0);
  for (const Vec3& d : dx) EXPECT_NEAR(d.y(), dy, 1e-9 * std::abs(dy));
}
