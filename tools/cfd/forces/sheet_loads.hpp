// Loads of a zero-thickness immersed surface on its elements (DESIGN.md section 5.1, sheet_forcing.hpp):
// the markers' forces are already the jump across the sheet (both sides act on the same marker).
// Their nodal sums over the nodes' lumped areas are tractions; the mean of an element's nodal
// tractions along its right-hand normal n is the element's pressure jump in the convention of
// loads.h5,
//     pressure_jump = p_back - p_front  (net pressure force = pressure_jump * area * n),
// to the (small) normal part of the shear, which a zero-thickness surface cannot tell apart.
#pragma once

#include <vector>

#include "cfd/immersed/sheet_markers.hpp"

namespace finverse::cfd {

// Per element of the sheet, at node positions x, from the loads of the same instant.
std::vector<double> sheet_pressure_jump(const SheetMarkers& markers, const std::vector<Vec3>& x,
                                        const SheetLoads& loads);

}  // namespace finverse::cfd
