// BIC of a Gaussian least-squares fit (information_criterion.hpp).
#include "loop/information_criterion.hpp"

#include <cmath>
#include <string>

#include "loop/errors.hpp"

namespace finverse::loop {

double bic(double rss, long m, int k) {
  if (m < 1 || k < 0 || !(rss >= 0))
    throw InvalidInput("BIC: expected m >= 1, k >= 0, rss >= 0 (got m " + std::to_string(m) + ", k " +
                       std::to_string(k) + ")");
  const double md = static_cast<double>(m);
  return md * std::log(rss / md) + k * std::log(md);
}

}  // namespace finverse::loop
