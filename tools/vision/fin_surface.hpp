// The truth fin surface that fin-synth moves and renders: a structured triangulation of the
// template's planform, column by column between neighbouring rays (seed paper section 4.1: rays
// with membrane between). Each vertex knows where it sits on the fin: its continuous ray
// coordinate, its arc-length fraction along the rays, its root point and its in-plane distance to
// the nearest ray, which is what the kinematic model and the renderer need.
#pragma once

#include <array>
#include <vector>

#include "core/nd_array.hpp"
#include "mesh/fin_template.hpp"

namespace finverse::vision {

struct FinSurface {
  double chord = 0;
  std::size_t rays = 0;
  NdArray<double> rest;                       // [nv,3] (x, 0, z), metres
  NdArray<std::int32_t> triangles;            // [ntri,3]
  std::vector<double> eta;                    // +1 dorsal edge .. -1 ventral edge, linear in ray index
  std::vector<double> s;                      // arc-length fraction along the rays, 0 root .. 1 tip
  std::vector<std::array<double, 2>> root;    // rest root point (x, z) of the vertex's ray line
  std::vector<double> ray_distance;           // in-plane distance to the nearest ray axis, metres
  std::vector<double> ray_half_width;         // half the in-plane width of that ray here, metres
  std::size_t size() const { return s.size(); }
};

// `subdivisions` columns of triangles per gap between two rays. Ray lines are sampled at their
// own polyline points when every ray has the same number of points (so the surface follows the
// template's rays and outline exactly), else at evenly spaced arc-length fractions.
FinSurface make_fin_surface(const mesh::FinTemplate& t, int subdivisions = 4);

}  // namespace finverse::vision
