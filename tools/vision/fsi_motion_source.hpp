// The truth motion from the fin's flow-structure simulation (issue 33, Deliver 1; DESIGN.md
// section 1: fin-synth "computes the motion with fin-fsi"). A MotionSource over fsi.h5 and the
// mesh.h5 it ran on:
//   - space: every render-surface vertex is bound once, at rest, to the nearest mid-surface
//     triangle of the mesh; its affine (barycentric) coordinates in that triangle's plane, not
//     clamped, and its offset along the normal then follow the deformed triangle. Affine
//     coordinates make a rigid motion exact, also for vertices just outside the mesh's outline;
//   - time: periodic cubic Hermite interpolation in T (C1) of the node positions over the last
//     period of the samples, slopes from second-order differences on the periodic sample set,
//     so the camera frames may fall between FSI outputs.
// Frame times are absolute: t and the FSI's own times are compared modulo T.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "core/nd_array.hpp"
#include "vision/fin_surface.hpp"
#include "vision/kinematic_model.hpp"

namespace finverse::vision {

struct FsiSamples {
  NdArray<double> rest;                 // [nv,3] mesh nodes at rest
  NdArray<std::int32_t> triangles;      // [ntri,3] mid-surface triangles
  std::vector<double> time;             // [nt] s, increasing
  NdArray<double> points;               // [nt,nv,3] node positions
  double period = 0;                    // s
  std::string label = "fsi";            // names the data in errors (file names)
  std::string source = "fsi";           // the motion source's name: fsi, or fem (a fin-fem run)
};

class FsiMotion final : public MotionSource {
 public:
  // Binds `surface` (its rest vertices) to the mesh; throws finverse::Error naming s.label for
  // samples that do not fit together or do not cover one period.
  FsiMotion(FsiSamples s, const FinSurface& surface);
  std::string name() const override { return source_; }
  double period() const override { return period_; }
  NdArray<double> positions(const FinSurface& surface, double t) const override;
  nlohmann::json parameters() const override;

  // Mesh node positions [nv,3] at time t (the periodic interpolation).
  NdArray<double> node_positions(double t) const;
  // Largest distance (m) of a surface vertex from the mesh's rest mid-surface.
  double max_outside_distance() const { return max_outside_; }
  // Largest node distance (m) between samples one period apart (0 when none are): how far the
  // simulated motion is from periodic.
  double periodicity_gap() const { return periodicity_gap_; }

 private:
  struct Binding {
    std::array<int, 3> nodes;
    std::array<double, 3> weights;  // affine: sum 1, may be < 0 just outside the triangle
    double normal_offset;           // m, along the triangle's unit normal
  };
  std::string label_, source_;
  double period_;
  std::size_t nv_;
  std::vector<double> phase_;                   // sample phases in [0, T), increasing
  std::vector<NdArray<double>> value_, slope_;  // [nv,3] per phase sample
  std::vector<Binding> binding_;
  double max_outside_ = 0, periodicity_gap_ = 0, t_first_ = 0, t_last_ = 0;
  std::size_t samples_used_ = 0;
};

// Reads fsi.h5 (stage::Fsi) and the mesh.h5 it ran on (stage::Mesh) and binds `surface`. One-line
// errors (exit 2 in the apps) name both files when the node counts differ, T is missing, the
// reference state is not the mesh's, or the surface is not on the mesh's fin (farther than
// max_distance_over_chord * c).
FsiMotion read_fsi_motion(const std::filesystem::path& fsi, const std::filesystem::path& mesh, const FinSurface& surface,
                          double max_distance_over_chord = 0.05);
// The same over a structural response (fin-fem run's finverse/motion output, with T) on the
// mesh.h5 it ran on: the cheap truth of issue 34's virtual fish (source "fem").
FsiMotion read_fem_motion(const std::filesystem::path& motion, const std::filesystem::path& mesh,
                          const FinSurface& surface, double max_distance_over_chord = 0.05);

}  // namespace finverse::vision
