// Cost of the structure's side of an FSI3 coupling step (not a test): the Turek-Hron flag
// (E = 5.6 MPa, rho_s = 1000 kg/m^3, Q9) advanced by CoupledStructure under an FSI3-like load
// (a pressure jump across the flag at 5.5 Hz, sized for a tip amplitude of a few cm), three
// coupling iterations per step (loads 1.1 f, 0.95 f, f, then accept), over one FSI3 period.
// Prints wall time per advance (first iteration of a step, which factorises the predictor's
// matrix, and repeats, which reuse it), per Newton iteration, and the interface-work balance
// W_I against Delta(T + U) over the period.
//   fem_coupled_bench [nx ny] [dt] [rho_inf] [pressure amplitude, Pa]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>

#include "fem/coupled_structure.hpp"
#include "fem/validation/turek_hron_flag.hpp"

using namespace finverse::fem;

int main(int argc, char** argv) {
  const int nx = argc > 2 ? std::atoi(argv[1]) : 20, ny = argc > 2 ? std::atoi(argv[2]) : 2;
  const double dt = argc > 3 ? std::atof(argv[3]) : 0.001;
  const double rho = argc > 4 ? std::atof(argv[4]) : 1.0;
  const double amplitude = argc > 5 ? std::atof(argv[5]) : 60.0;
  validation::TurekHronFlagSpec spec;
  spec.youngs_modulus = 5.6e6;
  spec.density = 1000;
  spec.mesh = {nx, ny, 3.0};
  const auto flag = validation::build_turek_hron_flag(spec);
  const auto& X = flag.model.reference_positions();
  const int n = static_cast<int>(flag.wet_nodes.size());
  auto load = [&](double t) {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(2 * n);
    const double p = amplitude * std::sin(2 * std::numbers::pi * 5.5 * t);
    for (int k = 0; k + 2 < n; k += 2) {
      const Vec3 &a = X[flag.wet_nodes[k]], &b = X[flag.wet_nodes[k + 2]];
      if (std::abs(a.y() - b.y()) > 1e-12) continue;
      const double L = std::abs(b.x() - a.x()), w[3] = {L / 6, 2 * L / 3, L / 6};
      for (int q = 0; q < 3; ++q) f(2 * (k + q) + 1) -= 0.5 * p * w[q];
    }
    return f;
  };
  CoupledStructureOptions o;
  o.dynamics.time_step = dt;
  o.dynamics.spectral_radius = rho;
  o.dynamics.residual_tolerance = 1e-8;
  o.dim = 2;
  CoupledStructure cs(flag.model, o, flag.wet_nodes);
  cs.save();
  using clock = std::chrono::steady_clock;
  double t_first = 0, t_repeat = 0, work = 0, work_trap = 0;
  long it_first = 0, it_repeat = 0, fac_first = 0, fac_repeat = 0, repeats = 0;
  const int steps = static_cast<int>(std::lround(1.0 / 5.5 / dt));
  const double e0 = cs.kinetic_energy() + cs.strain_energy();
  double emax = 0, uy_max = 0;
  for (int s = 1; s <= steps; ++s) {
    const double t = s * dt;
    const Eigen::VectorXd f = load(t);
    const double scales[3] = {1.1, 0.95, 1.0};
    for (int m = 0; m < 3; ++m) {
      const auto c0 = clock::now();
      const CoupledStepReport r = cs.advance(t, scales[m] * f);
      const double w = std::chrono::duration<double>(clock::now() - c0).count();
      if (m == 0) {
        t_first += w;
        it_first += r.newton_iterations;
        fac_first += r.factorizations;
      } else {
        t_repeat += w;
        it_repeat += r.newton_iterations;
        fac_repeat += r.factorizations;
        ++repeats;
      }
      if (m == 2) {
        work += r.interface_work;
        work_trap += r.interface_work_trapezoidal;
      }
    }
    cs.accept();
    emax = std::max(emax, cs.kinetic_energy() + cs.strain_energy());
    uy_max = std::max(uy_max, std::abs(cs.state().configuration.position[flag.point_a].y() - X[flag.point_a].y()));
  }
  const double de = cs.kinetic_energy() + cs.strain_energy() - e0;
  std::printf("flag %dx%d Q9: %d free DOFs, %d wet nodes, dt %g, rho_inf %g, %d steps (one 5.5 Hz period)\n",
              nx, ny, cs.integrator().dofs().free(), n, dt, rho, steps);
  std::printf("  max |uy_A| %.4f m\n", uy_max);
  std::printf("  first advance of a step: %.3f ms, %.2f Newton iterations, %.2f factorisations\n",
              1e3 * t_first / steps, double(it_first) / steps, double(fac_first) / steps);
  std::printf("  repeated advance:        %.3f ms, %.2f Newton iterations, %.2f factorisations\n",
              1e3 * t_repeat / repeats, double(it_repeat) / repeats, double(fac_repeat) / repeats);
  std::printf("  per Newton iteration:    %.3f ms (first), %.3f ms (repeat)\n", 1e3 * t_first / it_first,
              1e3 * t_repeat / it_repeat);
  std::printf("  interface work %.6e J/m, Delta(T + U) %.6e J/m, difference / max(T + U) %.2e\n", work, de,
              (work - de) / emax);
  std::printf("  trapezoidal interface work %.6e J/m, difference / max(T + U) %.2e\n", work_trap,
              (work_trap - de) / emax);
  return 0;
}
