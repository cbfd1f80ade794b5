// The flow's body of the Turek-Hron FSI benchmarks (Turek & Hron 2006, sec. 2; issue 32): one closed
// counter-clockwise polygon, the cylinder arc's vertices (fixed) followed by the elastic flag's wet
// nodes at their current positions (fem/validation/turek_hron_flag.hpp: lower clamp corner, lower
// edge, tip, upper edge, upper clamp corner). The arc is cfd::turek_hron_body's arc without its two
// end vertices, which the clamped corner nodes replace (they coincide to round-off; a structure whose
// wet surface does not close the arc is rejected). Caller edge e of the polygon runs from vertex e to
// e + 1: edges n_arc .. n_arc + n_wet - 2 are the flag's segments (wet node k to k + 1), the rest
// lie on the cylinder, whose loads are not transferred (it is rigid and fixed).
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Core>

#include "cfd/immersed/deforming_polygon.hpp"
#include "cfd/validation/turek_hron_cfd.hpp"

namespace finverse::fsi::validation {

class FlagFlowBody {
 public:
  // wet_reference: 2 x n_wet reference positions of the wet nodes in the order above. Throws
  // finverse::Error when the first / last wet node is not the arc's lower / upper end (within
  // 1e-9 m) or fewer than 3 wet nodes are given.
  FlagFlowBody(const cfd::TurekHronGeometry& geometry, int circle_vertices, Eigen::Matrix2Xd wet_reference);

  // The polygon's vertex state with the wet nodes at `position` moving with `velocity` and
  // `acceleration` (2 x n_wet each); the arc at rest.
  [[nodiscard]] cfd::PolygonState state(const Eigen::Matrix2Xd& position, const Eigen::Matrix2Xd& velocity,
                                        const Eigen::Matrix2Xd& acceleration) const;
  // The flag segment (wet node k to k + 1) that caller edge e is, if it is one.
  [[nodiscard]] std::optional<int> flag_segment(int edge) const;

  [[nodiscard]] int arc_vertices() const { return static_cast<int>(arc_.size()); }
  [[nodiscard]] int wet_nodes() const { return static_cast<int>(wet_reference_.cols()); }
  [[nodiscard]] const Eigen::Matrix2Xd& wet_reference() const { return wet_reference_; }
  [[nodiscard]] Eigen::Vector2d cylinder_centre() const { return centre_; }
  [[nodiscard]] double diameter() const { return diameter_; }

 private:
  std::vector<std::array<double, 2>> arc_;
  Eigen::Matrix2Xd wet_reference_;
  Eigen::Vector2d centre_;
  double diameter_;
};

}  // namespace finverse::fsi::validation
