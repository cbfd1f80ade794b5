// A rigid thin plate heaving and pitching in a stream, written as a mesh.h5 / motion.h5 pair of
// the same form fin-mesh writes (the fin-cfd loads validation, rules/cfd.smk thin_plate_loads):
// a chord x span rectangle in the x-z plane (leading edge at x = 0, span along +z), structured
// triangles counter-clockwise in (x, z) as fin-mesh's planform, the closed thin body of
// thin_body.hpp, one "ray" of beams along the leading edge (the root nodes), and the motion
//     y_heave(t) = h0 sin(2 pi t / T),   theta(t) = theta0 sin(2 pi t / T + phase)
// (pitch about the z axis through x = pivot), sampled at t_k = k T / frames with attribute T, and
// its exact velocity.
#pragma once

#include <nlohmann/json.hpp>

#include "core/stage_files.hpp"

namespace finverse::cfd::io {

struct ThinPlateSetup {
  double chord = 0.01, span = 0.015;  // [m]
  int nx = 8, nz = 12;                // cells along the chord and the span (2 triangles each)
  double thickness = 0.001;           // closed-body (IBM) thickness [m]
  double heave = 0.0044;              // h0 [m]
  double pitch = 0.35;                // theta0 [rad]
  double phase = 1.5707963267948966;  // pitch leads heave by this [rad]
  double pivot = 0.0025;              // pitch axis x [m]
  double period = 0.2;                // T [s]
  int frames = 40;                    // samples per period
};

struct ThinPlateFiles {
  stage::Mesh mesh;
  stage::Motion motion;
};

ThinPlateFiles make_thin_plate(const ThinPlateSetup& s);

// The set-up as recorded in the files' provenance (config attribute "plate").
nlohmann::json describe(const ThinPlateSetup& s);

}  // namespace finverse::cfd::io
