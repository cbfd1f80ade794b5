// Harmonics of the beat frequency in a sampled signal (issue 34, residual analysis): each row of a
// [rows, nf] matrix is fitted by least squares with
//     x(t) = m + sum_k Re(c_k e^(i k w t)),  w = 2 pi / T,  k = 1..K,
// i.e. c_k = a_k - i b_k for a_k cos(k w t) + b_k sin(k w t). The constant m is the cycle mean
// when the samples cover whole periods. A least-squares fit rather than an FFT, since the frames
// need not cover a whole number of periods or be equally spaced; such a fit over less than one
// period is ill-conditioned, which `condition` and `whole_period` report (the summary flags it).
#pragma once

#include <complex>
#include <vector>

#include <Eigen/Core>

namespace finverse::loop {

struct Harmonics {
  double period = 0;
  int order = 0;                        // K
  Eigen::VectorXd mean;                 // [rows]
  std::vector<Eigen::VectorXcd> coefficient;  // [K][rows]: c_k
  double condition = 0;                 // 2-norm condition number of the (column-scaled) design
  bool whole_period = false;            // the samples span at least one period
};

// Throws InvalidInput when period <= 0, order < 0, or fewer frames than 2 order + 1.
Harmonics fit_harmonics(const std::vector<double>& times, const Eigen::MatrixXd& rows, double period, int order);

// Per node (rows 3 i .. 3 i + 2) of harmonic k (1-based): amplitude sqrt(sum_c |c_k,c|^2) and the
// phase arg(c_k) of the node's axis with the largest |c_k,c| (x(t) = A cos(k w t + phase)).
Eigen::VectorXd node_amplitude(const Harmonics& h, int k);
Eigen::VectorXd node_phase(const Harmonics& h, int k);

}  // namespace finverse::loop
