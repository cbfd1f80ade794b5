// The fin's closed thin body moving with the interpolated mid-surface (see fin_surface_motion.hpp).
#include "cfd/immersed/fin_surface_motion.hpp"

#include <utility>

#include "core/error.hpp"

namespace finverse::cfd {

FinSurfaceMotion::FinSurfaceMotion(ThinBody body, std::vector<std::array<int, 3>> mid_triangles, TimeSpline nodes)
    : body_(std::move(body)), mid_(std::move(mid_triangles)), nodes_(std::move(nodes)) {
  if (nodes_.channels() != 3 * static_cast<std::size_t>(body_.node_count))
    throw Error("fin motion: " + std::to_string(nodes_.channels() / 3) + " moving nodes for a body around " +
                std::to_string(body_.node_count) + " mid-surface nodes");
}

MidSurfaceState FinSurfaceMotion::mid_surface(double t) const {
  const auto n = static_cast<std::size_t>(body_.node_count);
  MidSurfaceState s;
  s.x.resize(n);
  s.v.resize(n);
  s.a.resize(n);
  std::vector<double> x(3 * n), v(3 * n), a(3 * n);
  nodes_.evaluate(t, x.data(), v.data(), a.data());
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t d = 0; d < 3; ++d) {
      s.x[i][d] = x[3 * i + d];
      s.v[i][d] = v[3 * i + d];
      s.a[i][d] = a[3 * i + d];
    }
  return s;
}

SurfaceState FinSurfaceMotion::state(double t) const {
  const MidSurfaceState m = mid_surface(t);
  return place_thin_body(body_, m.x, m.v, m.a, mid_);
}

SurfaceMotion FinSurfaceMotion::as_surface_motion(std::shared_ptr<const FinSurfaceMotion> m) {
  return [m = std::move(m)](double t) { return m->state(t); };
}

}  // namespace finverse::cfd
