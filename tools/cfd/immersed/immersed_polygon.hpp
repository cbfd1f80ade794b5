// A closed 2-D body for the sharp-interface ghost-cell immersed boundary (Mittal et al. 2008,
// J. Comput. Phys. 227:4825; DESIGN.md section 5.1): a simple polygon, counter-clockwise, with
// the geometry queries the ghost-cell method needs: inside/outside of a cell centre, and the
// closest surface point with its outward normal (the boundary intercept of a ghost cell's probe).
// The 3-D counterpart is a closed triangulated surface with the same queries.
#pragma once

#include <array>
#include <vector>

namespace finverse::cfd {

struct SurfacePoint {
  std::array<double, 2> point{};   // closest point on the polygon
  std::array<double, 2> normal{};  // outward unit normal there
  double distance = 0;             // signed: > 0 outside the body, < 0 inside
  // The edge it lies on (vertices edge -> edge + 1 of Polygon::vertices()) and its parameter along
  // it in [0, 1] (for interpolating vertex data; -1 where not from Polygon::closest).
  int edge = -1;
  double edge_t = 0;
};

// Shoelace area of a vertex loop: > 0 counter-clockwise, < 0 clockwise.
double polygon_signed_area(const std::vector<std::array<double, 2>>& vertices);

class Polygon {
 public:
  // At least 3 distinct vertices, no self-intersections (not checked); either orientation (stored
  // counter-clockwise).
  explicit Polygon(std::vector<std::array<double, 2>> vertices);
  // A circle of radius r as a regular n-gon with the vertices on the circle.
  static Polygon circle(double cx, double cy, double r, int n);

  bool contains(double x, double y) const;  // crossing-number test
  std::array<double, 4> bounds() const;     // x_min, y_min, x_max, y_max of the vertices
  SurfacePoint closest(double x, double y) const;
  double area() const;
  const std::vector<std::array<double, 2>>& vertices() const { return v_; }

 private:
  std::vector<std::array<double, 2>> v_;
};

// A solid region of the immersed boundary: the inside of a closed polygon (a body), or with
// outside = true its outside (the polygon encloses the fluid, e.g. the outer cylinder of a
// Couette cell). closest() then reports the normal pointing into the fluid and the distance
// positive in the fluid, as for a body.
struct SolidRegion {
  Polygon polygon;
  bool outside = false;
  bool contains(double x, double y) const { return polygon.contains(x, y) != outside; }
  SurfacePoint closest(double x, double y) const {
    SurfacePoint s = polygon.closest(x, y);
    if (outside) {
      s.normal = {-s.normal[0], -s.normal[1]};
      s.distance = -s.distance;
    }
    return s;
  }
};

}  // namespace finverse::cfd
