// Twin of the seed paper's uniform plate (sections 3.2-3.3, Table 2): a plate of W/L = 0.54
// pitching about its leading edge, alpha0 = 12 deg, f L/U = 1, E/(rho_f U^2) = 6e6, nu = 0.25,
// mass ratio rho_s h/(rho_f L) = 0.1, K = E h^3/(12 (1 - nu^2))/(rho_f U^2 L^3) = 0.5 (Dai et
// al. 2012's K; with the paper's rho_s the numbers do not close): h = 9.787e-3 L, rho_s = 10.22.
// Parameters "E" and "nu"; shells of build_hybrid_plate without beams; the leading edge held but
// for its rotation about the span, prescribed = -theta (nose up positive, thin_airfoil_loads.hpp).
// The pitch starts from rest, theta = alpha0 r(t) sin(2 pi f t), r = (1 - cos(pi t/T_r))/2 up to
// T_r (whole periods), so theta is C2 and the added-mass loads have no jump.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "fem/load_history.hpp"
#include "fit/model_factory.hpp"
#include "fit/target_motion.hpp"
#include "fit/validation/hybrid_plate_twin.hpp"
#include "fit/validation/thin_airfoil_loads.hpp"

namespace finverse::fit::validation {

struct UniformPlateCase {
  double chord = 1, span = 0.54;
  double youngs_modulus = 6e6, poisson_ratio = 0.25;  // the truth, in rho_f U^2
  double mass_ratio = 0.1;                            // rho_s h / (rho_f L)
  double bending_stiffness = 0.5;                     // K = D / (rho_f U^2 L^3)
  double pitch_amplitude = 0.20943951023931956;       // alpha0 = 12 deg [rad]
  double frequency = 1;                               // f0 L / U
  int ramp_periods = 1;                               // smooth start (see above)

  double thickness() const;  // h from K, E, nu
  double density() const;    // rho_s from the mass ratio and h
  // theta(t), dtheta/dt, d2theta/dt2 (nose up positive).
  double pitch(double t) const;
  double pitch_rate(double t) const;
  double pitch_acceleration(double t) const;
  // The rigid pitching motion for thin_airfoil_loads.
  RigidPlateMotion rigid_motion() const;
};

class UniformPlateTwin : public ModelFactory {
 public:
  // loads: full-length (6 per node of the nx x nz plate) nodal loads, empty: the pitch alone.
  // Throws fem::InvalidInput for a bad grid or case or loads of the wrong length.
  UniformPlateTwin(UniformPlateCase plate, int nx = 8, int nz = 4, fem::LoadHistory loads = {});

  std::vector<std::string> parameter_names() const override { return {"E", "nu"}; }
  std::unique_ptr<fem::Model> build(const Eigen::VectorXd& physical) const override;
  Eigen::VectorXd default_parameters() const override { return truth(); }
  std::vector<int> prescribed_nodes() const override { return leading_edge_; }

  Eigen::VectorXd truth() const;  // (E, nu) of the case
  const UniformPlateCase& plate_case() const { return case_; }
  int nx() const { return nx_; }
  int nz() const { return nz_; }
  const fem::LoadHistory& loads() const { return loads_; }
  // Trailing-edge nodes (x = chord), z increasing.
  const std::vector<int>& trailing_edge() const { return trailing_edge_; }

 private:
  UniformPlateCase case_;
  int nx_, nz_;
  fem::LoadHistory loads_;
  std::vector<int> leading_edge_, trailing_edge_;
};

// The thin-airfoil loads (thin_airfoil_loads.hpp) of the rigid pitching plate on the shells of
// the nx x nz plate, fluid density rho_f = load_density (1: the case's), sampled at `times`.
fem::LoadHistory uniform_plate_loads(const UniformPlateCase& plate, int nx, int nz, double load_density,
                                     const std::vector<double>& times);

// The truth: generalized-alpha from rest at t = 0 with the given parameters, positions at
// t_k = k * output_interval, k = 1..end_time / output_interval. Both must be given (> 0).
TargetMotion uniform_plate_truth(const UniformPlateTwin& twin, const Eigen::VectorXd& physical,
                                 const TwinTruthOptions& options);

}  // namespace finverse::fit::validation
