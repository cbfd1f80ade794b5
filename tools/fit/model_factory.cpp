// Helpers of the model factories (see model_factory.hpp).
#include "fit/model_factory.hpp"

#include <array>

#include "fit/errors.hpp"

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

std::unique_ptr<fem::Model> nominal_model_for(const ModelFactory* factory, const TargetMotion& target,
                                              const std::string& what) {
  if (!factory) throw InvalidInput(what + ": no model factory");
  check_target(target);
  std::unique_ptr<fem::Model> model = factory->build(factory->default_parameters());
  if (target.node_count() != model->node_count())
    throw InvalidInput(target.source + ": the target has " + std::to_string(target.node_count()) +
                       " nodes, the model " + std::to_string(model->node_count()));
  return model;
}

}  // namespace finverse::fit
