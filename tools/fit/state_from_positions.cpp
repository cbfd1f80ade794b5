// Nodal rotations from node positions by a rigid fit of each node's 1-ring (see
// state_from_positions.hpp).
#include "fit/state_from_positions.hpp"

#include <algorithm>
#include <sstream>

#include "fem/root_motion.hpp"
#include "fit/errors.hpp"

namespace finverse::fit {

std::vector<std::vector<int>> node_one_rings(const fem::Model& model) {
  std::vector<std::vector<int>> ring(model.node_count());
  for (const auto& e : model.elements()) {
    const auto nodes = e->nodes();
    for (int a : nodes)
      for (int b : nodes)
        if (a != b) ring[a].push_back(b);
  }
  for (auto& r : ring) {
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
  }
  return ring;
}

StateFromPositions::StateFromPositions(const fem::Model& model)
    : reference_(model.reference_positions()), ring_(node_one_rings(model)) {
  for (size_t i = 0; i < ring_.size(); ++i) ring_[i].insert(ring_[i].begin(), static_cast<int>(i));
}

fem::NodalState StateFromPositions::operator()(const std::vector<fem::Vec3>& x) const {
  if (x.size() != reference_.size())
    throw InvalidInput("state from positions: " + std::to_string(x.size()) + " positions for a model of " +
                       std::to_string(reference_.size()) + " nodes");
  fem::NodalState s;
  s.position = x;
  s.rotation.resize(x.size());
  std::vector<fem::Vec3> X0, x0;
  for (size_t i = 0; i < x.size(); ++i) {
    if (!x[i].allFinite()) {
      std::ostringstream os;
      os << "state from positions: position of node " << i << " is not finite";
      throw InvalidInput(os.str());
    }
    X0.clear();
    x0.clear();
    for (int j : ring_[i]) {
      X0.push_back(reference_[j]);
      x0.push_back(x[j]);
    }
    // An isolated node (no element) has nothing to fit: fit_rigid_rotation returns I.
    s.rotation[i] = fem::fit_rigid_rotation(X0, x0);
  }
  return s;
}

fem::NodalState state_from_positions(const fem::Model& model, const std::vector<fem::Vec3>& positions) {
  return StateFromPositions(model)(positions);
}

}  // namespace finverse::fit
