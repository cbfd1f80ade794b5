// Pinhole cameras with OpenCV's distortion model and cameras.yml I/O (DESIGN.md section 3,
// "Cameras"; seed paper section 4.1, three synchronized views).
#include "vision/camera.hpp"

#include <cmath>
#include <numbers>
#include <random>

#include <opencv2/calib3d.hpp>

#include "core/atomic_file.hpp"
#include "core/error.hpp"

namespace finverse::vision {

cv::Matx33d Camera::rotation() const {
  cv::Matx33d R;
  cv::Rodrigues(rvec, R);
  return R;
}

cv::Vec3d Camera::center() const { return -(rotation().t() * tvec); }

cv::Point2d Camera::project(const cv::Vec3d& world, double* depth) const {
  const cv::Vec3d Xc = rotation() * world + tvec;
  if (depth) *depth = Xc[2];
  const double x = Xc[0] / Xc[2], y = Xc[1] / Xc[2];
  const double k1 = dist[0], k2 = dist[1], p1 = dist[2], p2 = dist[3], k3 = dist[4];
  const double r2 = x * x + y * y;
  const double radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3));
  const double xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x);
  const double yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y;
  return {K(0, 0) * xd + K(0, 1) * yd + K(0, 2), K(1, 1) * yd + K(1, 2)};
}

Camera look_at(const std::string& name, int width, int height, double focal_px, const cv::Vec3d& eye,
               const cv::Vec3d& target, const cv::Vec3d& up) {
  const cv::Vec3d z = cv::normalize(target - eye);
  const cv::Vec3d up_perp = up - up.dot(z) * z;
  if (cv::norm(up_perp) < 1e-9) throw Error("camera " + name + ": 'up' is parallel to the viewing direction");
  const cv::Vec3d y = -cv::normalize(up_perp);  // image y points down
  const cv::Vec3d x = y.cross(z);
  const cv::Matx33d R(x[0], x[1], x[2], y[0], y[1], y[2], z[0], z[1], z[2]);
  Camera c;
  c.name = name;
  c.width = width;
  c.height = height;
  c.K = cv::Matx33d(focal_px, 0, 0.5 * (width - 1), 0, focal_px, 0.5 * (height - 1), 0, 0, 1);
  cv::Rodrigues(R, c.rvec);
  c.tvec = -(R * eye);
  return c;
}

std::vector<Camera> default_rig(const std::vector<std::string>& views, double chord, int width, int height,
                                double half_field, double centre_x) {
  if (width < 16 || height < 16) throw Error("--width/--height: images must be at least 16 x 16 pixels");
  if (!(half_field > 0 && half_field < 6)) throw Error("--field-chords: expected a half field of view in (0, 6) chords");
  const double distance = 12 * chord;
  const double half_view = half_field * chord;  // 1.1: fin, heave and trailing-edge excursion fit inside
  const double focal = 0.5 * std::min(width, height) * distance / half_view;
  const cv::Vec3d centre(centre_x * chord, 0, 0);
  std::vector<Camera> rig;
  for (const auto& v : views) {
    // Slightly oblique, like cameras around a flow tank, so no view is exactly edge-on.
    Camera c;
    if (v == "side")
      c = look_at(v, width, height, focal, centre + distance * cv::normalize(cv::Vec3d(0.05, -1, 0.04)), centre, {0, 0, 1});
    else if (v == "back")
      c = look_at(v, width, height, focal, centre + distance * cv::normalize(cv::Vec3d(1, 0.04, 0.05)), centre, {0, 0, 1});
    else if (v == "ventral")
      c = look_at(v, width, height, focal, centre + distance * cv::normalize(cv::Vec3d(0.05, 0.04, -1)), centre, {1, 0, 0});
    else if (v == "dorsal")  // from above, as the 2-D mode's lab clips are filmed
      c = look_at(v, width, height, focal, centre + distance * cv::normalize(cv::Vec3d(0.05, 0.04, 1)), centre,
                  {1, 0, 0});
    else
      throw Error("--views: unknown view '" + v + "', expected side, back, ventral or dorsal");
    c.dist = {-0.08, 0.02, 0.0005, -0.0003, 0};
    c.K(0, 2) += 3.2;  // principal point off-centre, as in a real calibration
    c.K(1, 2) -= 2.1;
    rig.push_back(c);
  }
  return rig;
}

void perturb_principal_points(std::vector<Camera>& cameras, double px, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  for (auto& c : cameras) {
    const double a = 2 * std::numbers::pi * (static_cast<double>(rng() >> 11) * 0x1.0p-53);
    c.K(0, 2) += px * std::cos(a);
    c.K(1, 2) += px * std::sin(a);
  }
}

void write_cameras(const std::filesystem::path& yml, const std::vector<Camera>& cameras) {
  cv::FileStorage fs(".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  fs.writeComment("finverse cameras: OpenCV conventions, rvec/tvec map world (m) to camera; image y down");
  fs << "views" << "[";
  for (const auto& c : cameras) fs << c.name;
  fs << "]";
  for (const auto& c : cameras) {
    fs << c.name << "{";
    fs << "image_width" << c.width << "image_height" << c.height;
    fs << "camera_matrix" << cv::Mat(c.K);
    fs << "distortion_coefficients" << cv::Mat(c.dist).reshape(1, 1);
    fs << "rvec" << cv::Mat(c.rvec) << "tvec" << cv::Mat(c.tvec);
    fs << "}";
  }
  write_text_atomic(yml, fs.releaseAndGetString());
}

namespace {
// What the projection needs of a camera read from a file: finite numbers, positive focal lengths,
// a pinhole matrix [fx s cx; 0 fy cy; 0 0 1] and a principal point near the image (a NaN focal
// length once crashed fin-track).
void check_camera(const Camera& c, const std::string& where) {
  const std::string cam = where + ": camera '" + c.name + "': ";
  if (c.width > 65536 || c.height > 65536) throw Error(cam + "image_width and image_height must be at most 65536 px");
  for (int i = 0; i < 9; ++i)
    if (!std::isfinite(c.K(i / 3, i % 3))) throw Error(cam + "camera_matrix holds a value that is not a finite number");
  for (int i = 0; i < 5; ++i)
    if (!std::isfinite(c.dist[i]))
      throw Error(cam + "distortion_coefficients hold a value that is not a finite number");
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(c.rvec[i]) || !std::isfinite(c.tvec[i]))
      throw Error(cam + "rvec and tvec must hold finite numbers");
  if (!(c.K(0, 0) > 0 && c.K(1, 1) > 0)) throw Error(cam + "camera_matrix: focal lengths fx, fy must be > 0 px");
  if (c.K(1, 0) != 0 || c.K(2, 0) != 0 || c.K(2, 1) != 0 || std::abs(c.K(2, 2) - 1) > 1e-9)
    throw Error(cam + "camera_matrix: expected the pinhole form [fx s cx; 0 fy cy; 0 0 1]");
  const double cx = c.K(0, 2), cy = c.K(1, 2);
  if (cx < -c.width || cx > 2.0 * c.width || cy < -c.height || cy > 2.0 * c.height)
    throw Error(cam + "camera_matrix: principal point (" + std::to_string(cx) + ", " + std::to_string(cy) +
                ") px is more than an image away from the " + std::to_string(c.width) + " x " +
                std::to_string(c.height) + " image");
}
}  // namespace

std::vector<Camera> read_cameras(const std::filesystem::path& yml) {
  const std::string where = yml.string();
  cv::FileStorage fs;
  try {
    if (!fs.open(where, cv::FileStorage::READ)) throw Error(where + ": cannot open camera file");
  } catch (const cv::Exception& e) {
    throw Error(where + ": not an OpenCV FileStorage file: " + e.msg);
  }
  const auto views = fs["views"];
  if (!views.isSeq() || views.empty()) throw Error(where + ": 'views' must be a non-empty list of camera names");
  std::vector<Camera> out;
  for (const auto& v : views) {
    Camera c;
    c.name = static_cast<std::string>(v);
    const auto node = fs[c.name];
    if (!node.isMap()) throw Error(where + ": camera '" + c.name + "' listed in views but not defined");
    cv::Mat K, d, r, t;
    node["image_width"] >> c.width;
    node["image_height"] >> c.height;
    node["camera_matrix"] >> K;
    node["distortion_coefficients"] >> d;
    node["rvec"] >> r;
    node["tvec"] >> t;
    if (c.width <= 0 || c.height <= 0 || K.total() != 9 || d.total() != 5 || r.total() != 3 || t.total() != 3)
      throw Error(where + ": camera '" + c.name +
                  "': expected image_width, image_height, camera_matrix 3x3, distortion_coefficients 1x5, rvec 3x1, tvec 3x1");
    K.convertTo(K, CV_64F);
    d.convertTo(d, CV_64F);
    r.convertTo(r, CV_64F);
    t.convertTo(t, CV_64F);
    for (int i = 0; i < 9; ++i) c.K(i / 3, i % 3) = K.at<double>(i);
    for (int i = 0; i < 5; ++i) c.dist[i] = d.at<double>(i);
    for (int i = 0; i < 3; ++i) c.rvec[i] = r.at<double>(i), c.tvec[i] = t.at<double>(i);
    check_camera(c, where);
    out.push_back(c);
  }
  return out;
}

}  // namespace finverse::vision
