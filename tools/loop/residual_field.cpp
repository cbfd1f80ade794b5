// Residual = prediction - reconstruction on a common mesh and time base (residual_field.hpp).
#include "loop/residual_field.hpp"

#include <algorithm>
#include <cmath>

#include "loop/errors.hpp"

namespace finverse::loop {

ResidualField residual_field(const SampledMotion& prediction, const SampledMotion& reconstruction, int mesh_nodes,
                             double time_tolerance) {
  const std::string both = prediction.source + " and " + reconstruction.source;
  const int nf = static_cast<int>(prediction.times.size());
  if (nf == 0 || reconstruction.times.empty())
    throw InvalidInput(both + ": /time: expected at least one frame in each");
  if (static_cast<int>(prediction.positions.size()) != nf ||
      reconstruction.positions.size() != reconstruction.times.size())
    throw InvalidInput(both + ": /points: expected one frame of positions per /time entry");
  if (prediction.node_count() != mesh_nodes || reconstruction.node_count() != mesh_nodes)
    throw InvalidInput(both + ": /points: expected the mesh's " + std::to_string(mesh_nodes) + " nodes, got " +
                       std::to_string(prediction.node_count()) + " and " +
                       std::to_string(reconstruction.node_count()) + " (different meshes)");
  if (static_cast<int>(reconstruction.times.size()) != nf)
    throw InvalidInput(both + ": /time: expected the same time base, got " + std::to_string(nf) + " and " +
                       std::to_string(reconstruction.times.size()) + " frames");
  const double spacing = nf > 1 ? std::abs(prediction.times[1] - prediction.times[0]) : 1.0;
  for (int k = 0; k < nf; ++k) {
    if (std::abs(prediction.times[k] - reconstruction.times[k]) > time_tolerance * spacing)
      throw InvalidInput(both + ": /time: expected the same time base, frame " + std::to_string(k) + " is at " +
                         std::to_string(prediction.times[k]) + " s and " + std::to_string(reconstruction.times[k]) +
                         " s");
  }
  ResidualField field;
  field.times = reconstruction.times;
  field.values.resize(3 * mesh_nodes, nf);
  for (int k = 0; k < nf; ++k) {
    if (prediction.positions[k].size() != 3 * mesh_nodes || reconstruction.positions[k].size() != 3 * mesh_nodes)
      throw InvalidInput(both + ": /points: frame " + std::to_string(k) + " has a different node count");
    field.values.col(k) = prediction.positions[k] - reconstruction.positions[k];
  }
  if (!field.values.allFinite()) throw InvalidInput(both + ": /points: expected finite positions");
  return field;
}

}  // namespace finverse::loop
