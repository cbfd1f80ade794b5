// DeepLabCut and Anipose keypoint files (issue 35 item 7): what markerless trackers write, read
// as ray root and tip keypoints for fin-track's skeleton fit, and the fitted ray ends written back
// in the same layouts so the lab's own tools (plots, filters, Anipose's viewers) read them.
//
//   DeepLabCut, one CSV per camera: header rows "scorer", optionally "individuals", "bodyparts" and
//   "coords" (x, y, likelihood per bodypart), then one row per frame (first column: frame index or
//   image name). Pixel coordinates, top-left origin.
//   Anipose pose-3d CSV: columns <part>_x, <part>_y, <part>_z, <part>_error, <part>_ncams,
//   <part>_score per bodypart (and M_ij, center_i, fnum), one row per frame, in the unit of the
//   calibration's board (usually mm).
// Bodyparts named ray<N>_root and ray<N>_tip (N from 1, the dorsal edge ray) are the ray ends; any
// other bodypart is ignored.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "vision/camera.hpp"
#include "vision/keypoint_residual.hpp"

namespace finverse::vision {

struct KeypointTable {
  std::string scorer = "finverse";      // DeepLabCut's scorer row (written back unchanged)
  std::vector<std::string> bodyparts;
  std::vector<long> frames;             // frame index of each row
  std::vector<std::vector<cv::Vec3d>> xyz;  // [row][bodypart]; z unused in 2-D; NaN where missing
  std::vector<std::vector<double>> score;   // likelihood (DLC) or score (Anipose); NaN where missing
};

// Throws finverse::Error naming the file and row when the layout is not DeepLabCut's / Anipose's.
KeypointTable read_deeplabcut_csv(const std::filesystem::path& csv);
KeypointTable read_anipose_csv(const std::filesystem::path& csv);
void write_deeplabcut_csv(const std::filesystem::path& csv, const KeypointTable& table);
void write_anipose_csv(const std::filesystem::path& csv, const KeypointTable& table);

// "ray3_tip" -> (2, tip); nullopt for any other name (case-insensitive).
std::optional<std::pair<std::size_t, RayEnd>> ray_keypoint(const std::string& bodypart);
std::string ray_keypoint_name(std::size_t ray, RayEnd end);

// The keypoints of a record: 2-D tables (view index, table), a 3-D table (may be null, in the
// unit metres_per_unit), points below min_score left out. Throws naming `source` when a bodypart
// names a ray the template does not have (rays).
KeypointRecord keypoint_record(const std::vector<std::pair<std::size_t, const KeypointTable*>>& image_tables,
                               const KeypointTable* world_table, double metres_per_unit, double min_score, std::size_t rays);

// The ray ends of fitted points [nf,nv,3] (rows: frames): projected through `camera` (2-D, score 1)
// or in the world (3-D, in metres_per_unit, score 1), in a table with every ray's root and tip.
KeypointTable fitted_ray_ends(const std::vector<long>& frames, const NdArray<double>& points, const RayEnds& ends,
                              const Camera* camera, double metres_per_unit);

}  // namespace finverse::vision
