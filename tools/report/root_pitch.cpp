// Root pitch per ray (see root_pitch.hpp; paper Fig. 12).
#include "report/root_pitch.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace finverse::report {

std::vector<std::vector<double>> root_pitch_deg(const NdArray<double>& points, const NdArray<std::int32_t>& ray_offsets,
                                                const NdArray<std::int32_t>& ray_vertices) {
  if (points.rank() != 3 || points.dim(2) != 3) throw Error("root pitch: expected points [nf,nv,3]");
  const std::size_t nf = points.dim(0), nv = points.dim(1);
  std::vector<std::vector<double>> out;
  for (std::size_t r = 0; r + 1 < ray_offsets.size(); ++r) {
    const auto begin = static_cast<std::size_t>(ray_offsets(r)), end = static_cast<std::size_t>(ray_offsets(r + 1));
    if (end < begin + 2 || end > ray_vertices.size())
      throw Error("root pitch: ray " + std::to_string(r + 1) + " has fewer than 2 vertices");
    const std::size_t len = end - begin;
    const auto a = static_cast<std::size_t>(ray_vertices(begin));
    const auto b = static_cast<std::size_t>(ray_vertices(begin + std::max<std::size_t>(1, len / 5)));
    if (a >= nv || b >= nv) throw Error("root pitch: ray " + std::to_string(r + 1) + " names a vertex outside the points");
    std::vector<double> pitch(nf);
    for (std::size_t f = 0; f < nf; ++f) {
      const double dx = points(f, b, 0) - points(f, a, 0), dy = points(f, b, 1) - points(f, a, 1),
                   dz = points(f, b, 2) - points(f, a, 2);
      pitch[f] = std::atan2(dy, std::hypot(dx, dz)) * 180.0 / std::numbers::pi;
    }
    out.push_back(std::move(pitch));
  }
  return out;
}

}  // namespace finverse::report
