// Rectangular section constants and Gauss-Legendre rules (see beam_section.hpp).
#include "fem/beam_section.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fem/errors.hpp"

namespace finverse::fem {

SectionConstants rectangle(double width, double thickness) {
  SectionConstants s;
  s.area = width * thickness;
  s.iy = width * thickness * thickness * thickness / 12.0;
  s.iz = thickness * width * width * width / 12.0;
  const double a = std::max(width, thickness), c = std::min(width, thickness);
  const double r = c / a;
  s.j = a * c * c * c * (1.0 / 3.0 - 0.21 * r * (1.0 - r * r * r * r / 12.0));
  return s;
}

SectionConstants TaperedRectangle::at(double xi) const {
  return rectangle((1.0 - xi) * width[0] + xi * width[1],
                   (1.0 - xi) * thickness[0] + xi * thickness[1]);
}

void TaperedRectangle::validate() const {
  for (int i = 0; i < 2; ++i) {
    if (!(std::isfinite(width[i]) && width[i] > 0) ||
        !(std::isfinite(thickness[i]) && thickness[i] > 0)) {
      std::ostringstream os;
      os << "beam section at node " << i + 1 << ": width " << width[i] << ", thickness "
         << thickness[i] << ", expected finite values > 0";
      throw InvalidInput(os.str());
    }
  }
}

namespace {
// Nodes/weights on [-1, 1] (Abramowitz & Stegun 25.4.30), mapped to [0, 1] on first use.
struct Table {
  std::array<std::array<double, 8>, 9> x{}, w{};
  Table() {
    const double raw_x[9][8] = {
        {},
        {0},
        {-0.5773502691896257645, 0.5773502691896257645},
        {-0.7745966692414833770, 0, 0.7745966692414833770},
        {-0.8611363115940525752, -0.3399810435848562648, 0.3399810435848562648,
         0.8611363115940525752},
        {-0.9061798459386639928, -0.5384693101056830910, 0, 0.5384693101056830910,
         0.9061798459386639928},
        {-0.9324695142031520279, -0.6612093864662645137, -0.2386191860831969086,
         0.2386191860831969086, 0.6612093864662645137, 0.9324695142031520279},
        {-0.9491079123427585245, -0.7415311855993944399, -0.4058451513773971669, 0,
         0.4058451513773971669, 0.7415311855993944399, 0.9491079123427585245},
        {-0.9602898564975362317, -0.7966664774136267396, -0.5255324099163289858,
         -0.1834346424956498049, 0.1834346424956498049, 0.5255324099163289858,
         0.7966664774136267396, 0.9602898564975362317}};
    const double raw_w[9][8] = {
        {},
        {2},
        {1, 1},
        {0.5555555555555555556, 0.8888888888888888889, 0.5555555555555555556},
        {0.3478548451374538574, 0.6521451548625461426, 0.6521451548625461426,
         0.3478548451374538574},
        {0.2369268850561890875, 0.4786286704993664680, 0.5688888888888888889,
         0.4786286704993664680, 0.2369268850561890875},
        {0.1713244923791703450, 0.3607615730481386076, 0.4679139345726910474,
         0.4679139345726910474, 0.3607615730481386076, 0.1713244923791703450},
        {0.1294849661688696933, 0.2797053914892766679, 0.3818300505051189449,
         0.4179591836734693878, 0.3818300505051189449, 0.2797053914892766679,
         0.1294849661688696933},
        {0.1012285362903762591, 0.2223810344533744706, 0.3137066458778872873,
         0.3626837833783619830, 0.3626837833783619830, 0.3137066458778872873,
         0.2223810344533744706, 0.1012285362903762591}};
    for (int n = 1; n <= 8; ++n)
      for (int i = 0; i < n; ++i) {
        x[n][i] = 0.5 * (raw_x[n][i] + 1.0);
        w[n][i] = 0.5 * raw_w[n][i];
      }
  }
};
const Table& table() {
  static const Table t;
  return t;
}
}  // namespace

GaussRule gauss_legendre_01(int n) {
  if (n < 1 || n > 8) throw InvalidInput("Gauss rule: " + std::to_string(n) + " points, expected 1..8");
  const Table& t = table();
  return {std::span<const double>(t.x[n].data(), n), std::span<const double>(t.w[n].data(), n)};
}

}  // namespace finverse::fem
