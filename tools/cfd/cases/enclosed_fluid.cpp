// Flows inside walls: the pipes: lists of inlet sides, their inflow, and the geometric checks of a
// case whose fluid a body encloses; see enclosed_fluid.hpp.
#include "cfd/cases/enclosed_fluid.hpp"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "cfd/immersed/surface_geometry.hpp"
#include "core/error.hpp"

namespace finverse::cfd::cases {

namespace {

const char* const kSides[] = {"x_lo", "x_hi", "y_lo", "y_hi", "z_lo", "z_hi"};

std::string point(const Vec3& x) {
  char b[96];
  std::snprintf(b, sizeof b, "(%.6g, %.6g, %.6g)", x[0], x[1], x[2]);
  return b;
}

// The point at angle phi and distance rho from a disc's centre on side `side`'s plane.
Vec3 on_disc(const PipeInlet& p, int side, double rho, double phi) {
  const int a = side / 2, e1 = (a + 1) % 3, e2 = (a + 2) % 3;
  Vec3 x = p.centre;
  x[static_cast<std::size_t>(e1)] += rho * std::cos(phi);
  x[static_cast<std::size_t>(e2)] += rho * std::sin(phi);
  return x;
}

}  // namespace

std::vector<PipeInlet> read_pipe_inlets(const Reader& r, const YAML::Node& list, const std::string& at,
                                        const FlowCaseSpec& s, int side) {
  if (!list.IsSequence() || list.size() == 0) r.fail(list, at, "expected a list of {centre, radius, velocity}");
  const int a = side / 2;
  const double plane = s.domain[static_cast<std::size_t>(side)];
  const double extent = s.domain[static_cast<std::size_t>(2 * a + 1)] - s.domain[static_cast<std::size_t>(2 * a)];
  std::vector<PipeInlet> pipes;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string here = at + "[" + std::to_string(i) + "]";
    const YAML::Node n = list[i];
    r.only(n, here, {"centre", "radius", "velocity"});
    for (const char* k : {"centre", "radius", "velocity"})
      if (!n[k]) r.fail(n, here, std::string("missing ") + k);
    PipeInlet p;
    p.centre = r.numbers<3>(n["centre"], here + ".centre");
    if (std::abs(p.centre[static_cast<std::size_t>(a)] - plane) > 1e-9 * extent)
      r.fail(n["centre"], here + ".centre",
             std::string("its ") + "xyz"[a] + " is " + std::to_string(p.centre[static_cast<std::size_t>(a)]) +
                 ", not on the side's plane " + "xyz"[a] + " = " + std::to_string(plane));
    p.radius = r.positive(n["radius"], here + ".radius");
    p.speed = r.positive(n["velocity"], here + ".velocity");
    for (int d = 0; d < 3; ++d) {
      if (d == a) continue;
      const double c = p.centre[static_cast<std::size_t>(d)];
      if (c - p.radius < s.domain[static_cast<std::size_t>(2 * d)] ||
          c + p.radius > s.domain[static_cast<std::size_t>(2 * d + 1)])
        r.fail(n, here, std::string("the disc reaches beyond the side (along ") + "xyz"[d] + ")");
    }
    pipes.push_back(p);
  }
  return pipes;
}

VelocityFunction pipe_inflow(const std::vector<PipeInlet>& pipes, int side) {
  const int a = side / 2;
  const double sign = side % 2 == 1 ? -1.0 : 1.0;
  return [pipes, a, sign](double x, double y, double z, double) {
    const double xyz[3] = {x, y, z};
    double u = 0;
    for (const PipeInlet& p : pipes) {
      double r2 = 0;
      for (int d = 0; d < 3; ++d)
        if (d != a) r2 += (xyz[d] - p.centre[static_cast<std::size_t>(d)]) * (xyz[d] - p.centre[static_cast<std::size_t>(d)]);
      if (r2 < p.radius * p.radius) u += p.speed * (1 - r2 / (p.radius * p.radius));
    }
    std::array<double, 3> v{0, 0, 0};
    v[static_cast<std::size_t>(a)] = sign * u;
    return v;
  };
}

void check_enclosed_fluid(const Reader& r, const YAML::Node& root, const FlowCaseSpec& s) {
  std::vector<CaseBody> walls;
  for (const CaseBody& b : s.bodies)
    if (b.encloses_fluid) walls.push_back(b);
  if (walls.empty()) {
    for (int k = 0; k < 6; ++k)
      if (!s.sides[static_cast<std::size_t>(k)].pipes.empty())
        r.fail(root["boundaries"][kSides[k]]["pipes"], std::string("boundaries.") + kSides[k] + ".pipes",
               "no body encloses the fluid (a pipe's body needs fluid: inside)");
    return;
  }
  std::vector<std::size_t> first;
  SurfaceGeometry wall;
  try {
    wall = SurfaceGeometry(merged_bodies(walls, first), "the bodies with fluid: inside");
  } catch (const Error& e) {
    r.fail(root["bodies"], "bodies", e.what());
  }
  // Every other body floats in the fluid or is clamped to a wall: all its vertices on the fluid
  // side of the walls or on them (a flap's root), within rounding of the walls' size.
  const double touch = 1e-9 * norm(sub(wall.upper(), wall.lower()));
  for (std::size_t i = 0; i < s.bodies.size(); ++i) {
    const CaseBody& b = s.bodies[i];
    if (b.encloses_fluid) continue;
    for (std::size_t v = 0; v < b.surface.points.size(); ++v)
      if (!(wall.closest(b.surface.points[v]).distance >= -touch))
        r.fail(root["bodies"][i], "bodies[" + std::to_string(i) + "]",
               "body " + b.name + " sticks through a wall: its vertex " + std::to_string(v) + " at " +
                   point(b.surface.points[v]) + " is outside the fluid that the bodies with fluid: inside enclose");
  }
  // Every inlet disc is a pipe's cross-section: fluid out to 0.95 R, solid from 1.05 R.
  for (int k = 0; k < 6; ++k) {
    const auto& pipes = s.sides[static_cast<std::size_t>(k)].pipes;
    for (std::size_t i = 0; i < pipes.size(); ++i) {
      const std::string at = std::string("boundaries.") + kSides[k] + ".pipes[" + std::to_string(i) + "]";
      const YAML::Node n = root["boundaries"][kSides[k]]["pipes"][i];
      const PipeInlet& p = pipes[i];
      if (!(wall.closest(p.centre).distance > 0))
        r.fail(n, at, "the disc's centre " + point(p.centre) + " is not in a pipe's fluid");
      for (int q = 0; q < 32; ++q) {
        const double phi = 2 * std::numbers::pi * q / 32;
        const Vec3 in = on_disc(p, k, 0.95 * p.radius, phi), out = on_disc(p, k, 1.05 * p.radius, phi);
        if (!(wall.closest(in).distance > 0))
          r.fail(n, at,
                 "the disc does not meet a pipe's cross-section: " + point(in) +
                     ", at 0.95 of its radius, is in the wall (a narrower pipe, or none there)");
        if (!(wall.closest(out).distance < 0))
          r.fail(n, at,
                 "the disc does not fill the pipe's cross-section: " + point(out) +
                     ", at 1.05 of its radius, is still fluid (a wider or oblique pipe)");
      }
    }
  }
}

}  // namespace finverse::cfd::cases
