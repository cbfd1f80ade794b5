// Bayesian information criterion of a least-squares fit with Gaussian errors of unknown variance
// (Schwarz 1978): BIC = m ln(RSS / m) + k ln m, m residuals, k parameters; lower is better.
// On a fin the residuals of neighbouring nodes and frames are correlated, so m overstates the
// independent data and BIC alone admits small gains: the tracer (effect_tracing.hpp) also asks
// that the error on held-out cycles falls.
#pragma once

namespace finverse::loop {

// Throws InvalidInput for m < 1, k < 0 or rss < 0; rss 0 gives -infinity.
double bic(double rss, long m, int k);

}  // namespace finverse::loop
