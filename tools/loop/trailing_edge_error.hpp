// The residual measured where the paper measured its disagreement (issue 34): RMS of |r| over the
// trailing-edge nodes and the frames, and the same as a fraction of the trailing edge's
// excursion (mean over those nodes of the peak-to-peak of the reconstructed position along the
// node's principal direction of motion), comparable with the paper's "amplitude 8-10 % low".
#pragma once

#include <vector>

#include <Eigen/Core>

#include "loop/residual_field.hpp"

namespace finverse::loop {

struct TrailingEdgeError {
  double rms = 0;        // m
  double excursion = 0;  // m
  double relative = 0;   // rms / excursion (NaN when the edge does not move)
};

// nodes: the trailing-edge nodes (non-empty, in range). Throws InvalidInput otherwise.
TrailingEdgeError trailing_edge_error(const ResidualField& residual, const SampledMotion& reconstruction,
                                      const std::vector<int>& nodes);
// The excursion alone (for residual vectors that are not a ResidualField).
double trailing_edge_excursion(const SampledMotion& reconstruction, const std::vector<int>& nodes);

}  // namespace finverse::loop
