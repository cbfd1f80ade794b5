// The phase of a residual mode against the root motion (issue 34): a residual in phase with the
// root displacement points at stiffness, one in phase with the root velocity at damping, one in
// phase with its acceleration at inertia. The root signal d(t) is the mean displacement of the
// root region's nodes (fin_regions.hpp: a pitching root moves the nodes beside the root line even
// when the root line itself turns in place) along its principal direction; v and a are its
// first and second time derivatives by second-order finite differences. The mode's coefficient
// a_m(t) is correlated with each (centred Pearson coefficients); the largest |rho| names the
// character. Over one harmonic, acceleration = -w^2 displacement, so stiffness and inertia cannot
// be told apart from the phase alone: then |rho(d, a)| is near 1 and the label says so.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "loop/fin_regions.hpp"
#include "loop/residual_field.hpp"

namespace finverse::loop {

struct RootSignal {
  Eigen::VectorXd displacement, velocity, acceleration;  // [nf]
  Eigen::Vector3d direction = Eigen::Vector3d::UnitY();
  double amplitude = 0;  // half the peak-to-peak of the displacement [m]
};

// From the reconstruction (positions per frame, 3 nv each) and the regions. Throws InvalidInput
// for fewer than 3 frames.
RootSignal root_signal(const SampledMotion& reconstruction, const FinRegions& regions);

struct PhaseCharacter {
  double rho_displacement = 0, rho_velocity = 0, rho_acceleration = 0;
  double rho_displacement_acceleration = 0;  // collinearity of the references
  // "stiffness-like" | "damping-like" | "inertia-like" | "stiffness- or inertia-like" | "none"
  // (every |rho| below `weak`: the mode does not follow the root motion)
  std::string character;
};

// Ambiguity threshold: |rho(d, a)| above `collinear` gives "stiffness- or inertia-like".
PhaseCharacter phase_character(const Eigen::VectorXd& coefficient, const RootSignal& root, double collinear = 0.9,
                               double weak = 0.5);

}  // namespace finverse::loop
