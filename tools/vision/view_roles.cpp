// A view's role in the fit from its camera's geometry (see view_roles.hpp).
#include "vision/view_roles.hpp"

#include <algorithm>
#include <cmath>

namespace finverse::vision {
namespace {

bool listed(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}
bool is(const std::vector<std::string>& names, const char* word) { return names.size() == 1 && names[0] == word; }

}  // namespace

double face_on_cosine(const Camera& camera) {
  // The optical axis in world coordinates is the third row of world -> camera rotation.
  const auto R = camera.rotation();
  return std::abs(R(2, 1)) / std::sqrt(R(2, 0) * R(2, 0) + R(2, 1) * R(2, 1) + R(2, 2) * R(2, 2));
}

ViewRole view_role(const Camera& camera) {
  return face_on_cosine(camera) >= std::sqrt(0.5) ? ViewRole::face_on : ViewRole::edge_on;
}

const char* role_name(ViewRole role) { return role == ViewRole::face_on ? "face-on" : "edge-on"; }

bool fits_rays(const std::vector<std::string>& ray_views, const Camera& camera) {
  if (ray_views.empty() || is(ray_views, "all")) return true;
  if (is(ray_views, "auto")) return view_role(camera) == ViewRole::face_on;
  return listed(ray_views, camera.name);
}

bool fits_coverage(const std::vector<std::string>& coverage_views, const Camera& camera) {
  if (coverage_views.empty() || is(coverage_views, "none")) return false;
  if (is(coverage_views, "auto")) return view_role(camera) == ViewRole::edge_on;
  return listed(coverage_views, camera.name);
}

}  // namespace finverse::vision
