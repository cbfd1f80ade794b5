// ParaView output of a coupled flow-structure run (issue 32 "Outputs"; DESIGN.md section 3,
// "Viewing"), through the existing VTK writers (core/vtk_output.hpp):
//   <dir>/structure.pvd + structure/*.vtp: the structure's surface (the fin's mid-surface
//     triangles; the flag's Q9 mesh, each element as 8 triangles) at every k-th fsi.h5 frame, with point data
//     displacement, velocity and the nodal hydrodynamic load; built from the fsi.h5 frames (FsiOutput), so a restarted
//     run's series is the uninterrupted run's;
//   <dir>/flow.pvd + flow/*.vtr: flow snapshots on the grid at the same frames (velocity, pressure,
//     vorticity, lambda_2: cfd/io/flow_snapshots.hpp), resumed after a restart.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <vector>

#include "cfd/flow/flow_solver.hpp"
#include "cfd/io/flow_snapshots.hpp"
#include "core/nd_array.hpp"
#include "fem/model.hpp"
#include "fsi/fsi_output.hpp"

namespace finverse::fsi {

class FsiParaView {
 public:
  // every >= 1; restarting: keep the flow frames an earlier run wrote up to the restart's time.
  FsiParaView(std::filesystem::path dir, long every, bool restarting);
  // At every fsi.h5 frame f (1-based: the step's count over the output interval).
  void at_frame(long f, double t, double dt, const cfd::FlowSolver& flow);
  // At the end: the structure series from the run's frames (every k-th) on the surface
  // `triangles` over the structure's nodes (reference: their undeformed positions).
  void write_structure(const NdArray<std::int32_t>& triangles, const std::vector<Eigen::Vector3d>& reference,
                       const FsiOutput& output) const;
  // The same for a plane mesh of Q9 elements (the flag), each drawn as 8 triangles.
  void write_structure(const fem::Model& model, const FsiOutput& output) const;

  [[nodiscard]] std::filesystem::path flow_pvd() const { return dir_ / "flow.pvd"; }
  [[nodiscard]] std::filesystem::path structure_pvd() const { return dir_ / "structure.pvd"; }

 private:
  std::filesystem::path dir_;
  long every_;
  cfd::io::FlowSnapshots flow_;
};

}  // namespace finverse::fsi
