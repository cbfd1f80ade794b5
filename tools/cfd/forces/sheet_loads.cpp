// Pressure jump per element of a zero-thickness immersed surface (see sheet_loads.hpp).
#include "cfd/forces/sheet_loads.hpp"

#include "core/error.hpp"

namespace finverse::cfd {

std::vector<double> sheet_pressure_jump(const SheetMarkers& markers, const std::vector<Vec3>& x,
                                        const SheetLoads& loads) {
  if (loads.marker.size() != markers.size())
    throw Error("sheet pressure jump: " + std::to_string(loads.marker.size()) + " marker forces for " +
                std::to_string(markers.size()) + " markers");
  if (loads.nodal.size() != markers.topology().nodes)
    throw Error("sheet pressure jump: " + std::to_string(loads.nodal.size()) + " nodal forces for " +
                std::to_string(markers.topology().nodes) + " nodes");
  // Traction at every node (its force over its lumped area), then per element the mean of its
  // nodes' tractions along the element's normal: defined on every element, also on one that holds
  // no marker.
  const std::vector<double> area = markers.node_measure(x);
  std::vector<double> measure;
  std::vector<Vec3> normal;
  markers.element_geometry(x, measure, normal);
  const auto& el = markers.topology().elements;
  const int nq = markers.topology().dim;
  std::vector<double> jump(measure.size(), 0.0);
  for (std::size_t e = 0; e < jump.size(); ++e) {
    double s = 0;
    for (int q = 0; q < nq; ++q) {
      const auto k = static_cast<std::size_t>(el[e][q]);
      if (area[k] > 0) s += dot(loads.nodal[k], normal[e]) / area[k];
    }
    jump[e] = s / nq;
  }
  return jump;
}

}  // namespace finverse::cfd
