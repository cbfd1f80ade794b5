// The structural model of the fin as fin-mesh writes it to mesh.h5 (seed paper section 4.1,
// Fig. 9: shell membrane + 20 tapered beams; DESIGN.md section 4): shell triangles with the
// membrane thickness, beam elements on the ray edges with ray number, arc-length fraction and
// section at both ends, the root node set, and the closed immersed-boundary surface.
#pragma once

#include "core/stage_files.hpp"
#include "mesh/fin_template.hpp"
#include "mesh/ibm_surface.hpp"
#include "mesh/planform_mesher.hpp"

namespace finverse::mesh {

// Nodes whose motion is prescribed: within root_band (metres, >= 0) of the root segment. The
// paper prescribes the root region within 10% chord (section 4.4); root_band = 0 keeps the
// nodes on the root segment itself.
std::vector<int> root_nodes(const FinTemplate& t, const PlanformMesh& m, double root_band);

// Mid-surface node positions in 3-D at rest: (x, 0, z).
NdArray<double> rest_points(const PlanformMesh& m);

stage::Mesh assemble_mesh(const FinTemplate& t, const PlanformMesh& m, const IbmSurface& ibm, double root_band);

}  // namespace finverse::mesh
