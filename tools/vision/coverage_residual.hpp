// Sub-pixel, area-based silhouette term (issue 5: silhouette IoU >= 0.97 in the edge-on views).
// The chamfer residuals (silhouette_residual.hpp) compare pixel-centre silhouettes, so the fit can
// place an edge only to within a pixel; an edge-on view of the thin fin is a strip 4-10 px wide
// and an IoU of 0.97 needs both of its edges to about 0.1 px. Here every pixel of a band around
// the data silhouette compares coverages, the fraction of the pixel's area the fin covers:
//   r = model coverage - data coverage,
// the data coverage being the darkening relative to the local full contrast
// (segmentation.hpp, Segmentation::coverage). The model coverage of a pixel near the model's
// projected outline is that of the half-plane behind the nearest outline edge (a boundary edge
// of the mesh or a fold, where the two triangles of an edge project onto the same side of it):
// with d the signed distance (px, positive inside) of the pixel centre from the edge's line and
// n = (nx, ny) its unit normal, the covered area is the distribution function at d of n . u for
// u uniform on the unit pixel, a piecewise quadratic (the convolution of two boxes of widths |nx|
// and |ny|), exact for a straight edge. Its derivative with respect to the edge's two projected
// vertices is exact for a line, dd/da = -(1 - t) n, dd/db = -t n (t the foot of the pixel centre
// along the edge), and goes on through the projection and skinning Jacobians. Pixels no model
// edge reaches take the pixel-centre silhouette (0 or 1, no gradient). Where a second outline
// edge facing the other way also cuts the pixel, the two half-planes combine: a sliver (their
// intersection) covers c1 + c2 - 1, a gap between two prongs (the complement) c1 + c2.
// The band is the data's (pixels within band_px of the segmented outline), so the residual set
// does not change with the pose and LM costs of candidate poses compare. What the term gains, and
// fin-track's weight, band and views: docs/studies/tracking_fit_defaults.md.
#pragma once

#include <array>
#include <vector>

#include <opencv2/core.hpp>

#include "core/nd_array.hpp"
#include "vision/normal_equations.hpp"
#include "vision/silhouette_residual.hpp"
#include "vision/skinning.hpp"
#include "vision/view_data.hpp"

namespace finverse::vision {

// A mesh edge with its one or two triangles (t1 = -1 on the mesh boundary).
struct MeshEdge {
  int a, b, t0, t1;
};
// Throws finverse::Error if an edge has more than two triangles.
std::vector<MeshEdge> mesh_edges(const NdArray<std::int32_t>& triangles);

// Area of the unit pixel on the inner side of a straight edge whose line passes at signed
// distance d (px, positive: the pixel centre is inside) with unit normal (nx, ny); `slope` gets
// the derivative with respect to d.
double half_plane_coverage(double d, double nx, double ny, double* slope);

// Coverage of every pixel by the projected model (as above), CV_32F of the camera's size.
class ModelCoverage {
 public:
  ModelCoverage(const ModelView& model, const NdArray<std::int32_t>& triangles, const std::vector<MeshEdge>& edges);

  // The coverage of a pixel and the outline edges that set it (none: pixel-centre silhouette,
  // no gradient; two: a sliver or a gap narrower than a pixel, between edges facing opposite ways).
  struct Sample {
    double coverage = 0;
    int count = 0;
    std::array<int, 2> edge{-1, -1};
    std::array<double, 2> slope{0, 0};  // d coverage / d (signed distance from that edge)
    std::array<double, 2> t{0, 0};      // foot of the pixel centre along the edge (0 at a, 1 at b)
    std::array<cv::Point2d, 2> n;       // inward unit normal of the edge
  };
  Sample at(int x, int y) const;
  const MeshEdge& edge(int e) const { return edges_[static_cast<std::size_t>(e)]; }
  cv::Mat image() const;  // the coverage of every pixel (tests, diagnostics)

 private:
  bool covered_by_others(cv::Point2d q, const MeshEdge& e) const;
  const ModelView& m_;
  const NdArray<std::int32_t>& tri_;
  const std::vector<MeshEdge>& edges_;
  std::vector<int> outline_;          // indices of outline edges
  std::vector<cv::Point2d> inward_;   // their inward normals
  int nx_ = 0, ny_ = 0;
  std::vector<std::vector<int>> edge_cells_, tri_cells_;
};

struct CoverageOptions {
  double weight = 1.0;     // per pixel residual (coverage is dimensionless)
  double band_px = 3.0;    // pixels within this distance of the data outline
  double huber = 0.3;      // residuals beyond this get linear weight (a bad full-contrast estimate)
};

struct CoverageStats {
  double rms = 0;
  std::size_t residuals = 0;
};

// Adds the coverage rows of one view (needs view.coverage); with jacobian == nullptr, only their cost.
CoverageStats add_coverage_residuals(const ViewData& view, const ModelView& model, const NdArray<std::int32_t>& triangles,
                                     const std::vector<MeshEdge>& edges, const SkinJacobian* jacobian, const CoverageOptions& options,
                                     NormalEquations& ne);

}  // namespace finverse::vision
