// The structure as an FSI participant (coupled_structure.hpp) and the Turek-Hron flag with its
// wet surface (turek_hron_flag.hpp): the generalized-alpha response to a caller-set load against
// the scalar recurrence and the exact solution, the interface-work energy balance, bitwise
// save/restore, the wet-node order against the flow body's polygon, and bad input.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <gtest/gtest.h>

#include "fem/coupled_structure.hpp"
#include "fem/errors.hpp"
#include "fem/static_solver.hpp"
#include "fem/validation/turek_hron_flag.hpp"

namespace finverse::fem {
namespace {

// A point mass on an isotropic linear spring in the x-y plane: two independent linear
// oscillators, m u'' + k u = f, so the integrator's response is known in closed form.
class SpringMass final : public Element {
 public:
  SpringMass(int node, Vec3 X, double k, double m) : node_{node}, X_(X), k_(k), m_(m) {}
  std::string_view type() const override { return "spring_mass"; }
  std::span<const int> nodes() const override { return node_; }
  std::span<const int> active_dofs() const override { return dofs_; }
  void internal_force(const NodalState& s, VectorRef f, MatrixRef* K) const override {
    const Vec3 u = s.position[node_[0]] - X_;
    f(0) = k_ * u.x();
    f(1) = k_ * u.y();
    if (K) *K = k_ * Eigen::Matrix2d::Identity();
  }
  void mass_matrix(const NodalState&, MatrixRef M) const override {
    M = m_ * Eigen::Matrix2d::Identity();
  }
  void gravity_force(const NodalState&, const Vec3& g, VectorRef f) const override {
    f(0) = m_ * g.x();
    f(1) = m_ * g.y();
  }
  double strain_energy(const NodalState& s) const override {
    const Vec3 u = s.position[node_[0]] - X_;
    return 0.5 * k_ * (u.x() * u.x() + u.y() * u.y());
  }
  double total_mass() const override { return m_; }

 private:
  std::array<int, 1> node_;
  std::array<int, 2> dofs_{0, 1};
  Vec3 X_;
  double k_, m_;
};

constexpr double kM = 2.0, kK = 50.0;  // omega = 5 rad/s
const Vec3 kX0(0.3, -0.1, 0);

Model oscillator() {
  Model m;
  const int n = m.add_node(kX0);
  m.add_element(std::make_unique<SpringMass>(n, kX0, kK, kM));
  return m;
}

// Load on the oscillator: x sin, y cos (a sudden start in y).
constexpr double kOmegaLoad = 3.0, kFx = 1.5, kFy = -0.8;
Eigen::VectorXd harmonic(double t) {
  return Eigen::Vector2d(kFx * std::sin(kOmegaLoad * t), kFy * std::cos(kOmegaLoad * t));
}

// The scalar generalized-alpha recurrence (Chung & Hulbert 1993) for m a + k u = f with the
// load at n+1-alpha_f interpolated, solved for a_{n+1} in closed form.
struct Scalar {
  double u = 0, v = 0, a = 0;
};
Scalar recurrence_step(const Scalar& s, double h, double fn, double f1, double am, double af,
                       double beta, double gamma) {
  const double pred = s.u + h * s.v + h * h * (0.5 - beta) * s.a;
  const double rhs = (1 - af) * f1 + af * fn - kM * am * s.a - kK * af * s.u - kK * (1 - af) * pred;
  Scalar n;
  n.a = rhs / (kM * (1 - am) + kK * (1 - af) * beta * h * h);
  n.u = pred + h * h * beta * n.a;
  n.v = s.v + h * ((1 - gamma) * s.a + gamma * n.a);
  return n;
}

CoupledStructureOptions options(double dt, double rho, int substeps = 1) {
  CoupledStructureOptions o;
  o.dynamics.time_step = dt;
  o.dynamics.spectral_radius = rho;
  o.dynamics.residual_tolerance = 1e-12;
  o.substeps = substeps;
  o.dim = 2;
  return o;
}

class OscillatorResponse : public ::testing::TestWithParam<std::tuple<double, int>> {};

TEST_P(OscillatorResponse, MatchesTheScalarGeneralizedAlphaRecurrence) {
  const auto [rho, substeps] = GetParam();
  const Model model = oscillator();
  const double dt = 0.04;
  CoupledStructure cs(model, options(dt, rho, substeps), {0});
  cs.initialize(0.0, harmonic(0));
  cs.save();
  const auto& ga = cs.integrator();
  Scalar sx, sy;
  sy.a = kFy / kM;  // equilibrium acceleration at rest under the load at t = 0
  double err = 0, umax = 0;
  for (int n = 0; n < 150; ++n) {
    const double t0 = n * dt, t1 = (n + 1) * dt;
    const Eigen::VectorXd f0 = harmonic(t0), f1 = harmonic(t1);
    cs.advance(t1, f1);
    cs.accept();
    // Sub-steps: the load linear in time between f0 and f1.
    const double h = dt / substeps;
    for (int j = 0; j < substeps; ++j) {
      const double wa = double(j) / substeps, wb = double(j + 1) / substeps;
      sx = recurrence_step(sx, h, (1 - wa) * f0(0) + wa * f1(0), (1 - wb) * f0(0) + wb * f1(0),
                           ga.alpha_m(), ga.alpha_f(), ga.beta(), ga.gamma());
      sy = recurrence_step(sy, h, (1 - wa) * f0(1) + wa * f1(1), (1 - wb) * f0(1) + wb * f1(1),
                           ga.alpha_m(), ga.alpha_f(), ga.beta(), ga.gamma());
    }
    const Eigen::VectorXd x = cs.wet_positions(), v = cs.wet_velocities(), a = cs.wet_accelerations();
    err = std::max({err, std::abs(x(0) - kX0.x() - sx.u), std::abs(x(1) - kX0.y() - sy.u),
                    std::abs(v(0) - sx.v) / 5, std::abs(v(1) - sy.v) / 5, std::abs(a(0) - sx.a) / 25,
                    std::abs(a(1) - sy.a) / 25});
    umax = std::max({umax, std::abs(sx.u), std::abs(sy.u)});
  }
  EXPECT_NEAR(cs.time(), 150 * dt, 1e-12);
  std::printf("rho_inf %.1f, %d sub-steps: max deviation from the recurrence / max |u| = %.2e\n", rho,
              substeps, err / umax);
  EXPECT_LT(err / umax, 1e-10) << "rho_inf " << rho << ", substeps " << substeps;
}

INSTANTIATE_TEST_SUITE_P(CoupledStructure, OscillatorResponse,
                         ::testing::Values(std::tuple{1.0, 1}, std::tuple{0.8, 1}, std::tuple{1.0, 3},
                                           std::tuple{0.6, 2}));

TEST(CoupledStructure, TrapezoidalResponseConvergesToTheExactForcedVibration) {
  // u_x = F/(k - m W^2) (sin W t - (W/w) sin w t), u_y = F/(k - m W^2) (cos W t - cos w t): the
  // trapezoidal rule's error falls as dt^2 (a check independent of the scheme's algebra).
  const Model model = oscillator();
  const double w = std::sqrt(kK / kM), W = kOmegaLoad, T = 4.0;
  auto error = [&](double dt) {
    CoupledStructure cs(model, options(dt, 1.0), {0});
    cs.initialize(0.0, harmonic(0));
    cs.save();
    const int steps = static_cast<int>(std::lround(T / dt));
    double e = 0;
    for (int n = 1; n <= steps; ++n) {
      const double t = n * dt;
      cs.advance(t, harmonic(t));
      cs.accept();
      const double c = 1 / (kK - kM * W * W);
      const Eigen::VectorXd x = cs.wet_positions();
      e = std::max({e, std::abs(x(0) - kX0.x() - kFx * c * (std::sin(W * t) - W / w * std::sin(w * t))),
                    std::abs(x(1) - kX0.y() - kFy * c * (std::cos(W * t) - std::cos(w * t)))});
    }
    return e;
  };
  const double e1 = error(0.01), e2 = error(0.005);
  const double amplitude = kFx / (kK - kM * W * W) * (1 + W / w);
  std::printf("max error / amplitude: %.3e (dt 0.01), %.3e (dt 0.005), ratio %.3f\n", e1 / amplitude,
              e2 / amplitude, e1 / e2);
  EXPECT_LT(e2 / amplitude, 2e-3);
  EXPECT_NEAR(e1 / e2, 4.0, 0.2);  // second order
}

TEST(CoupledStructure, InterfaceWorkEqualsEnergyChangeToRoundOffWhenUndamped) {
  // rho_inf = 1, linear, undamped: W_I = Delta(T + U) every step (coupled_structure.hpp), with and
  // without sub-steps. With rho_inf < 1 the algorithm dissipates: W_I > Delta(T + U).
  const Model model = oscillator();
  for (int substeps : {1, 4}) {
    CoupledStructure cs(model, options(0.05, 1.0, substeps), {0});
    cs.initialize(0.0, harmonic(0));
    cs.save();
    const double e0 = cs.kinetic_energy() + cs.strain_energy();
    double work = 0, emax = 0, worst = 0;
    for (int n = 1; n <= 200; ++n) {
      const CoupledStepReport r = cs.advance(n * 0.05, harmonic(n * 0.05));
      cs.accept();
      EXPECT_EQ(r.model_load_work, 0.0);
      work += r.interface_work;
      const double e = cs.kinetic_energy() + cs.strain_energy();
      emax = std::max(emax, e);
      worst = std::max(worst, std::abs(work - (e - e0)));
    }
    std::printf("%d sub-steps: max |W_I - Delta(T + U)| / max(T + U) = %.2e\n", substeps, worst / emax);
    EXPECT_GT(emax, 1e-3);
    EXPECT_LT(worst / emax, 1e-12) << "substeps " << substeps;
  }
  CoupledStructure damped(model, options(0.05, 0.5), {0});
  damped.initialize(0.0, harmonic(0));
  damped.save();
  double work = 0;
  for (int n = 1; n <= 200; ++n) {
    work += damped.advance(n * 0.05, harmonic(n * 0.05)).interface_work;
    damped.accept();
  }
  const double dissipated = work - (damped.kinetic_energy() + damped.strain_energy());
  std::printf("rho_inf 0.5: W_I - (T + U) = %.3e J after 200 steps (W_I = %.3e)\n", dissipated, work);
  EXPECT_GT(dissipated, 1e-2);
}

TEST(CoupledStructure, RayleighDampingWorkClosesTheBalance) {
  // W_I = Delta(T + U) + D to round-off at rho_inf = 1 with C = a_M M + a_K K; D > 0 and a sizable
  // share of the work, so leaving it out would miss by far more than the tolerance.
  const Model model = oscillator();
  CoupledStructureOptions o = options(0.05, 1.0, 2);
  o.dynamics.rayleigh_mass = 0.3;
  o.dynamics.rayleigh_stiffness = 0.01;
  CoupledStructure cs(model, o, {0});
  cs.initialize(0.0, harmonic(0));
  cs.save();
  double work = 0, work_trap = 0, damping = 0, worst = 0, emax = 0;
  for (int n = 1; n <= 200; ++n) {
    const CoupledStepReport r = cs.advance(n * 0.05, harmonic(n * 0.05));
    cs.accept();
    EXPECT_GE(r.damping_work, 0);
    work += r.interface_work;
    work_trap += r.interface_work_trapezoidal;
    damping += r.damping_work;
    const double e = cs.kinetic_energy() + cs.strain_energy();
    emax = std::max(emax, e);
    worst = std::max(worst, std::abs(work - e - damping));
  }
  std::printf("damped: W_I %.4e, D %.4e, max |W_I - Delta(T + U) - D| / max(T + U) %.2e\n", work, damping,
              worst / emax);
  EXPECT_GT(damping, 0.3 * work);
  EXPECT_LT(worst / emax, 1e-12);
  EXPECT_NEAR(work_trap, work, 1e-14 * std::abs(work) * 200);  // alpha_f = 1/2: the same sum
}

// The flag of FSI3 (E = 5.6 MPa, rho_s = 1000), coarse.
validation::TurekHronFlag fsi3_flag(int nx = 10, int ny = 1) {
  validation::TurekHronFlagSpec spec;
  spec.youngs_modulus = 5.6e6;
  spec.density = 1000;
  spec.mesh = {nx, ny, 3.0};
  return validation::build_turek_hron_flag(spec);
}

// An FSI3-like interface load: a pressure jump across the flag oscillating at 5.5 Hz (half of it
// pushing on the upper edge, half pulling on the lower one), as consistent nodal forces.
Eigen::VectorXd flapping_load(const validation::TurekHronFlag& f, double t, double amplitude) {
  const int n = static_cast<int>(f.wet_nodes.size());
  Eigen::VectorXd load = Eigen::VectorXd::Zero(2 * n);
  const double p = amplitude * std::sin(2 * std::numbers::pi * 5.5 * t);
  const auto& X = f.model.reference_positions();
  for (int k = 0; k + 2 < n; k += 2) {
    const Vec3 &a = X[f.wet_nodes[k]], &b = X[f.wet_nodes[k + 2]];
    if (std::abs(a.y() - b.y()) > 1e-12) continue;  // the tip: no pressure jump there
    const double L = std::abs(b.x() - a.x());
    const double w[3] = {L / 6, 2 * L / 3, L / 6};
    for (int q = 0; q < 3; ++q) load(2 * (k + q) + 1) -= 0.5 * p * w[q];
  }
  return load;
}

bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}

TEST(CoupledStructure, RepeatedAdvancesFromTheSavedStateAreBitwiseIdentical) {
  const auto flag = fsi3_flag();
  CoupledStructure cs(flag.model, options(0.002, 0.8), flag.wet_nodes);
  cs.save();
  // A few accepted steps so that velocities, accelerations and the old-step terms are non-zero.
  for (int n = 1; n <= 5; ++n) {
    cs.advance(n * 0.002, flapping_load(flag, n * 0.002, 80));
    cs.accept();
  }
  const double t = 6 * 0.002;
  const Eigen::VectorXd A = flapping_load(flag, t, 80), B = flapping_load(flag, t, 60);
  cs.advance(t, A);
  const Eigen::VectorXd xa = cs.wet_positions(), va = cs.wet_velocities(), aa = cs.wet_accelerations();
  cs.restore();
  cs.advance(t, B);
  const Eigen::VectorXd xb = cs.wet_positions();
  EXPECT_FALSE(same_bits(xa, xb));
  EXPECT_GT((xa - xb).norm(), 1e-7);
  cs.restore();
  cs.advance(t, A);
  EXPECT_TRUE(same_bits(xa, cs.wet_positions()));
  EXPECT_TRUE(same_bits(va, cs.wet_velocities()));
  EXPECT_TRUE(same_bits(aa, cs.wet_accelerations()));
  // advance() restores by itself: the same again without restore().
  cs.advance(t, B);
  cs.advance(t, A);
  EXPECT_TRUE(same_bits(xa, cs.wet_positions()));
}

TEST(CoupledStructure, CouplingIterationsThenAcceptEqualPlainSteppingBitwise) {
  // Junk iterates before the accepted load must leave no trace: the integrator's memory is part
  // of the snapshot, and the reused predictor factorisation changes nothing.
  const auto flag = fsi3_flag();
  CoupledStructure cs(flag.model, options(0.002, 0.8), flag.wet_nodes);
  cs.save();
  DynamicOptions plain_options = options(0.002, 0.8).dynamics;
  GeneralizedAlpha plain(flag.model, plain_options);
  DynamicState s = plain.reference_state();
  plain.initialize(s, cs.scatter(Eigen::VectorXd::Zero(2 * flag.wet_nodes.size())));
  int reuse_saved = 0;
  for (int n = 1; n <= 8; ++n) {
    const double t = n * 0.002;
    const Eigen::VectorXd f = flapping_load(flag, t, 80);
    // The first advance factorises the predictor's matrix, the repeats with the same load reuse
    // it: the same Newton path with one factorisation fewer.
    const CoupledStepReport first = cs.advance(t, f);
    cs.advance(t, 1.3 * f);
    const CoupledStepReport last = cs.advance(t, f);
    reuse_saved += first.factorizations - last.factorizations;
    cs.accept();
    plain.step(s, cs.scatter(f));
    ASSERT_TRUE(same_bits(s.velocity, cs.state().velocity)) << "step " << n;
    for (int i = 0; i < s.configuration.node_count(); ++i)
      ASSERT_EQ(std::memcmp(s.configuration.position[i].data(), cs.state().configuration.position[i].data(),
                            3 * sizeof(double)), 0);
  }
  EXPECT_EQ(reuse_saved, 8);  // one factorisation fewer per repeated coupling iteration
  // The integrator's memory matters: restoring the state alone, not the old-step terms, changes
  // the step (so the bitwise test above can fail).
  GeneralizedAlpha ga(flag.model, plain_options);
  DynamicState s0 = ga.reference_state();
  ga.initialize(s0, cs.scatter(flapping_load(flag, 0.001, 80)));
  DynamicState s1 = s0, s2 = s0;
  const GeneralizedAlpha::Snapshot snap = ga.snapshot();
  ga.step(s1, cs.scatter(flapping_load(flag, 0.003, 80)));
  ga.step(s2, cs.scatter(flapping_load(flag, 0.003, 80)));  // old terms now from s1's end
  EXPECT_FALSE(same_bits(s1.velocity, s2.velocity));
  ga.restore(snap);
  DynamicState s3 = s0;
  ga.step(s3, cs.scatter(flapping_load(flag, 0.003, 80)));
  EXPECT_TRUE(same_bits(s1.velocity, s3.velocity));
}

TEST(CoupledStructure, LoadRampFromZeroConverges) {
  // FSI inflows ramp up from zero ((1 - cos(pi t / 2)) / 2): the first steps' loads and
  // increments are ~1e-7 of the later ones, below what a 1e-9 relative increment test can
  // resolve; the round-off floor (increment_roundoff_floor) lets them converge, without it the
  // first step fails.
  const auto flag = fsi3_flag();
  auto ramped = [&](double t) {
    return Eigen::VectorXd(0.5 * (1 - std::cos(std::numbers::pi * t / 2)) * flapping_load(flag, t + 0.05, 80));
  };
  CoupledStructure cs(flag.model, options(0.001, 0.8), flag.wet_nodes);
  cs.save();
  for (int n = 1; n <= 5; ++n) {
    EXPECT_NO_THROW(cs.advance(n * 0.001, ramped(n * 0.001))) << "step " << n;
    cs.accept();
  }
  EXPECT_LT(cs.state().configuration.position[flag.point_a].y(), 0.2);  // p > 0 pushes it down
  DynamicOptions o = options(0.001, 0.8).dynamics;
  GeneralizedAlpha plain(flag.model, o);
  DynamicState s = plain.reference_state();
  plain.initialize(s);
  EXPECT_THROW(plain.step(s, cs.scatter(ramped(0.001))), NotConverged);
}

TEST(CoupledStructure, AFailedSubStepIsRetriedAsTwoHalves) {
  // The flag under a sudden, large pressure (a coupling iterate's load jump) with a tight Newton
  // budget: the whole sub-step does not converge, its halves do (max_halvings), and the result
  // lies nearer the step taken in 8 sub-steps than the whole step solved with Newton unbounded.
  // Without halvings the failure ends the advance, as before.
  const auto flag = fsi3_flag();
  const Eigen::VectorXd jump = flapping_load(flag, 0.05, 8000);
  CoupledStructureOptions o = options(0.02, 0.8);
  o.dynamics.max_iterations = 5;
  CoupledStructure plain(flag.model, o, flag.wet_nodes);
  plain.save();
  EXPECT_THROW(plain.advance(0.02, jump), NotConverged);
  o.max_halvings = 3;
  CoupledStructure halving(flag.model, o, flag.wet_nodes);
  halving.save();
  CoupledStepReport r;
  ASSERT_NO_THROW(r = halving.advance(0.02, jump));
  EXPECT_GT(r.halvings, 0);
  std::printf("halvings %d, Newton iterations %d\n", r.halvings, r.newton_iterations);
  // Against the step in 8 sub-steps with Newton unbounded: the same motion to a fraction of it.
  CoupledStructureOptions fine = options(0.02, 0.8, 8);
  fine.dynamics.max_iterations = 40;
  CoupledStructure reference(flag.model, fine, flag.wet_nodes);
  reference.save();
  reference.advance(0.02, jump);
  const Eigen::VectorXd X0 = plain.wet_positions();  // restored to the start by the failed advance
  const double moved = (reference.wet_positions() - X0).cwiseAbs().maxCoeff();
  const double apart = (halving.wet_positions() - reference.wet_positions()).cwiseAbs().maxCoeff();
  // The whole step with Newton unbounded: a coarser time step, so farther from the fine one.
  CoupledStructureOptions whole = options(0.02, 0.8);
  whole.dynamics.max_iterations = 40;
  CoupledStructure coarse(flag.model, whole, flag.wet_nodes);
  coarse.save();
  coarse.advance(0.02, jump);
  const double coarse_apart = (coarse.wet_positions() - reference.wet_positions()).cwiseAbs().maxCoeff();
  std::printf("moved %.3e m; against 8 sub-steps: halved %.3e m, whole step %.3e m\n", moved, apart, coarse_apart);
  EXPECT_GT(moved, 1e-3);
  EXPECT_LT(apart, 0.15 * moved);
  EXPECT_LT(apart, coarse_apart);
}

TEST(CoupledStructure, PressureOnTheWetNodesGivesTheStaticDeflection) {
  // A uniform pressure on the flag's upper edge, as consistent nodal forces on the wet nodes,
  // stepped with rho_inf = 0 and steps far longer than the flag's periods (every mode is damped
  // within a few steps), must end at the static solution of the same forces as nodal loads.
  const double p = 10;  // Pa: tip deflection ~ 1 cm at E = 1.4 MPa
  validation::TurekHronFlagSpec spec;
  spec.youngs_modulus = 1.4e6;
  spec.mesh = {20, 2, 3.0};
  const auto flag = validation::build_turek_hron_flag(spec);
  const int n = static_cast<int>(flag.wet_nodes.size());
  const auto& X = flag.model.reference_positions();
  Eigen::VectorXd load = Eigen::VectorXd::Zero(2 * n);
  const int first_top = 2 * spec.mesh.nx + 2 * spec.mesh.ny;  // the tip's upper corner
  for (int k = first_top; k + 2 < n; k += 2) {
    const double L = X[flag.wet_nodes[k]].x() - X[flag.wet_nodes[k + 2]].x();
    ASSERT_GT(L, 0);
    for (int q = 0; q < 3; ++q) load(2 * (k + q) + 1) -= p * L * (q == 1 ? 2.0 / 3 : 1.0 / 6);
  }
  EXPECT_NEAR(-load.sum(), p * (spec.x_tip - spec.clamp_x(spec.yc + 0.01)), 1e-12);

  CoupledStructureOptions o = options(10.0, 0.0);
  o.dynamics.residual_tolerance = 1e-10;
  // Once at rest a step has no increment to be relative to: let the residual decide.
  o.dynamics.increment_tolerance = 1;
  CoupledStructure cs(flag.model, o, flag.wet_nodes);
  cs.save();
  for (int k = 1; k <= 12; ++k) {
    cs.advance(10.0 * k, load);
    cs.accept();
  }
  const Vec3 u_dyn = cs.state().configuration.position[flag.point_a] - X[flag.point_a];

  auto twin = validation::build_turek_hron_flag(spec);
  const Eigen::VectorXd full = cs.scatter(load);
  for (int g = 0; g < full.size(); ++g)
    if (full(g) != 0) twin.model.add_nodal_load(g / kDofsPerNode, g % kDofsPerNode, full(g));
  StaticOptions so;
  so.steps = 2;
  so.residual_tolerance = 1e-10;
  StaticSolver solver(twin.model, so);
  NodalState st = twin.model.reference_state();
  solver.solve(st, 0.0, 1.0);
  const Vec3 u_static = st.position[twin.point_a] - X[twin.point_a];
  std::printf("tip: static (%.6e, %.6e), stepped (%.6e, %.6e)\n", u_static.x(), u_static.y(), u_dyn.x(),
              u_dyn.y());
  EXPECT_LT(u_static.y(), -5e-3);
  EXPECT_NEAR(u_dyn.y(), u_static.y(), 1e-7 * std::abs(u_static.y()));
  EXPECT_NEAR(u_dyn.x(), u_static.x(), 1e-6 * std::abs(u_static.x()));
}

// Shoelace area of a closed polygon.
double polygon_area(const std::vector<Eigen::Vector2d>& v) {
  double a = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const auto& p = v[i];
    const auto& q = v[(i + 1) % v.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

TEST(TurekHronFlag, WetNodesRunCounterClockwiseAndCloseWithTheCylinderArc) {
  for (const validation::FlagMesh mesh : {validation::FlagMesh{10, 1, 3.0}, validation::FlagMesh{20, 2, 3.0}}) {
    validation::TurekHronFlagSpec spec;
    spec.mesh = mesh;
    const auto flag = validation::build_turek_hron_flag(spec);
    const auto& X = flag.model.reference_positions();
    const auto& w = flag.wet_nodes;
    ASSERT_EQ(static_cast<int>(w.size()), 4 * mesh.nx + 2 * mesh.ny + 1);
    const double a = 0.5 * spec.thickness, r = spec.radius;
    // Ends: the clamped corners, on the arc at the flag's edges; the tip centre is point A.
    EXPECT_EQ(w.front(), flag.clamp_nodes.front());
    EXPECT_EQ(w.back(), flag.clamp_nodes.back());
    EXPECT_NEAR(X[w.front()].x(), spec.xc + std::sqrt(r * r - a * a), 1e-15);
    EXPECT_NEAR(X[w.front()].y(), spec.yc - a, 1e-15);
    EXPECT_NEAR(X[w.back()].y(), spec.yc + a, 1e-15);
    EXPECT_EQ(w[2 * mesh.nx + mesh.ny], flag.point_a);
    EXPECT_NEAR(X[flag.point_a].x(), 0.6, 1e-15);
    EXPECT_NEAR(X[flag.point_a].y(), 0.2, 1e-15);
    // Every wet node on the boundary, none twice, neighbours in the list close (at most half the
    // longest element, 0.06 at 10 x 1 with grading 3).
    std::vector<int> sorted = w;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end());
    for (int n : w)
      EXPECT_TRUE(std::abs(std::abs(X[n].y() - spec.yc) - a) < 1e-15 || X[n].x() == spec.x_tip) << n;
    for (std::size_t k = 0; k + 1 < w.size(); ++k) EXPECT_LT((X[w[k + 1]] - X[w[k]]).norm(), 0.031);

    // The flow body of turek_hron_cfd.cpp: the arc from the upper corner (angle theta0)
    // counter-clockwise to the lower one, ends excluded (they are the wet list's ends), then the
    // wet nodes. Positive area = counter-clockwise; equal to the circle plus the flag outside it
    // less the circular segments cut off by the arc's chords, r^2/2 (phi - sin phi) each.
    const double theta0 = std::asin(a / r), arc = 2 * std::numbers::pi - 2 * theta0;
    std::vector<Eigen::Vector2d> body;
    const int segments = 400;
    for (int k = 1; k < segments; ++k) {
      const double th = theta0 + arc * k / segments;
      body.emplace_back(spec.xc + r * std::cos(th), spec.yc + r * std::sin(th));
    }
    for (int n : w) body.emplace_back(X[n].x(), X[n].y());
    const double overlap = a * std::sqrt(r * r - a * a) + r * r * std::asin(a / r);
    const double flag_area = 2 * a * (spec.x_tip - spec.xc) - overlap;
    const double body_area = std::numbers::pi * r * r + flag_area;
    const double phi = arc / segments;
    const double cut = segments * 0.5 * r * r * (phi - std::sin(phi));
    EXPECT_NEAR(polygon_area(body), body_area - cut, 1e-12 * body_area);
    // The flag alone: the wet nodes closed by the clamped edge's interior nodes, top to bottom.
    std::vector<Eigen::Vector2d> flag_polygon;
    for (int n : w) flag_polygon.emplace_back(X[n].x(), X[n].y());
    for (int j = static_cast<int>(flag.clamp_nodes.size()) - 2; j >= 1; --j)
      flag_polygon.emplace_back(X[flag.clamp_nodes[j]].x(), X[flag.clamp_nodes[j]].y());
    // Its chords on the clamped arc add the segments between chord and arc to the flag.
    double added = 0;
    for (std::size_t j = 0; j + 1 < flag.clamp_nodes.size(); ++j) {
      const double c = (X[flag.clamp_nodes[j + 1]] - X[flag.clamp_nodes[j]]).norm();
      const double angle = 2 * std::asin(0.5 * c / r);
      added += 0.5 * r * r * (angle - std::sin(angle));
    }
    EXPECT_GT(added, 1e-7);
    EXPECT_NEAR(polygon_area(flag_polygon), flag_area + added, 1e-12 * flag_area);
    // The Q9 elements interpolate the clamped arc quadratically: their area is ~4e-6 off.
    EXPECT_NEAR(flag.mass, 1000 * flag_area, 1e-5 * flag.mass);
  }
}

TEST(TurekHronFlag, SpecFromTheReferenceFile) {
  // The keys of turek_hron.json (geometry, solid, cases): FSI cases have no gravity.
  const auto path = std::filesystem::temp_directory_path() / "finverse_test_turek_hron_flag.json";
  {
    std::ofstream out(path);
    out << R"({"geometry": {"cylinder_centre": [0.2, 0.2], "cylinder_radius": 0.05, "flag_length": 0.35,
                "flag_thickness": 0.02, "point_A": [0.6, 0.2]}, "solid": {"nu_s": 0.4},
               "cases": {"CSM1": {"rho_s": 1000, "E": 1.4e6, "g": 2.0}, "FSI3": {"rho_s": 1000, "E": 5.6e6},
                         "BAD": {"E": 1e6}}})";
  }
  const auto fsi3 = validation::turek_hron_flag_spec(path, "FSI3");
  EXPECT_EQ(fsi3.youngs_modulus, 5.6e6);
  EXPECT_EQ(fsi3.density, 1000);
  EXPECT_EQ(fsi3.gravity, 0);
  EXPECT_EQ(fsi3.poisson_ratio, 0.4);
  EXPECT_EQ(fsi3.x_tip, 0.6);
  EXPECT_EQ(validation::turek_hron_flag_spec(path, "CSM1").gravity, 2.0);
  EXPECT_THROW(validation::turek_hron_flag_spec(path, "BAD"), InvalidInput);  // no rho_s
  EXPECT_THROW(validation::turek_hron_flag_spec(path, "FSI9"), InvalidInput);
  std::filesystem::remove(path);
  validation::TurekHronFlagSpec bad;
  bad.thickness = 0.2;  // thicker than the cylinder
  EXPECT_THROW(validation::build_turek_hron_flag(bad), InvalidInput);
}

TEST(CoupledStructure, BadInputThrows) {
  const Model model = oscillator();
  CoupledStructure cs(model, options(0.01, 1.0), {0});
  EXPECT_THROW(cs.advance(0.01, Eigen::Vector2d(1, 0)), InvalidInput);  // before save()
  EXPECT_THROW(cs.restore(), InvalidInput);
  cs.save();
  EXPECT_THROW(cs.accept(), InvalidInput);                                    // nothing advanced
  EXPECT_THROW(cs.advance(0.01, Eigen::Vector3d(1, 0, 0)), InvalidInput);     // wrong size
  EXPECT_THROW(cs.advance(0.01, Eigen::Vector2d(NAN, 0)), InvalidInput);      // NaN
  EXPECT_THROW(cs.advance(0.02, Eigen::Vector2d(1, 0)), InvalidInput);        // off the step
  EXPECT_NO_THROW(cs.advance(0.01, Eigen::Vector2d(1, 0)));
  EXPECT_THROW(CoupledStructure(model, options(0.01, 1.0), {1}), InvalidInput);     // no node 1
  EXPECT_THROW(CoupledStructure(model, options(0.01, 1.0), {0, 0}), InvalidInput);  // repeated
  EXPECT_THROW(CoupledStructure(model, options(0.01, 1.0), {}), InvalidInput);
  CoupledStructureOptions bad = options(0.01, 1.0);
  bad.substeps = 0;
  EXPECT_THROW(CoupledStructure(model, bad, {0}), InvalidInput);
  bad = options(0.01, 1.0);
  bad.dim = 4;
  EXPECT_THROW(CoupledStructure(model, bad, {0}), InvalidInput);
  try {
    cs.advance(0.01, Eigen::Vector3d(1, 0, 0));
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("expected 2"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace finverse::fem
