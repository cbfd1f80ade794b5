// Flow-field snapshot frames and series; see flow_snapshots.hpp.
#include "cfd/io/flow_snapshots.hpp"

#include <utility>
#include <vector>

namespace finverse::cfd::io {

vtkio::GridFrame flow_frame(const FlowSolver& solver) {
  vtkio::GridFrame frame;
  const std::size_t n = solver.grid().cells();
  for (StateArray& a : solver.cell_output()) {
    const std::size_t k = a.values.size() / n;
    frame.cell_data.push_back(
        {a.name,
         NdArray<double>(k == 1 ? std::vector<std::size_t>{n} : std::vector<std::size_t>{n, k}, std::move(a.values))});
  }
  return frame;
}

FlowSnapshots::FlowSnapshots(std::filesystem::path pvd, long every, bool restarting)
    : pvd_(std::move(pvd)), every_(every), restarting_(restarting) {}

void FlowSnapshots::at_output(long output, double t, double dt, const FlowSolver& solver) {
  if (every_ <= 0 || output % every_ != 0) return;
  if (!series_) {
    const auto& g = solver.grid();
    series_ = std::make_unique<vtkio::GridSeries>(pvd_, g.axis(0).faces(), g.axis(1).faces(), g.axis(2).faces());
    // The frames after the restart's time belong to the interrupted run and are rewritten.
    if (restarting_) series_->resume(t - 1e-9 * dt);
  }
  series_->add(t, flow_frame(solver));
}

}  // namespace finverse::cfd::io
