// fsi.h5 frames of a coupled run; see fsi_output.hpp.
#include "fsi/validation/fsi_output.hpp"

#include <string>

#include "core/error.hpp"
#include "core/stage_files.hpp"

namespace finverse::fsi::validation {

FsiOutput::FsiOutput(int nodes, double rho, double speed, double reference_area)
    : nodes_(nodes), rho_(rho), speed_(speed), area_(reference_area) {
  if (nodes < 1 || !(rho > 0) || !(speed > 0) || !(reference_area > 0))
    throw Error("fsi output: expected nodes >= 1 and positive rho, speed and reference area");
}

void FsiOutput::add(const fem::DynamicState& s, const Eigen::VectorXd& f, const std::array<double, 3>& force,
                    int iterations, double residual) {
  const auto n = static_cast<Eigen::Index>(nodes_);
  if (s.configuration.node_count() != nodes_ || s.velocity.size() != 6 * n || f.size() != 6 * n)
    throw Error("fsi output: expected " + std::to_string(nodes_) + " nodes (6 values each) in every frame");
  time_.push_back(s.time);
  for (Eigen::Index i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      points_.push_back(s.configuration.position[static_cast<std::size_t>(i)](c));
      velocity_.push_back(s.velocity(6 * i + c));
      nodal_force_.push_back(f(6 * i + c));
    }
  force_.insert(force_.end(), force.begin(), force.end());
  iterations_.push_back(iterations);
  residual_.push_back(residual);
}

void FsiOutput::write(const std::filesystem::path& path, const Provenance& provenance) const {
  if (time_.empty()) throw Error("fsi output: no frames to write to " + path.string());
  const std::size_t nt = time_.size(), nv = static_cast<std::size_t>(nodes_);
  stage::Fsi out;
  out.time = NdArray<double>({nt}, time_);
  out.points = NdArray<double>({nt, nv, 3}, points_);
  out.velocity = NdArray<double>({nt, nv, 3}, velocity_);
  out.nodal_force = NdArray<double>({nt, nv, 3}, nodal_force_);
  out.force_total = NdArray<double>({nt, 3}, force_);
  const double q = 0.5 * rho_ * speed_ * speed_ * area_;
  out.thrust = NdArray<double>({nt});
  out.lateral = NdArray<double>({nt});
  out.vertical = NdArray<double>({nt});
  for (std::size_t k = 0; k < nt; ++k) {
    out.thrust.data[k] = -force_[3 * k] / q;
    out.lateral.data[k] = force_[3 * k + 1] / q;
    out.vertical.data[k] = force_[3 * k + 2] / q;
  }
  out.coupling_iterations = NdArray<std::int32_t>({nt}, iterations_);
  out.coupling_residual = NdArray<double>({nt}, residual_);
  out.rho = rho_;
  out.U = speed_;
  out.reference_area = area_;
  stage::write(path, out, provenance);
}

}  // namespace finverse::fsi::validation
