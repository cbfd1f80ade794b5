// The loads history fin-cfd writes (loads.h5, DESIGN.md section 4, tools/core/CONTRACTS.md): per
// output time the net nodal forces on the mid-surface, the total force the flow solver integrated
// from the surface traction, the pressure jump per shell triangle, and the force coefficients
// C = F / (0.5 rho U^2 A) (C_T = -F_x: thrust is along -x).
#pragma once

#include <optional>
#include <vector>

#include "cfd/immersed/thin_body.hpp"
#include "core/stage_files.hpp"

namespace finverse::cfd::io {

class LoadsRecord {
 public:
  LoadsRecord(std::size_t nodes, std::size_t shell_triangles) : nodes_(nodes), shell_(shell_triangles) {}

  // One output time: nodal forces [nodes] and total [N], pressure jump [shell triangles] [Pa].
  void add(double time, const std::vector<Vec3>& nodal, const Vec3& total, const std::vector<double>& jump);

  std::size_t size() const { return time_.size(); }
  // The record so far as flat arrays (time [nt], nodal [nt nodes 3], total [nt 3], jump [nt shell];
  // checkpoints) and its inverse, which checks the sizes against the record's shape.
  const std::vector<double>& times() const { return time_; }
  const std::vector<double>& nodal() const { return nodal_; }
  const std::vector<double>& totals() const { return total_; }
  const std::vector<double>& jumps() const { return jump_; }
  void restore(std::vector<double> time, std::vector<double> nodal, std::vector<double> total, std::vector<double> jump);
  // The contract's struct; rho [kg/m^3], U [m/s], reference area [m^2], period T [s] if periodic.
  stage::Loads to_stage(double rho, double U, double reference_area, std::optional<double> period) const;

 private:
  std::size_t nodes_, shell_;
  std::vector<double> time_, nodal_, total_, jump_;
};

// Per output time, |sum of nodal forces - force_total| / |force_total| (the denominator floored
// at 1e-12 of the largest |force_total|, so a zero force does not divide by zero).
std::vector<double> nodal_sum_relative_error(const stage::Loads& loads);

}  // namespace finverse::cfd::io
