// Defaults of TracedModel (traced_model.hpp).
#include "loop/traced_model.hpp"

#include <algorithm>
#include <cmath>

namespace finverse::loop {

Eigen::VectorXd TracedModel::effect_start(const std::string& candidate, const Eigen::VectorXd& step) const {
  const Eigen::VectorXd off = effect_off(candidate);
  const auto dirs = score_directions(candidate);
  const auto params = effect_parameters(candidate);
  Eigen::VectorXd p = off;
  for (std::size_t j = 0; j < dirs.size() && static_cast<Eigen::Index>(j) < step.size(); ++j)
    p += step(static_cast<Eigen::Index>(j)) * (dirs[j].parameters - off) / dirs[j].step;
  for (std::size_t i = 0; i < params.size(); ++i)
    p(static_cast<Eigen::Index>(i)) = std::clamp(p(static_cast<Eigen::Index>(i)), params[i].lower, params[i].upper);
  return p;
}

double TracedModel::trailing_edge_rms(const Eigen::VectorXd& r) const {
  return r.size() ? std::sqrt(r.squaredNorm() / static_cast<double>(r.size() / 3)) : 0.0;
}

Eigen::VectorXd TracedModel::node_rms(const Eigen::VectorXd& r) const {
  const Eigen::Index frames = frame_count();
  if (frames <= 0 || r.size() == 0) return {};
  const Eigen::Index rows = r.size() / frames, nodes = rows / 3;
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(nodes);
  for (Eigen::Index k = 0; k < frames; ++k)
    for (Eigen::Index n = 0; n < nodes; ++n) sum(n) += r.segment(k * rows + 3 * n, 3).squaredNorm();
  return (sum / static_cast<double>(frames)).cwiseSqrt();
}

}  // namespace finverse::loop
