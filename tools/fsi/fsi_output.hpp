// The frames of a coupled flow-structure run and their fsi.h5 (schema finverse/fsi, tools/core/
// CONTRACTS.md; issue 32 "Outputs"): per output step the time, every structure node's position and
// velocity, the hydrodynamic force on each node, the total force on the body with its coefficients,
// and the coupling's iterations and final residuals (absolute and relative); besides, the reference
// positions and, at every step, the displacement of a few probe nodes (e.g. point A). A 2-D run (the plane-strain flag)
// stores z = 0 and forces per metre depth [N/m]; its reference area is then D x 1 m. The file is written to a temporary
// and renamed (stage::write, core/atomic_file.hpp): nothing half-written under the final name.
// frames()/restore_frames(): the frames so far as named arrays, for a run's checkpoint (fsi_checkpoint.hpp), so that a
// restarted run writes the uninterrupted run's file.
#pragma once

#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "core/provenance.hpp"
#include "core/stage_files.hpp"
#include "fem/generalized_alpha.hpp"

namespace finverse::fsi {

class FsiOutput {
 public:
  // rho, speed, reference_area: the coefficients' normalisation F / (rho U^2 A / 2); reference:
  // the undeformed node positions; probes: node indices tracked every step.
  FsiOutput(const std::vector<Eigen::Vector3d>& reference, std::vector<int> probes, double rho, double speed,
            double reference_area);

  // state: the structure (positions, velocities 6 per node: the translations are kept);
  // nodal_force: full length (6 per node) hydrodynamic load; force: on the whole body (x, y, z);
  // residual, relative: the coupling's final |x_out - x_in| [m] and that over |x_out|.
  void add(const fem::DynamicState& state, const Eigen::VectorXd& nodal_force, const std::array<double, 3>& force,
           int iterations, double residual, double relative);
  // The probes' displacement at state.time (call every step).
  void add_probes(const fem::DynamicState& state);
  // Atomic write (temporary + rename); throws finverse::Error.
  void write(const std::filesystem::path& path, const Provenance& provenance) const;
  // The frames as fsi.h5's arrays (for a caller that adds its own attributes before writing).
  [[nodiscard]] stage::Fsi to_stage() const;

  [[nodiscard]] std::size_t frames() const { return time_.size(); }
  // Everything added so far, as named flat arrays, and back (throws finverse::Error when the sizes
  // do not fit this output's nodes and probes).
  using Arrays = std::map<std::string, std::vector<double>>;
  [[nodiscard]] Arrays saved_frames() const;
  [[nodiscard]] static std::vector<std::string> array_names();
  void restore_frames(const Arrays& arrays);

 private:
  int nodes_;
  std::vector<Eigen::Vector3d> reference_;
  std::vector<int> probes_;
  double rho_, speed_, area_;
  std::vector<double> time_, points_, velocity_, nodal_force_, force_, residual_, relative_;
  std::vector<std::int32_t> iterations_;
  std::vector<double> probe_time_, probe_displacement_;
};

}  // namespace finverse::fsi
