// Which fit terms a view carries, decided by its camera's geometry and not by its name (issue 35,
// item 1): a view that looks at the fin's face (the rest plane x-z, normal y; DESIGN.md 5.5) sees
// the rays as dark lines, so its ray features are fitted; a view that sees the fin nearly edge-on
// sees a strip a few pixels wide whose outline only the sub-pixel coverage term places (why:
// docs/studies/tracking_fit_defaults.md). The split is at 45 degrees between the optical axis and
// the fin's normal. A user may still list views by name; "auto" selects by role.
#pragma once

#include <string>
#include <vector>

#include "vision/camera.hpp"

namespace finverse::vision {

enum class ViewRole { face_on, edge_on };

// |cos| of the angle between the camera's optical axis and the fin's rest normal (world y).
double face_on_cosine(const Camera& camera);
ViewRole view_role(const Camera& camera);
const char* role_name(ViewRole role);

// Ray-feature views: {"auto"} the face-on views, {} or {"all"} every view, else the named ones.
bool fits_rays(const std::vector<std::string>& ray_views, const Camera& camera);
// Coverage-term views: {"auto"} the edge-on views, {} or {"none"} no view, else the named ones.
bool fits_coverage(const std::vector<std::string>& coverage_views, const Camera& camera);

}  // namespace finverse::vision
