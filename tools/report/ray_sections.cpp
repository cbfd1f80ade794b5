// Root second moment of area per ray (see ray_sections.hpp; paper Fig. 11).
#include "report/ray_sections.hpp"

#include <limits>

#include "core/error.hpp"

namespace finverse::report {

std::map<int, double> root_second_moments(const stage::Mesh& mesh) {
  const std::size_t ne = mesh.beam_ray.size();
  if (ne == 0 || mesh.beam_s.size() != 2 * ne || mesh.beam_thickness.size() != 2 * ne || mesh.beam_width.size() != 2 * ne)
    throw Error("ray sections: the mesh has no beam elements with s, thickness and width per end");
  std::map<int, double> s_min, moment;
  for (std::size_t e = 0; e < ne; ++e)
    for (std::size_t end = 0; end < 2; ++end) {
      const int ray = mesh.beam_ray(e);
      const double s = mesh.beam_s(e, end);
      auto it = s_min.find(ray);
      if (it == s_min.end() || s < it->second) {
        s_min[ray] = s;
        const double t = mesh.beam_thickness(e, end), w = mesh.beam_width(e, end);
        moment[ray] = w * t * t * t / 12.0;
      }
    }
  return moment;
}

}  // namespace finverse::report
