// Distance between two motions of the fin (see motion_distance.hpp).
#include "report/motion_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/error.hpp"
#include "mesh/motion_transfer.hpp"

namespace finverse::report {

NdArray<double> truth_on_mesh(const stage::Truth& truth, const stage::Mesh& mesh) {
  const auto binding = mesh::bind_to_surface(truth.template_points, truth.template_triangles, mesh.points);
  return mesh::carry_motion(binding, truth.points);
}

double mean_node_distance(const NdArray<double>& a_time, const NdArray<double>& a_points, const NdArray<double>& b_time,
                          const NdArray<double>& b_points) {
  if (a_points.rank() != 3 || b_points.rank() != 3 || a_points.dim(1) != b_points.dim(1))
    throw Error("motion distance: the motions have different node counts (" + shape_string(a_points.shape) + " vs " +
                shape_string(b_points.shape) + ")");
  const std::size_t nb = b_time.size(), nv = a_points.dim(1);
  if (nb == 0 || b_points.dim(0) != nb || a_points.dim(0) != a_time.size())
    throw Error("motion distance: times and frames do not match");
  const double eps = 1e-9 * std::max(1e-12, std::abs(b_time(nb - 1) - b_time(0)));
  double sum = 0;
  std::size_t count = 0;
  for (std::size_t f = 0; f < a_time.size(); ++f) {
    const double t = a_time(f);
    if (t < b_time(0) - eps || t > b_time(nb - 1) + eps) continue;
    std::size_t k = 0;
    while (k + 2 < nb && b_time(k + 1) < t) ++k;
    const double span = nb > 1 ? b_time(k + 1) - b_time(k) : 0;
    const double w = span > 0 ? std::clamp((t - b_time(k)) / span, 0.0, 1.0) : 0.0;
    const std::size_t k1 = nb > 1 ? k + 1 : k;
    for (std::size_t v = 0; v < nv; ++v) {
      double d2 = 0;
      for (std::size_t a = 0; a < 3; ++a) {
        const double b = (1 - w) * b_points(k, v, a) + w * b_points(k1, v, a);
        d2 += (a_points(f, v, a) - b) * (a_points(f, v, a) - b);
      }
      sum += std::sqrt(d2);
    }
    count += nv;
  }
  return count ? sum / double(count) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace finverse::report
