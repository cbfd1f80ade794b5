// ChArUco boards (issue 35 item 2; the board Anipose calibrates with): a checkerboard whose white
// squares hold ArUco markers (OpenCV aruco), so every corner is identified by the markers around
// it and the board's orientation is never ambiguous. The board of a CheckerboardSpec with a
// dictionary has (cols + 1) x (rows + 1) squares; its inner corners are numbered as
// CheckerboardSpec::corners() (OpenCV's ChArUco corner ids, shifted by one square), and the square
// before corner (0, 0) is black, as on the plain board.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "vision/calibration.hpp"

namespace finverse::vision {

// Throws finverse::Error naming the dictionary when it is unknown ("4X4_50", "DICT_5X5_100", ...)
// or has fewer markers than the board's white squares.
void check_charuco(const CheckerboardSpec& board);

// The inner corners of the ChArUco board found in `grey` and their indices in
// CheckerboardSpec::corners(), ascending; none unless at least half of them were found.
void detect_charuco_corners(const cv::Mat& grey, const CheckerboardSpec& board, std::vector<cv::Point2f>& corners,
                            std::vector<int>& ids);

// The printed board, `px_per_square` pixels per square (8-bit, black 0, white 255, no margin).
cv::Mat charuco_image(const CheckerboardSpec& board, int px_per_square);

}  // namespace finverse::vision
