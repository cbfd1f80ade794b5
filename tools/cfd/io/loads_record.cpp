// Accumulating the loads history and converting it to loads.h5's contract (see loads_record.hpp).
#include "cfd/io/loads_record.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "core/error.hpp"

namespace finverse::cfd::io {

void LoadsRecord::add(double time, const std::vector<Vec3>& nodal, const Vec3& total, const std::vector<double>& jump) {
  if (nodal.size() != nodes_ || jump.size() != shell_)
    throw Error("loads: " + std::to_string(nodal.size()) + " nodal forces and " + std::to_string(jump.size()) +
                " pressure jumps for " + std::to_string(nodes_) + " nodes and " + std::to_string(shell_) +
                " shell triangles");
  if (!time_.empty() && !(time > time_.back()))
    throw Error("loads: output time " + std::to_string(time) + " s does not follow " + std::to_string(time_.back()) + " s");
  time_.push_back(time);
  for (const auto& f : nodal) nodal_.insert(nodal_.end(), f.begin(), f.end());
  total_.insert(total_.end(), total.begin(), total.end());
  jump_.insert(jump_.end(), jump.begin(), jump.end());
}

void LoadsRecord::restore(std::vector<double> time, std::vector<double> nodal, std::vector<double> total,
                          std::vector<double> jump) {
  const std::size_t nt = time.size();
  if (nodal.size() != nt * nodes_ * 3 || total.size() != nt * 3 || jump.size() != nt * shell_)
    throw Error("loads: a restored record of " + std::to_string(nt) + " output times has " + std::to_string(nodal.size()) +
                " nodal, " + std::to_string(total.size()) + " total and " + std::to_string(jump.size()) +
                " pressure-jump values (" + std::to_string(nodes_) + " nodes, " + std::to_string(shell_) +
                " shell triangles)");
  for (std::size_t k = 1; k < nt; ++k)
    if (!(time[k] > time[k - 1])) throw Error("loads: restored output times are not increasing");
  time_ = std::move(time);
  nodal_ = std::move(nodal);
  total_ = std::move(total);
  jump_ = std::move(jump);
}

stage::Loads LoadsRecord::to_stage(double rho, double U, double area, std::optional<double> period) const {
  if (!(rho > 0 && U > 0 && area > 0))
    throw Error("loads: rho, U and the reference area must be positive (got " + std::to_string(rho) + ", " +
                std::to_string(U) + ", " + std::to_string(area) + ")");
  const std::size_t nt = time_.size();
  stage::Loads l;
  l.time = NdArray<double>({nt}, time_);
  l.nodal_force = NdArray<double>({nt, nodes_, 3}, nodal_);
  l.force_total = NdArray<double>({nt, 3}, total_);
  l.pressure_jump = NdArray<double>({nt, shell_}, jump_);
  const double q = 0.5 * rho * U * U * area;
  l.thrust = NdArray<double>({nt});
  l.lateral = NdArray<double>({nt});
  l.vertical = NdArray<double>({nt});
  for (std::size_t k = 0; k < nt; ++k) {
    l.thrust(k) = -total_[3 * k] / q;
    l.lateral(k) = total_[3 * k + 1] / q;
    l.vertical(k) = total_[3 * k + 2] / q;
  }
  l.rho = rho;
  l.U = U;
  l.reference_area = area;
  l.period = period;
  return l;
}

std::vector<double> nodal_sum_relative_error(const stage::Loads& l) {
  const std::size_t nt = l.time.size(), nv = nt ? l.nodal_force.dim(1) : 0;
  double largest = 0;
  for (std::size_t k = 0; k < nt; ++k)
    largest = std::max(largest, std::hypot(l.force_total(k, 0), l.force_total(k, 1), l.force_total(k, 2)));
  std::vector<double> err(nt);
  for (std::size_t k = 0; k < nt; ++k) {
    double s[3] = {0, 0, 0};
    for (std::size_t i = 0; i < nv; ++i)
      for (std::size_t d = 0; d < 3; ++d) s[d] += l.nodal_force(k, i, d);
    const double F = std::hypot(l.force_total(k, 0), l.force_total(k, 1), l.force_total(k, 2));
    err[k] = std::hypot(s[0] - l.force_total(k, 0), s[1] - l.force_total(k, 1), s[2] - l.force_total(k, 2)) /
             std::max(F, 1e-12 * largest + 1e-300);
  }
  return err;
}

}  // namespace finverse::cfd::io
