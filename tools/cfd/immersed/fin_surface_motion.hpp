// The moving fin as the 3-D immersed boundary sees it (DESIGN.md section 5.1): the mid-surface node
// positions of motion.h5 interpolated in time (time_spline.hpp) and the closed thin body placed
// around the deformed mid-surface at every instant (thin_body.hpp), as a cfd::SurfaceMotion.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "cfd/immersed/thin_body.hpp"
#include "cfd/immersed/time_spline.hpp"
#include "cfd/immersed/triangulated_surface.hpp"

namespace finverse::cfd {

// Mid-surface nodes at one instant: positions, velocities, accelerations (all [nv]).
struct MidSurfaceState {
  std::vector<Vec3> x, v, a;
};

class FinSurfaceMotion {
 public:
  // nodes: the spline of the nv mid-surface nodes (3 nv channels, node-major, x y z).
  FinSurfaceMotion(ThinBody body, std::vector<std::array<int, 3>> mid_triangles, TimeSpline nodes);

  MidSurfaceState mid_surface(double t) const;
  SurfaceState state(double t) const;
  // A copyable SurfaceMotion that shares this motion.
  static SurfaceMotion as_surface_motion(std::shared_ptr<const FinSurfaceMotion> m);

  const ThinBody& body() const { return body_; }
  const std::vector<std::array<int, 3>>& mid_triangles() const { return mid_; }
  const TimeSpline& nodes() const { return nodes_; }

 private:
  ThinBody body_;
  std::vector<std::array<int, 3>> mid_;
  TimeSpline nodes_;
};

}  // namespace finverse::cfd
