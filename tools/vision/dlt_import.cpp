// DLT coefficients <-> pinhole cameras (see dlt_import.hpp for the model and the conventions).
#include "vision/dlt_import.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include <opencv2/calib3d.hpp>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace finverse::vision {

namespace {

// Pixel frame change between DLTdv (v up from the bottom edge) and OpenCV; its own inverse.
cv::Matx33d pixel_flip(DltOrigin origin, int height) {
  if (origin == DltOrigin::top_left) return cv::Matx33d::eye();
  return {1, 0, 0, 0, -1, static_cast<double>(height), 0, 0, 1};
}

}  // namespace

Camera camera_from_dlt(const DltCoefficients& L, const std::string& name, int width, int height, DltOrigin origin,
                       double metres_per_unit, const std::string& where) {
  if (width <= 0 || height <= 0) throw Error(where + ": camera " + name + ": image size must be > 0 (--image-size)");
  if (!(metres_per_unit > 0)) throw Error(where + ": metres per DLT unit must be > 0");
  cv::Matx34d P(L[0], L[1], L[2], L[3], L[4], L[5], L[6], L[7], L[8], L[9], L[10], 1.0);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) P(r, c) /= metres_per_unit;
  P = pixel_flip(origin, height) * P;
  cv::Matx33d A(P(0, 0), P(0, 1), P(0, 2), P(1, 0), P(1, 1), P(1, 2), P(2, 0), P(2, 1), P(2, 2));
  cv::Vec3d b(P(0, 3), P(1, 3), P(2, 3));
  const double row3 = std::hypot(A(2, 0), A(2, 1), A(2, 2));
  const double det = cv::determinant(A);
  if (!(row3 > 0) || !std::isfinite(det) || std::abs(det) < 1e-12 * std::pow(cv::norm(A), 3))
    throw Error(where + ": camera " + name + ": the DLT matrix is singular, expected 11 coefficients of a real camera");
  // Scale so the third row of K R is a unit vector and det(K R) > 0 (K has a positive diagonal).
  const double s = (det > 0 ? 1.0 : -1.0) / row3;
  A *= s;
  b *= s;
  cv::Matx33d K, R;
  cv::RQDecomp3x3(A, K, R);
  const cv::Matx33d D(K(0, 0) < 0 ? -1 : 1, 0, 0, 0, K(1, 1) < 0 ? -1 : 1, 0, 0, 0, K(2, 2) < 0 ? -1 : 1);
  K = K * D;
  R = D * R;
  Camera c;
  c.name = name;
  c.width = width;
  c.height = height;
  c.K = K * (1.0 / K(2, 2));
  c.tvec = K.inv() * b;
  cv::Rodrigues(R, c.rvec);
  if (cv::determinant(R) < 0)
    throw Error(where + ": camera " + name + ": the DLT matrix is mirrored (check the image origin, --dlt-origin)");
  return c;
}

DltCoefficients dlt_from_camera(const Camera& cam, DltOrigin origin, double metres_per_unit) {
  const cv::Matx33d R = cam.rotation();
  cv::Matx34d P;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) P(r, c) = R(r, c);
    P(r, 3) = cam.tvec[r];
  }
  P = pixel_flip(origin, cam.height) * cam.K * P;
  if (std::abs(P(2, 3)) < 1e-12) throw Error("camera " + cam.name + ": the world origin lies in its focal plane; a DLT cannot represent it");
  DltCoefficients L{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) {
      if (r == 2 && c == 3) continue;
      L[static_cast<std::size_t>(4 * r + c)] = P(r, c) * (c < 3 ? metres_per_unit : 1.0) / P(2, 3);
    }
  return L;
}

std::vector<DltCoefficients> read_dlt_file(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  if (!in) throw Error(csv.string() + ": cannot open the DLT coefficient file");
  std::vector<std::vector<double>> rows;
  std::string line;
  while (std::getline(in, line)) {
    for (char& ch : line)
      if (ch == ',' || ch == ';' || ch == '\t' || ch == '\r') ch = ' ';
    std::istringstream ls(line);
    std::vector<double> row;
    std::string tok;
    while (ls >> tok) {
      try {
        std::size_t used = 0;
        row.push_back(std::stod(tok, &used));
        if (used != tok.size()) throw std::invalid_argument(tok);
      } catch (const std::exception&) {
        throw Error(csv.string() + ": row " + std::to_string(rows.size() + 1) + ": '" + tok +
                    "' is not a number; expected 11 rows of DLT coefficients, one column per camera");
      }
    }
    if (!row.empty()) rows.push_back(row);
  }
  if (rows.size() != 11)
    throw Error(csv.string() + ": " + std::to_string(rows.size()) + " rows, expected 11 rows of DLT coefficients (one column per camera)");
  std::vector<DltCoefficients> cams(rows[0].size());
  for (std::size_t r = 0; r < 11; ++r) {
    if (rows[r].size() != cams.size())
      throw Error(csv.string() + ": row " + std::to_string(r + 1) + " has " + std::to_string(rows[r].size()) +
                  " columns, expected " + std::to_string(cams.size()) + " (one per camera)");
    for (std::size_t c = 0; c < cams.size(); ++c) cams[c][r] = rows[r][c];
  }
  return cams;
}

void write_dlt_file(const std::filesystem::path& csv, const std::vector<DltCoefficients>& cameras) {
  std::ostringstream out;
  out.precision(17);
  for (std::size_t r = 0; r < 11; ++r) {
    for (std::size_t c = 0; c < cameras.size(); ++c) out << (c ? "," : "") << cameras[c][r];
    out << "\n";
  }
  write_text_atomic(csv, out.str());
}

}  // namespace finverse::vision
