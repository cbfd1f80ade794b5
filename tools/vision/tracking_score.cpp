// Reconstruction error against truth.h5 (issue 5, "Accuracy").
#include "vision/tracking_score.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace finverse::vision {

TrackingScore score_tracking(const NdArray<double>& fit, const NdArray<double>& truth, double chord,
                             const std::vector<std::size_t>& te) {
  if (fit.shape != truth.shape || fit.rank() != 3 || fit.dim(2) != 3)
    throw Error("tracking score: reconstruction " + shape_string(fit.shape) + " and truth " + shape_string(truth.shape) +
                " must both be [nf,nv,3] on the same template");
  const std::size_t nf = fit.dim(0), nv = fit.dim(1);
  std::vector<double> e(nf * nv);
  for (std::size_t i = 0; i < nf * nv; ++i) {
    double d2 = 0;
    for (int d = 0; d < 3; ++d) d2 += std::pow(fit.data[3 * i + d] - truth.data[3 * i + d], 2);
    e[i] = std::sqrt(d2) / chord;
  }
  TrackingScore s;
  if (e.empty()) return s;
  double sum = 0;
  for (double x : e) sum += x;
  s.mean_error = sum / e.size();
  const std::size_t k = std::min(e.size() - 1, static_cast<std::size_t>(std::ceil(0.95 * e.size())) - 1);
  std::nth_element(e.begin(), e.begin() + k, e.end());
  s.p95_error = e[k];
  s.max_error = *std::max_element(e.begin(), e.end());
  // Peak-to-peak lateral (y) excursion of every trailing-edge vertex over the record.
  double at = 0, af = 0;
  for (std::size_t v : te) {
    double tlo = 1e300, thi = -1e300, flo = 1e300, fhi = -1e300;
    for (std::size_t f = 0; f < nf; ++f) {
      tlo = std::min(tlo, truth(f, v, 1)), thi = std::max(thi, truth(f, v, 1));
      flo = std::min(flo, fit(f, v, 1)), fhi = std::max(fhi, fit(f, v, 1));
    }
    at += thi - tlo;
    af += fhi - flo;
    if (thi > tlo) s.te_amplitude_error = std::max(s.te_amplitude_error, std::abs((fhi - flo) - (thi - tlo)) / (thi - tlo));
  }
  if (!te.empty()) s.te_amplitude_truth = at / te.size(), s.te_amplitude_fit = af / te.size();
  return s;
}

}  // namespace finverse::vision
