// fsi.h5 frames of a coupled run; see fsi_output.hpp.
#include "fsi/fsi_output.hpp"

#include <string>

#include "core/error.hpp"
#include "core/stage_files.hpp"

namespace finverse::fsi {

FsiOutput::FsiOutput(const std::vector<Eigen::Vector3d>& reference, std::vector<int> probes, double rho, double speed,
                     double reference_area)
    : nodes_(static_cast<int>(reference.size())),
      reference_(reference),
      probes_(std::move(probes)),
      rho_(rho),
      speed_(speed),
      area_(reference_area) {
  if (nodes_ < 1 || !(rho > 0) || !(speed > 0) || !(reference_area > 0))
    throw Error("fsi output: expected nodes >= 1 and positive rho, speed and reference area");
  for (const int p : probes_)
    if (p < 0 || p >= nodes_) throw Error("fsi output: probe node " + std::to_string(p) + " out of range");
}

void FsiOutput::add_probes(const fem::DynamicState& s) {
  probe_time_.push_back(s.time);
  for (const int p : probes_) {
    const auto P = static_cast<std::size_t>(p);
    for (int c = 0; c < 3; ++c) probe_displacement_.push_back(s.configuration.position[P](c) - reference_[P](c));
  }
}

void FsiOutput::add(const fem::DynamicState& s, const Eigen::VectorXd& f, const std::array<double, 3>& force,
                    int iterations, double residual, double relative) {
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
  relative_.push_back(relative);
}

void FsiOutput::write(const std::filesystem::path& path, const Provenance& provenance) const {
  if (time_.empty()) throw Error("fsi output: no frames to write to " + path.string());
  stage::Fsi out = to_stage();
  stage::write(path, out, provenance);
}

stage::Fsi FsiOutput::to_stage() const {
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
  out.coupling_relative_residual = NdArray<double>({nt}, relative_);
  out.reference_points = NdArray<double>({nv, 3});
  for (std::size_t i = 0; i < nv; ++i)
    for (std::size_t c = 0; c < 3; ++c)
      out.reference_points.data[3 * i + c] = reference_[i](static_cast<Eigen::Index>(c));
  if (!probes_.empty() && !probe_time_.empty()) {
    const std::size_t np = probes_.size(), ns = probe_time_.size();
    out.probe_nodes = NdArray<std::int32_t>({np}, std::vector<std::int32_t>(probes_.begin(), probes_.end()));
    out.probe_time = NdArray<double>({ns}, probe_time_);
    out.probe_displacement = NdArray<double>({ns, np, 3}, probe_displacement_);
  }
  out.rho = rho_;
  out.U = speed_;
  out.reference_area = area_;
  return out;
}

std::vector<std::string> FsiOutput::array_names() {
  std::vector<std::string> names;
  for (const auto& [name, v] : FsiOutput({Eigen::Vector3d::Zero()}, {}, 1, 1, 1).saved_frames()) names.push_back(name);
  return names;
}

FsiOutput::Arrays FsiOutput::saved_frames() const {
  Arrays a{{"output_time", time_},
           {"output_points", points_},
           {"output_velocity", velocity_},
           {"output_nodal_force", nodal_force_},
           {"output_force", force_},
           {"output_residual", residual_},
           {"output_relative", relative_},
           {"output_iterations", std::vector<double>(iterations_.begin(), iterations_.end())},
           {"output_probe_time", probe_time_},
           {"output_probe_displacement", probe_displacement_}};
  return a;
}

void FsiOutput::restore_frames(const Arrays& a) {
  const auto get = [&](const char* key) {
    const auto it = a.find(key);
    return it == a.end() ? std::vector<double>{} : it->second;
  };
  std::vector<double> time = get("output_time"), points = get("output_points"), velocity = get("output_velocity"),
                      nodal = get("output_nodal_force"), force = get("output_force"), residual = get("output_residual"),
                      relative = get("output_relative"), iterations = get("output_iterations"),
                      probe_time = get("output_probe_time"), probe = get("output_probe_displacement");
  const std::size_t nt = time.size(), nv = 3 * static_cast<std::size_t>(nodes_), ns = probe_time.size();
  if (points.size() != nt * nv || velocity.size() != nt * nv || nodal.size() != nt * nv || force.size() != 3 * nt ||
      residual.size() != nt || relative.size() != nt || iterations.size() != nt ||
      probe.size() != 3 * ns * probes_.size())
    throw Error("fsi output: saved frames do not fit " + std::to_string(nodes_) + " nodes and " +
                std::to_string(probes_.size()) + " probes (" + std::to_string(nt) + " frames, " + std::to_string(ns) +
                " probe samples)");
  time_ = std::move(time);
  points_ = std::move(points);
  velocity_ = std::move(velocity);
  nodal_force_ = std::move(nodal);
  force_ = std::move(force);
  residual_ = std::move(residual);
  relative_ = std::move(relative);
  iterations_.assign(iterations.begin(), iterations.end());
  probe_time_ = std::move(probe_time);
  probe_displacement_ = std::move(probe);
}

}  // namespace finverse::fsi
