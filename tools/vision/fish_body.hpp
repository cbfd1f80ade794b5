// The fish's body and caudal peduncle in front of the fin, for realistic virtual footage (issue 35,
// item 8): in a lab's clip the caudal fin is attached to an opaque body, and the tracker must cut
// the fin from it (fin_separation.hpp). The body is a tapered solid of elliptic cross-section on
// the x axis, from the snout at x = -L to the peduncle at the fin's root (x = 0), deepest (z) and
// widest (y) at 40 % of its length from the snout, narrowing to the peduncle, whose depth is a
// little more than the fin's root segment so the fin's root sits inside it. It follows the fin's
// root (the mean of the root vertices): fore-aft rigidly, across (y, z) with an envelope that falls
// from 1 at the peduncle to head_motion at the snout, quadratic in the distance from the snout (a
// swimming fish's lateral excursion grows towards its tail; the head moves little). The bend is
// in phase along the body (a standing, not a travelling wave). Drawn opaque, lit as the fin is.
// Pectoral fins (issue 47: fins that stick out of a deep-bodied fish's silhouette seen from above):
// two flat fans in the body's mid-depth plane, hinged on the flanks at pectoral_station of the
// length; each fan's rays spread from the flank (pectoral_open_min) to a leading ray whose angle
// from the flank swings between pectoral_open_min and pectoral_open_max at pectoral_frequency, the
// left fin half a cycle after the right (they open and close in turn, as a labriform swimmer's do).
#pragma once

#include <limits>

#include <opencv2/core.hpp>

#include "core/nd_array.hpp"
#include "vision/camera.hpp"
#include "vision/fin_surface.hpp"

namespace finverse::vision {

struct FishBodyOptions {
  double length = 4.0;           // snout to peduncle, in chords
  double max_depth = 1.0;        // dorsal-ventral (z) depth at its deepest, in chords
  double max_width = 0.45;       // lateral (y) width at its widest, in chords
  double peduncle_depth = 1.15;  // depth at the peduncle over the fin's root segment
  double peduncle_width = 0.12;  // width at the peduncle, in chords
  double level = 0.2;            // grey level of the lit body (the fin's membrane: 0.55)
  double head_motion = 0.1;      // the snout's lateral excursion over the peduncle's
  int stations = 48;             // cross-sections from snout to peduncle
  int sides = 32;                // vertices around a cross-section
  double pectoral_length = 0;    // pectoral fin length, in chords (0: none)
  double pectoral_station = 0.3;  // hinge, as a fraction of the length from the snout
  double pectoral_open_min = 10;  // angle of the fin's rays from the flank, closed (degrees)
  double pectoral_open_max = 80;  // ... of the leading ray, fully open (degrees)
  double pectoral_frequency = 1;  // opening and closing cycles per second
  double pectoral_level = 0.3;    // grey level of a lit pectoral fin
};

// One sample layer of the opaque body in a camera: camera-frame depth (+inf where the body is
// absent) and the body's grey level, CV_32F, at the renderer's supersampled resolution.
struct OpaqueLayer {
  cv::Mat depth, level;
};

class FishBody {
 public:
  // Throws finverse::Error naming the flag when an option is out of range.
  FishBody(const FinSurface& fin, const FishBodyOptions& options);

  // The body's vertices [nb,3] (m), pectoral fins included, for the fin at `fin_positions`
  // [nv,3] at time `t` (s; the pectoral fins' phase).
  NdArray<double> place(const NdArray<double>& fin_positions, double t = 0) const;
  const NdArray<std::int32_t>& triangles() const { return triangles_; }

  // The body's axis [stations + 2, 3] (m): the snout, the centre of every cross-section and the
  // peduncle's end, placed as place() places the body (the true midline of the 2-D mode, issue 47).
  NdArray<double> axis(const NdArray<double>& fin_positions) const;

  // Z-buffered rasterisation at `supersample` samples per pixel and axis (the renderer's grid).
  OpaqueLayer rasterize(const Camera& camera, const NdArray<double>& fin_positions, int supersample,
                        double time = 0) const;

 private:
  const FinSurface& fin_;
  FishBodyOptions o_;
  NdArray<double> rest_;              // [nb,3] at the fin's rest pose
  NdArray<std::int32_t> triangles_;   // [nt,3]
  std::vector<std::size_t> root_;     // the fin's root vertices (s = 0)
  std::vector<double> envelope_;      // per body vertex: its share of the root's y and z motion
  std::size_t trunk_ = 0;             // vertices of the trunk; the pectoral fans' follow
  cv::Vec3d hinge_[2];                // the pectoral hinges at rest (right, left)
  double pectoral_envelope_ = 0;      // the hinges' share of the root's y and z motion

  void add_pectoral_fins(std::vector<std::int32_t>& triangles);
  double pectoral_opening(int side, double t) const;  // the leading ray's angle from the flank (rad)
};

}  // namespace finverse::vision
