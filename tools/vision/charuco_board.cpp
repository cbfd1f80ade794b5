// ChArUco boards through OpenCV's aruco module (see charuco_board.hpp).
#include "vision/charuco_board.hpp"

#include <algorithm>
#include <cctype>
#include <map>

#include <opencv2/aruco/charuco.hpp>

#include "core/error.hpp"

namespace finverse::vision {

namespace {

cv::Ptr<cv::aruco::Dictionary> dictionary(const std::string& name) {
  static const std::map<std::string, int> known = {
      {"4X4_50", cv::aruco::DICT_4X4_50},     {"4X4_100", cv::aruco::DICT_4X4_100},   {"4X4_250", cv::aruco::DICT_4X4_250},
      {"4X4_1000", cv::aruco::DICT_4X4_1000}, {"5X5_50", cv::aruco::DICT_5X5_50},     {"5X5_100", cv::aruco::DICT_5X5_100},
      {"5X5_250", cv::aruco::DICT_5X5_250},   {"5X5_1000", cv::aruco::DICT_5X5_1000}, {"6X6_50", cv::aruco::DICT_6X6_50},
      {"6X6_100", cv::aruco::DICT_6X6_100},   {"6X6_250", cv::aruco::DICT_6X6_250},   {"6X6_1000", cv::aruco::DICT_6X6_1000},
      {"7X7_50", cv::aruco::DICT_7X7_50},     {"7X7_100", cv::aruco::DICT_7X7_100},   {"7X7_250", cv::aruco::DICT_7X7_250},
      {"7X7_1000", cv::aruco::DICT_7X7_1000}, {"ARUCO_ORIGINAL", cv::aruco::DICT_ARUCO_ORIGINAL}};
  std::string key = name;
  std::transform(key.begin(), key.end(), key.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  if (key.rfind("DICT_", 0) == 0) key = key.substr(5);
  const auto it = known.find(key);
  if (it == known.end()) throw Error("--charuco: dictionary '" + name + "', expected one of OpenCV's, e.g. 4X4_50, 5X5_100, 6X6_250");
  return cv::aruco::getPredefinedDictionary(it->second);
}

cv::Ptr<cv::aruco::CharucoBoard> make_board(const CheckerboardSpec& b) {
  return cv::aruco::CharucoBoard::create(b.cols + 1, b.rows + 1, static_cast<float>(b.square_m),
                                         static_cast<float>(b.marker_fraction * b.square_m), dictionary(b.charuco));
}

}  // namespace

void check_charuco(const CheckerboardSpec& b) {
  if (!(b.marker_fraction > 0.2 && b.marker_fraction < 0.95))
    throw Error("--marker-fraction: expected the marker side / square side in (0.2, 0.95)");
  const auto d = dictionary(b.charuco);
  const int markers = ((b.cols + 1) * (b.rows + 1)) / 2;
  if (d->bytesList.rows < markers)
    throw Error("--charuco: dictionary '" + b.charuco + "' has " + std::to_string(d->bytesList.rows) + " markers, the " +
                std::to_string(b.cols + 1) + "x" + std::to_string(b.rows + 1) + " squares board needs " + std::to_string(markers));
}

void detect_charuco_corners(const cv::Mat& grey, const CheckerboardSpec& b, std::vector<cv::Point2f>& corners,
                            std::vector<int>& ids) {
  corners.clear(), ids.clear();
  const auto board = make_board(b);
  std::vector<std::vector<cv::Point2f>> marker_corners;
  std::vector<int> marker_ids;
  cv::aruco::detectMarkers(grey, board->dictionary, marker_corners, marker_ids);
  if (marker_ids.empty()) return;
  std::vector<cv::Point2f> found;
  std::vector<int> found_ids;  // OpenCV's ChArUco ids are j * cols + i: the same numbering
  cv::aruco::interpolateCornersCharuco(marker_corners, marker_ids, grey, board, found, found_ids);
  // Half the board at least: fewer corners, often along one edge, pin the pose poorly.
  if (2 * found_ids.size() < static_cast<std::size_t>(b.cols * b.rows)) return;
  std::vector<std::size_t> order(found_ids.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t c) { return found_ids[a] < found_ids[c]; });
  for (auto k : order) corners.push_back(found[k]), ids.push_back(found_ids[k]);
}

cv::Mat charuco_image(const CheckerboardSpec& b, int px_per_square) {
  cv::Mat img;
  make_board(b)->draw(cv::Size((b.cols + 1) * px_per_square, (b.rows + 1) * px_per_square), img, 0, 1);
  return img;
}

}  // namespace finverse::vision
