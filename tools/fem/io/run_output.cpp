// motion.h5-schema response file and ParaView series of a structural run (see run_output.hpp).
#include "fem/io/run_output.hpp"

#include "core/vtk_output.hpp"

namespace finverse::fem::io {

stage::Motion to_motion(const std::vector<RunFrame>& frames, std::optional<double> period) {
  stage::Motion m;
  const size_t nf = frames.size(), nv = nf ? frames[0].state.position.size() : 0;
  m.time = NdArray<double>({nf});
  m.points = NdArray<double>({nf, nv, 3});
  const bool velocity = nf && frames[0].velocity.size() > 0;
  if (velocity) m.velocity = NdArray<double>({nf, nv, 3});
  for (size_t k = 0; k < nf; ++k) {
    m.time.data[k] = frames[k].time;
    for (size_t i = 0; i < nv; ++i)
      for (int d = 0; d < 3; ++d) {
        m.points(k, i, d) = frames[k].state.position[i](d);
        if (velocity) m.velocity(k, i, d) = frames[k].velocity(kDofsPerNode * i + d);
      }
  }
  m.period = period;
  return m;
}

void write_run_output(const std::filesystem::path& h5, const std::optional<std::filesystem::path>& pvd,
                      const stage::Mesh& mesh, const std::vector<RunFrame>& frames,
                      std::optional<double> period, const Provenance& provenance,
                      std::optional<std::string> effects) {
  stage::Motion m = to_motion(frames, period);
  m.effects = std::move(effects);
  stage::write(h5, m, provenance);
  if (!pvd) return;
  std::vector<double> times;
  std::vector<vtkio::SurfaceFrame> vf;
  const size_t nv = mesh.points.dim(0);
  for (const auto& f : frames) {
    times.push_back(f.time);
    vtkio::SurfaceFrame s;
    s.points = NdArray<double>({nv, 3});
    NdArray<double> u({nv, 3});
    for (size_t i = 0; i < nv; ++i)
      for (int d = 0; d < 3; ++d) {
        s.points(i, d) = f.state.position[i](d);
        u(i, d) = f.state.position[i](d) - mesh.points(i, d);
      }
    s.point_data.push_back({"displacement", std::move(u)});
    NdArray<double> region({mesh.shell_region.data.size()});
    for (size_t e = 0; e < region.data.size(); ++e) region.data[e] = mesh.shell_region.data[e];
    s.cell_data.push_back({"region", std::move(region)});
    vf.push_back(std::move(s));
  }
  vtkio::write_surface_series(*pvd, times, mesh.triangles, vf);
}

}  // namespace finverse::fem::io
