// Plane samples of the flow's velocity (flow_planes.hpp).
#include "fsi/validation/flow_planes.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "core/printf_format.hpp"

namespace finverse::fsi::validation {

FlowPlane sample_flow_plane(const cfd::FlowSolver& flow, double z) {
  const cfd::StretchedGrid& g = flow.grid();
  const cfd::Axis& az = g.axis(2);
  if (g.dim() != 3 || !(z >= az.centre(0) && z <= az.centre(az.size() - 1)))
    throw Error("flow plane: z = " + printf_format("%.4g", z) + " m is outside the grid's cell centres");
  int k = 0;
  while (k + 2 < az.size() && az.centre(k + 1) <= z) ++k;
  const double t = (z - az.centre(k)) / (az.centre(k + 1) - az.centre(k));
  FlowPlane p;
  p.z = z;
  for (int i = 0; i < g.nx(); ++i) p.x.push_back(g.xc(i));
  for (int j = 0; j < g.ny(); ++j) p.y.push_back(g.yc(j));
  const cfd::GhostCellSet* walls = flow.immersed();
  const auto fluid = [&](int i, int j, int kk) { return !walls || walls->kind(i, j, kk) == cfd::CellKind::Fluid; };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double>* out[3] = {&p.u, &p.v, &p.w};
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) {
      const bool ok = fluid(i, j, k) && fluid(i, j, k + 1);
      for (int c = 0; c < 3; ++c)
        out[c]->push_back(ok ? (1 - t) * flow.u(c)(i, j, k) + t * flow.u(c)(i, j, k + 1) : nan);
    }
  return p;
}

void write_flow_planes(const std::filesystem::path& path, const std::vector<FlowPlane>& planes) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  auto file = h5::File::create(path);
  file.set_attr(".", "schema", std::string("finverse/flow-planes"));
  file.set_attr(".", "schema_version", std::int64_t{1});
  for (const FlowPlane& p : planes) {
    auto grp = file.create_group("z_" + printf_format("%g", p.z * 1e3) + "mm");
    grp.set_attr(".", "z_m", p.z);
    grp.write("x", NdArray<double>({p.x.size()}, p.x), h5::WriteOptions{"m", false});
    grp.write("y", NdArray<double>({p.y.size()}, p.y), h5::WriteOptions{"m", false});
    const std::vector<std::size_t> shape{p.y.size(), p.x.size()};
    grp.write("u", NdArray<double>(shape, p.u), h5::WriteOptions{"m/s", true});
    grp.write("v", NdArray<double>(shape, p.v), h5::WriteOptions{"m/s", true});
    grp.write("w", NdArray<double>(shape, p.w), h5::WriteOptions{"m/s", true});
  }
  file.commit();
}

}  // namespace finverse::fsi::validation
