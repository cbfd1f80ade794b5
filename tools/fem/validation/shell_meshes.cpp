// Shell validation meshes (see shell_meshes.hpp).
#include "fem/validation/shell_meshes.hpp"

#include <cmath>
#include <memory>
#include <numbers>

#include "fem/corotational_shell.hpp"
#include "fem/errors.hpp"

namespace finverse::fem::validation {

namespace {
// Splits every cell of an (nx+1) x (ny+1) grid into two triangles, alternating the diagonal.
void triangulate_grid(TriangleMesh& m) {
  for (int j = 0; j < m.ny; ++j)
    for (int i = 0; i < m.nx; ++i) {
      const int a = m.node(i, j), b = m.node(i + 1, j), c = m.node(i + 1, j + 1),
                d = m.node(i, j + 1);
      if ((i + j) % 2 == 0) {
        m.triangles.push_back({a, b, c});
        m.triangles.push_back({a, c, d});
      } else {
        m.triangles.push_back({a, b, d});
        m.triangles.push_back({b, c, d});
      }
    }
}

void check_counts(int nx, int ny, const char* what) {
  if (nx < 1 || ny < 1)
    throw InvalidInput(std::string(what) + ": element counts must be >= 1");
}
}  // namespace

TriangleMesh rectangle_mesh(double length, double width, int nx, int ny) {
  check_counts(nx, ny, "rectangle mesh");
  TriangleMesh m;
  m.nx = nx, m.ny = ny;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.nodes.emplace_back(length * i / nx, width * j / ny, 0.0);
  triangulate_grid(m);
  return m;
}

TriangleMesh quarter_hemisphere_mesh(double R, double hole_deg, int n_meridian,
                                     int n_circumference) {
  check_counts(n_meridian, n_circumference, "hemisphere mesh");
  TriangleMesh m;
  m.nx = n_meridian, m.ny = n_circumference;
  const double deg = std::numbers::pi / 180.0;
  // Grid "x" runs from the equator towards the hole, grid "y" circumferentially.
  for (int j = 0; j <= n_circumference; ++j)
    for (int i = 0; i <= n_meridian; ++i) {
      const double latitude = (90.0 - hole_deg) * deg * i / n_meridian;  // 0 at the equator
      const double azimuth = 0.5 * std::numbers::pi * j / n_circumference;
      m.nodes.emplace_back(R * std::cos(latitude) * std::cos(azimuth),
                           R * std::cos(latitude) * std::sin(azimuth), R * std::sin(latitude));
    }
  triangulate_grid(m);
  return m;
}

std::vector<int> add_shell_mesh(Model& model, const TriangleMesh& mesh, const Material& material,
                                double thickness) {
  std::vector<int> id;
  id.reserve(mesh.nodes.size());
  for (const Vec3& X : mesh.nodes) id.push_back(model.add_node(X));
  for (const auto& t : mesh.triangles) {
    const auto& X = model.reference_positions();
    model.add_element(std::make_unique<CorotationalShell>(id[t[0]], id[t[1]], id[t[2]], X[id[t[0]]], X[id[t[1]]],
                                                          X[id[t[2]]], material, thickness),
                      -1, material.youngs_modulus);  // no region, but a known modulus (stiffness_field.hpp)
  }
  return id;
}

}  // namespace finverse::fem::validation
