// Accuracy of a reconstructed motion against the virtual experiment's truth (issue 5 accuracy
// criteria; seed paper section 4.1 reports reconstruction errors below 5 %): vertex position
// errors as fractions of the chord over every vertex of every frame, and the trailing-edge
// peak-to-peak lateral excursion, the quantity that sets the thrust and that the paper's
// Fig. 12 plots.
#pragma once

#include <vector>

#include "core/nd_array.hpp"

namespace finverse::vision {

struct TrackingScore {
  double mean_error = 0, p95_error = 0, max_error = 0;  // / chord
  double te_amplitude_truth = 0, te_amplitude_fit = 0;  // mean trailing-edge peak-to-peak (m)
  double te_amplitude_error = 0;                        // worst relative error over TE vertices
};

// `fit`, `truth`: [nf,nv,3] on the same vertices; `trailing_edge`: vertex indices of the
// trailing edge. Throws finverse::Error if the shapes differ.
TrackingScore score_tracking(const NdArray<double>& fit, const NdArray<double>& truth, double chord,
                             const std::vector<std::size_t>& trailing_edge);

}  // namespace finverse::vision
