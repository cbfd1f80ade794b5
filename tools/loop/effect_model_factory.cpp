// The fitted fin with effects on, as a model factory (effect_model_factory.hpp).
#include "loop/effect_model_factory.hpp"

#include "fem/io/fin_layout.hpp"

namespace finverse::loop {

std::vector<fem::EffectParameter> EffectModelFactory::effect_parameters(const nlohmann::json& spec) {
  auto e = fem::make_effect(spec);
  auto p = e->parameters();
  for (auto& q : p) q.name = e->name() + "." + q.name;
  return p;
}

EffectModelFactory::EffectModelFactory(std::shared_ptr<const fit::FinModelFactory> base,
                                       std::vector<nlohmann::json> effects, fem::FinLayout layout)
    : base_(std::move(base)), specs_(std::move(effects)), layout_(std::move(layout)) {
  names_ = base_->parameter_names();
  base_count_ = static_cast<int>(names_.size());
  const Eigen::VectorXd base_defaults = base_->default_parameters();
  std::vector<double> defaults(base_defaults.data(), base_defaults.data() + base_count_);
  for (const auto& s : specs_)
    for (const auto& q : effect_parameters(s)) {
      names_.push_back(q.name);
      defaults.push_back(q.value);
    }
  defaults_ = Eigen::Map<const Eigen::VectorXd>(defaults.data(), static_cast<Eigen::Index>(defaults.size()));
}

std::unique_ptr<fem::Model> EffectModelFactory::build(const Eigen::VectorXd& physical) const {
  fem::io::Effects effects;
  Eigen::Index at = base_count_;
  for (const auto& s : specs_) {
    auto e = fem::make_effect(s);
    const auto n = static_cast<Eigen::Index>(e->parameters().size());
    std::vector<double> v(physical.data() + at, physical.data() + at + n);
    e->set_parameters(v);
    at += n;
    effects.push_back(std::move(e));
  }
  const Eigen::VectorXd p = physical.head(base_count_);
  // Rest-shape effects move the mesh before the model is built (the drive stays the same).
  stage::Mesh moved = base_->mesh();
  fem::io::reshape_mesh(moved, effects, layout_);
  bool reshaped = false;
  for (std::size_t i = 0; i < moved.points.data.size(); ++i) reshaped |= moved.points.data[i] != base_->mesh().points.data[i];
  std::unique_ptr<fem::Model> model;
  if (reshaped) {
    std::vector<fem::Vec3> rest(moved.points.dim(0));
    for (std::size_t i = 0; i < rest.size(); ++i) rest[i] = {moved.points(i, 0), moved.points(i, 1), moved.points(i, 2)};
    model = base_->rebased(rest)->build(p);
  } else {
    model = base_->build(p);
  }
  fem::io::apply_effects(*model, effects, layout_);
  return model;
}

}  // namespace finverse::loop
