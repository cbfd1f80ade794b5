// Flow-field snapshots for ParaView (DESIGN.md section 3, "Viewing"): the solver's cell fields
// (velocity, pressure, vorticity, lambda_2; FlowSolver::cell_output) as one frame of a VTK image
// series, and a writer that adds a frame every N-th output time of a run and, after a restart,
// keeps the frames the interrupted run wrote before it.
#pragma once

#include <filesystem>
#include <memory>

#include "cfd/flow/flow_solver.hpp"
#include "core/vtk_output.hpp"

namespace finverse::cfd::io {

// The solver's cell fields at its current time level as one frame.
vtkio::GridFrame flow_frame(const FlowSolver& solver);

class FlowSnapshots {
 public:
  // Every `every`-th output into `pvd`; `restarting`: resume the collection already there.
  FlowSnapshots(std::filesystem::path pvd, long every, bool restarting);
  // Called at every output time (FinCheckpointing::at_output); `output` counts from 1.
  void at_output(long output, double t, double dt, const FlowSolver& solver);
  std::size_t size() const { return series_ ? series_->size() : 0; }
  const std::filesystem::path& pvd() const { return pvd_; }

 private:
  std::filesystem::path pvd_;
  long every_;
  bool restarting_;
  std::unique_ptr<vtkio::GridSeries> series_;
};

}  // namespace finverse::cfd::io
