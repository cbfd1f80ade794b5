// Target motion: checks, reading from motion.h5 and interpolation in time (see target_motion.hpp).
#include "fit/target_motion.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fit/errors.hpp"

namespace finverse::fit {

double TargetMotion::frame_spacing() const { return times.size() > 1 ? times[1] - times[0] : 0.0; }

std::vector<fem::Vec3> TargetMotion::positions_at(double t) const {
  if (times.empty()) throw InvalidInput(source + ": no frames");
  const double tol = 1e-9 * std::max(frame_spacing(), 1e-300);
  if (!(t >= times.front() - tol && t <= times.back() + tol)) {
    std::ostringstream os;
    os << source << ": time " << t << " lies outside the sampled span [" << times.front() << ", "
       << times.back() << "]";
    throw InvalidInput(os.str());
  }
  if (times.size() == 1) return positions[0];
  // First sample > t, clamped so that [i0, i0 + 1] brackets t.
  const auto it = std::upper_bound(times.begin(), times.end(), t);
  const size_t i1 = std::clamp<size_t>(static_cast<size_t>(it - times.begin()), 1, times.size() - 1);
  const size_t i0 = i1 - 1;
  const double w = std::clamp((t - times[i0]) / (times[i1] - times[i0]), 0.0, 1.0);
  std::vector<fem::Vec3> x(positions[i0].size());
  for (size_t n = 0; n < x.size(); ++n) x[n] = (1.0 - w) * positions[i0][n] + w * positions[i1][n];
  return x;
}

TargetMotion TargetMotion::window(double t_begin, double t_end) const {
  TargetMotion w;
  w.source = source;
  const double tol = 1e-9 * std::max(frame_spacing(), 1e-300);
  for (size_t k = 0; k < times.size(); ++k)
    if (times[k] >= t_begin - tol && times[k] <= t_end + tol) {
      w.times.push_back(times[k]);
      w.positions.push_back(positions[k]);
    }
  if (w.times.empty()) {
    std::ostringstream os;
    os << source << ": no frame in the window [" << t_begin << ", " << t_end << "]";
    throw InvalidInput(os.str());
  }
  return w;
}

void check_target(const TargetMotion& target) {
  const std::string& s = target.source;
  if (target.times.empty()) throw InvalidInput(s + ": the target has no frames");
  if (target.positions.size() != target.times.size())
    throw InvalidInput(s + ": " + std::to_string(target.times.size()) + " times but " +
                       std::to_string(target.positions.size()) + " frames of positions");
  const size_t nv = target.positions[0].size();
  for (size_t k = 0; k < target.times.size(); ++k) {
    if (!std::isfinite(target.times[k]) || (k > 0 && !(target.times[k] > target.times[k - 1]))) {
      std::ostringstream os;
      os << s << ": time[" << k << "] = " << target.times[k] << ", expected finite and increasing";
      throw InvalidInput(os.str());
    }
    if (target.positions[k].size() != nv)
      throw InvalidInput(s + ": frame " + std::to_string(k) + " has " +
                         std::to_string(target.positions[k].size()) + " nodes, frame 0 has " +
                         std::to_string(nv));
    for (size_t n = 0; n < nv; ++n)
      if (!target.positions[k][n].allFinite()) {
        std::ostringstream os;
        os << s << ": points[frame " << k << ", node " << n << "] (t = " << target.times[k]
           << ") is not finite";
        throw InvalidInput(os.str());
      }
  }
}

TargetMotion target_from_motion(const stage::Motion& motion, int mesh_nodes, const std::string& motion_source,
                                const std::string& mesh_source) {
  const auto& p = motion.points;
  if (p.rank() != 3 || p.dim(2) != 3)
    throw InvalidInput(motion_source + ": /points has shape " + shape_string(p.shape) + ", expected [nf,nv,3]");
  const size_t nf = p.dim(0), nv = p.dim(1);
  if (motion.time.size() != nf)
    throw InvalidInput(motion_source + ": /time has " + std::to_string(motion.time.size()) +
                       " entries, /points " + std::to_string(nf) + " frames");
  if (nv != static_cast<size_t>(mesh_nodes))
    throw InvalidInput(motion_source + ": /points has " + std::to_string(nv) + " nodes, " + mesh_source +
                       " has " + std::to_string(mesh_nodes));
  TargetMotion t;
  t.source = motion_source;
  t.times = motion.time.data;
  t.positions.assign(nf, std::vector<fem::Vec3>(nv));
  for (size_t k = 0; k < nf; ++k)
    for (size_t n = 0; n < nv; ++n) t.positions[k][n] = fem::Vec3(p(k, n, 0), p(k, n, 1), p(k, n, 2));
  check_target(t);
  return t;
}

}  // namespace finverse::fit
