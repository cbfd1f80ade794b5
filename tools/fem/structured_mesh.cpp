// Structured Q9 strip mesh (see structured_mesh.hpp).
#include "fem/structured_mesh.hpp"

#include <cmath>
#include <memory>
#include <sstream>

#include "fem/errors.hpp"
#include "fem/plane_strain_solid.hpp"

namespace finverse::fem {

namespace {
// Grid-line parameters 0..1 for n elements whose lengths grow geometrically by `grading` (last /
// first); 2n + 1 values, the odd ones at element midpoints.
std::vector<double> graded_parameters(int n, double grading) {
  const double q = n > 1 ? std::pow(grading, 1.0 / (n - 1)) : 1.0;
  std::vector<double> edge(n + 1, 0.0);
  double len = 1.0;
  for (int k = 0; k < n; ++k, len *= q) edge[k + 1] = edge[k] + len;
  std::vector<double> s(2 * n + 1);
  for (int k = 0; k <= n; ++k) s[2 * k] = edge[k] / edge[n];
  for (int k = 0; k < n; ++k) s[2 * k + 1] = 0.5 * (s[2 * k] + s[2 * k + 2]);
  s[2 * n] = 1.0;
  return s;
}
}  // namespace

StructuredMeshQ9 mesh_strip_q9(const StripSpec& spec) {
  if (spec.nx < 1 || spec.ny < 1) {
    std::ostringstream os;
    os << "structured mesh: nx = " << spec.nx << ", ny = " << spec.ny << ", expected >= 1";
    throw InvalidInput(os.str());
  }
  if (!(spec.grading_x > 0) || !std::isfinite(spec.grading_x))
    throw InvalidInput("structured mesh: grading_x must be > 0, got " +
                       std::to_string(spec.grading_x));
  if (!(spec.y1 > spec.y0))
    throw InvalidInput("structured mesh: y1 must exceed y0");
  StructuredMeshQ9 m;
  m.nx = spec.nx;
  m.ny = spec.ny;
  const std::vector<double> s = graded_parameters(spec.nx, spec.grading_x);
  const int ni = 2 * spec.nx + 1, nj = 2 * spec.ny + 1;
  m.nodes.resize(static_cast<std::size_t>(ni) * nj);
  for (int j = 0; j < nj; ++j) {
    const double y = spec.y0 + (spec.y1 - spec.y0) * j / (nj - 1);
    const double xb = spec.x_begin ? spec.x_begin(y) : spec.x0;
    if (!(xb < spec.x_end)) {
      std::ostringstream os;
      os << "structured mesh: left edge x = " << xb << " at y = " << y
         << " is not left of x_end = " << spec.x_end;
      throw InvalidInput(os.str());
    }
    for (int i = 0; i < ni; ++i) m.nodes[m.node(i, j)] = Vec3(xb + s[i] * (spec.x_end - xb), y, 0);
  }
  for (int ey = 0; ey < spec.ny; ++ey)
    for (int ex = 0; ex < spec.nx; ++ex) {
      const int i = 2 * ex, j = 2 * ey;
      m.elements.push_back({m.node(i, j), m.node(i + 2, j), m.node(i + 2, j + 2), m.node(i, j + 2),
                            m.node(i + 1, j), m.node(i + 2, j + 1), m.node(i + 1, j + 2),
                            m.node(i, j + 1), m.node(i + 1, j + 1)});
    }
  return m;
}

std::vector<int> add_plane_strain_mesh(Model& model, const StructuredMeshQ9& mesh,
                                       const Material& material, double thickness) {
  std::vector<int> id(mesh.nodes.size());
  for (std::size_t k = 0; k < mesh.nodes.size(); ++k) id[k] = model.add_node(mesh.nodes[k]);
  for (const auto& e : mesh.elements) {
    std::array<int, 9> nodes;
    std::array<Vec3, 9> X;
    for (int k = 0; k < 9; ++k) {
      nodes[k] = id[e[k]];
      X[k] = mesh.nodes[e[k]];
    }
    model.add_element(std::make_unique<PlaneStrainSolid>(nodes, X, material, thickness));
  }
  return id;
}

}  // namespace finverse::fem
