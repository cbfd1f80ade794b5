// Helpers of the model factories (see model_factory.hpp).
#include "fit/model_factory.hpp"

#include <array>

namespace finverse::fit {

std::vector<int> translation_prescribed_nodes(const fem::Model& model) {
  std::vector<std::array<bool, 3>> held(model.node_count(), {false, false, false});
  for (const auto& p : model.prescribed())
    if (p.dof < 3) held[p.node][p.dof] = true;
  std::vector<int> nodes;
  for (int n = 0; n < model.node_count(); ++n)
    if (held[n][0] && held[n][1] && held[n][2]) nodes.push_back(n);
  return nodes;
}

}  // namespace finverse::fit
