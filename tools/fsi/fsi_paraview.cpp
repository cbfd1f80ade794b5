// ParaView series of a coupled run; see fsi_paraview.hpp.
#include "fsi/fsi_paraview.hpp"

#include <array>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "core/vtk_output.hpp"

namespace finverse::fsi {

FsiParaView::FsiParaView(std::filesystem::path dir, long every, bool restarting)
    : dir_(std::move(dir)), every_(every), flow_(dir_ / "flow.pvd", every, restarting) {
  if (every_ < 1) throw Error("fsi paraview: expected an output every k >= 1 steps, got " + std::to_string(every));
  std::filesystem::create_directories(dir_);
}

void FsiParaView::at_frame(long f, double t, double dt, const cfd::FlowSolver& flow) {
  flow_.at_output(f, t, dt, flow);
}

void FsiParaView::write_structure(const fem::Model& model, const FsiOutput& output) const {
  // Q9 node order: corners 0-3 counter-clockwise, mid-sides 4 (0-1) .. 7 (3-0), centre 8; the four
  // sub-quads, each as two triangles.
  static constexpr std::array<std::array<int, 3>, 8> kSplit = {
      {{0, 4, 8}, {0, 8, 7}, {4, 1, 5}, {4, 5, 8}, {8, 5, 2}, {8, 2, 6}, {7, 8, 6}, {7, 6, 3}}};
  std::vector<std::int32_t> tri;
  for (const auto& e : model.elements()) {
    const auto nodes = e->nodes();
    if (nodes.size() != 9) throw Error("fsi paraview: the structure series expects Q9 elements");
    for (const auto& t : kSplit)
      for (const int k : t) tri.push_back(nodes[static_cast<std::size_t>(k)]);
  }
  const auto& reference = model.reference_state().position;
  write_structure(NdArray<std::int32_t>({tri.size() / 3, 3}, tri),
                  std::vector<Eigen::Vector3d>(reference.begin(), reference.end()), output);
}

void FsiParaView::write_structure(const NdArray<std::int32_t>& triangles, const std::vector<Eigen::Vector3d>& reference,
                                  const FsiOutput& output) const {
  const FsiOutput::Arrays a = output.saved_frames();
  const std::vector<double>& time = a.at("output_time");
  const std::size_t nv = reference.size(), block = 3 * nv;
  std::vector<double> times;
  std::vector<vtkio::SurfaceFrame> frames;
  for (std::size_t f = static_cast<std::size_t>(every_) - 1; f < time.size(); f += static_cast<std::size_t>(every_)) {
    const auto slice = [&](const char* key) {
      const std::vector<double>& v = a.at(key);
      return NdArray<double>({nv, 3}, std::vector<double>(v.begin() + static_cast<std::ptrdiff_t>(f * block),
                                                          v.begin() + static_cast<std::ptrdiff_t>((f + 1) * block)));
    };
    vtkio::SurfaceFrame frame;
    frame.points = slice("output_points");
    NdArray<double> displacement = frame.points;
    for (std::size_t i = 0; i < nv; ++i)
      for (std::size_t c = 0; c < 3; ++c) displacement.data[3 * i + c] -= reference[i](static_cast<Eigen::Index>(c));
    frame.point_data = {{"displacement", displacement},
                        {"velocity", slice("output_velocity")},
                        {"nodal_force", slice("output_nodal_force")}};
    times.push_back(time[f]);
    frames.push_back(std::move(frame));
  }
  if (frames.empty()) return;
  vtkio::write_surface_series(structure_pvd(), times, triangles, frames);
}

}  // namespace finverse::fsi
