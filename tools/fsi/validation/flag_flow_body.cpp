// The Turek-Hron flow body: fixed cylinder arc + the flag's wet nodes; see flag_flow_body.hpp.
#include "fsi/validation/flag_flow_body.hpp"

#include <cmath>
#include <string>

#include "core/error.hpp"

namespace finverse::fsi::validation {

FlagFlowBody::FlagFlowBody(const cfd::TurekHronGeometry& g, int circle_vertices, Eigen::Matrix2Xd wet_reference)
    : wet_reference_(std::move(wet_reference)), centre_(g.xc, g.yc), diameter_(2 * g.radius) {
  if (wet_reference_.cols() < 3) throw Error("fsi: the flag needs at least 3 wet nodes");
  const cfd::Polygon body = cfd::turek_hron_body(g, circle_vertices);
  const auto& v = body.vertices();
  // turek_hron_body: the arc from the upper flag edge round to the lower, then the two tip corners.
  const std::size_t n_arc = v.size() - 2;
  const auto mismatch = [&](const std::array<double, 2>& a, Eigen::Index k) {
    return std::hypot(a[0] - wet_reference_(0, k), a[1] - wet_reference_(1, k));
  };
  const double lower = mismatch(v[n_arc - 1], 0), upper = mismatch(v[0], wet_reference_.cols() - 1);
  if (!(lower < 1e-9 && upper < 1e-9))
    throw Error("fsi: the structure's wet surface does not match the flow body: its first / last wet node is " +
                std::to_string(lower) + " / " + std::to_string(upper) +
                " m from the cylinder arc's lower / upper end (expected the clamped flag corners)");
  arc_.assign(v.begin() + 1, v.begin() + static_cast<std::ptrdiff_t>(n_arc - 1));
}

cfd::PolygonState FlagFlowBody::state(const Eigen::Matrix2Xd& position, const Eigen::Matrix2Xd& velocity,
                                      const Eigen::Matrix2Xd& acceleration) const {
  const Eigen::Index n = wet_reference_.cols();
  if (position.cols() != n || velocity.cols() != n || acceleration.cols() != n)
    throw Error("fsi: flag body state needs " + std::to_string(n) + " wet-node columns");
  cfd::PolygonState s;
  const std::size_t total = arc_.size() + static_cast<std::size_t>(n);
  s.position.reserve(total);
  s.velocity.assign(arc_.size(), {0, 0});
  s.acceleration.assign(arc_.size(), {0, 0});
  s.position = arc_;
  for (Eigen::Index k = 0; k < n; ++k) {
    s.position.push_back({position(0, k), position(1, k)});
    s.velocity.push_back({velocity(0, k), velocity(1, k)});
    s.acceleration.push_back({acceleration(0, k), acceleration(1, k)});
  }
  return s;
}

std::optional<int> FlagFlowBody::flag_segment(int edge) const {
  const int k = edge - arc_vertices();
  if (k >= 0 && k < wet_nodes() - 1) return k;
  return std::nullopt;
}

}  // namespace finverse::fsi::validation
