// Nodal rotations from positions (tools/fit/state_from_positions.hpp): exact for a rigid motion
// of a plate with beams, the tangent rotation to O(h) on a beam bent into a circular arc.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "fit_test_util.hpp"

#include "fem/model.hpp"
#include "fem/rotation.hpp"
#include "fem/static_solver.hpp"
#include "fem/validation/hybrid_plate_model.hpp"
#include "fit/errors.hpp"
#include "fit/rotation_relaxation.hpp"
#include "fit/state_from_positions.hpp"

using namespace finverse;
using fem::Mat3;
using fem::Vec3;

namespace {

using fit::test::hybrid_plate_case;
fem::validation::HybridPlateCase state_plate_case() { return hybrid_plate_case(); }

// A straight beam of n elements along x, length 1.
fem::Model straight_beam(int n) {
  fem::Model m;
  const int mat = m.add_material({"beam", 1e9, 0.3, 1000.0});
  for (int i = 0; i <= n; ++i) m.add_node(Vec3(static_cast<double>(i) / n, 0, 0));
  for (int i = 0; i < n; ++i)
    m.add_beam(i, i + 1, mat, fem::TaperedRectangle::uniform(0.02, 0.01), Vec3::UnitY());
  return m;
}

// Largest angle between the fitted rotations and the arc's tangent rotation Rz(s / radius).
double arc_rotation_error(int n, double radius) {
  const fem::Model m = straight_beam(n);
  std::vector<Vec3> x;
  for (const Vec3& X : m.reference_positions()) {
    const double phi = X.x() / radius;
    x.emplace_back(radius * std::sin(phi), radius * (1 - std::cos(phi)), 0.0);
  }
  const fem::NodalState s = fit::state_from_positions(m, x);
  double err = 0;
  for (int i = 0; i < m.node_count(); ++i) {
    const Mat3 exact = fem::exp_so3(Vec3(0, 0, m.reference_positions()[i].x() / radius));
    err = std::max(err, fem::log_so3(exact.transpose() * s.rotation[i]).norm());
  }
  return err;
}

}  // namespace

TEST(StateFromPositions, RigidMotionGivesTheRotationExactly) {
  const auto hp = fem::validation::build_hybrid_plate(state_plate_case(), 4, 4, fem::validation::HybridPlateLoad::none);
  const fem::Model& m = hp.model;
  const Mat3 R = fem::exp_so3(Vec3(0.3, -0.7, 1.1));
  const Vec3 c(0.4, -2.0, 5.0);
  std::vector<Vec3> x;
  for (const Vec3& X : m.reference_positions()) x.push_back(R * X + c);
  const fem::NodalState s = fit::state_from_positions(m, x);
  ASSERT_EQ(s.node_count(), m.node_count());
  for (int i = 0; i < m.node_count(); ++i) {
    EXPECT_LT((s.rotation[i] - R).norm(), 1e-12) << "node " << i;
    EXPECT_EQ(s.position[i], x[i]);
  }
}

TEST(StateFromPositions, ReferenceShapeGivesIdentity) {
  const fem::Model m = straight_beam(5);
  const fem::NodalState s = fit::state_from_positions(m, m.reference_positions());
  for (const Mat3& R : s.rotation) EXPECT_LT((R - Mat3::Identity()).norm(), 1e-14);
}

TEST(StateFromPositions, BentBeamGivesTheTangentRotationToFirstOrder) {
  // Arc of radius 1 (a 57 degree bend): interior nodes see the chord of their neighbours (O(h^2)),
  // the two end nodes the chord of their one element (O(h)); halving h at least halves the error.
  const double e8 = arc_rotation_error(8, 1.0), e16 = arc_rotation_error(16, 1.0), e32 = arc_rotation_error(32, 1.0);
  EXPECT_LT(e8, 0.6 / 8);  // within about half an element's bend angle
  EXPECT_LT(e16, 0.55 * e8);
  EXPECT_LT(e32, 0.55 * e16);
}

TEST(StateFromPositions, RejectsWrongCountAndNaN) {
  const fem::Model m = straight_beam(3);
  std::vector<Vec3> x = m.reference_positions();
  x.pop_back();
  EXPECT_THROW(fit::state_from_positions(m, x), fit::InvalidInput);
  x = m.reference_positions();
  x[2].y() = std::nan("");
  try {
    fit::state_from_positions(m, x);
    FAIL() << "no exception";
  } catch (const fit::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("node 2"), std::string::npos) << e.what();
  }
}

TEST(RotationRelaxation, HeldEquilibriumPositionsGiveTheSolversRotations) {
  // A cantilever of 8 beam elements bent by a tip load to a large deflection (PL^2/EI = 2) by the
  // static solver: the truth. From its positions alone, the 1-ring fits miss the rotations by
  // O(h) (the tip sees the chord of its one element); relaxed with the positions held, the
  // rotations are the solver's own, to its tolerance, because moment balance at the true
  // positions has the true rotations as its solution.
  auto cantilever = [] {
    fem::Model m = straight_beam(8);
    m.fix_node(0);
    const double EI = 1e9 * 0.02 * 0.01 * 0.01 * 0.01 / 12;  // b = 0.02 along y, h = 0.01 along z
    m.add_nodal_load(8, 2, 2.0 * EI);                          // P = 2 EI / L^2, L = 1
    return m;
  };
  fem::Model truth_model = cantilever();
  fem::StaticSolver solver(truth_model, fem::StaticOptions{.steps = 8});
  fem::NodalState truth = truth_model.reference_state();
  solver.solve(truth, 0.0, 1.0);
  ASSERT_GT(std::abs(truth.position[8].z()), 0.3);  // a large deflection

  fem::Model m = cantilever();
  fem::NodalState base = fit::state_from_positions(m, truth.position);
  base.rotation[0] = Mat3::Identity();  // the clamp's prescribed value
  auto worst = [&](const fem::NodalState& s) {
    double e = 0;
    for (int i = 0; i < m.node_count(); ++i)
      e = std::max(e, fem::log_so3(truth.rotation[i].transpose() * s.rotation[i]).norm());
    return e;
  };
  const double fitted = worst(base);
  const fem::NodalState relaxed = fit::relax_rotations(m, base, 1.0);
  const double after = worst(relaxed);
  EXPECT_GT(fitted, 2e-3);  // measured 5.1e-3 rad
  EXPECT_LT(after, 1e-7);
  for (int i = 0; i < m.node_count(); ++i) EXPECT_EQ(relaxed.position[i], truth.position[i]);
}
