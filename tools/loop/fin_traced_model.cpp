// The fin with candidate effects as a traced model (fin_traced_model.hpp).
#include "loop/fin_traced_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "loop/effect_model_factory.hpp"
#include "loop/errors.hpp"

namespace finverse::loop {

std::string candidate_name(const nlohmann::json& spec) {
  std::string n = spec.value("name", std::string("?"));
  if (spec.contains("group") && spec["group"].is_string() && spec["group"] != "all")
    n += ":" + spec["group"].get<std::string>();
  return n;
}

FinTracedModel::FinTracedModel(FinTraceSetup setup) : setup_(std::move(setup)) {
  const auto base_names = setup_.base->parameter_names();
  for (const auto& p : setup_.refit.parameters()) {
    const auto it = std::find(base_names.begin(), base_names.end(), p.name);
    if (it == base_names.end())
      throw InvalidInput("--parameters: '" + p.name + "' is not a parameter of the materials file");
    refit_index_.push_back(static_cast<int>(it - base_names.begin()));
  }
  for (const auto& s : setup_.candidates) {
    const auto name = candidate_name(s);
    if (specs_.count(name)) throw InvalidInput("--candidates: candidate '" + name + "' given twice");
    names_.push_back(name);
    specs_[name] = s;
    params_[name] = EffectModelFactory::effect_parameters(s);
  }
}

Eigen::VectorXd FinTracedModel::base_start() const {
  Eigen::VectorXd p(refit_index_.size());
  for (std::size_t i = 0; i < refit_index_.size(); ++i) p(static_cast<Eigen::Index>(i)) = setup_.best(refit_index_[i]);
  return p;
}

std::vector<fit::Parameter> FinTracedModel::effect_parameters(const std::string& candidate) const {
  std::vector<fit::Parameter> out;
  for (const auto& q : params_.at(candidate)) {
    fit::Parameter p;
    p.name = candidate + "." + q.name.substr(q.name.find('.') + 1);
    p.unit = q.unit.empty() ? "1" : q.unit;
    p.lower = q.lower;
    p.upper = q.upper;
    p.scale = fit::Scale::linear;
    out.push_back(p);
  }
  return out;
}

bool FinTracedModel::has_phase(const std::string& candidate) const {
  const auto& p = params_.at(candidate);
  return p.size() == 2 && p[1].name.ends_with(".phase");
}

Eigen::VectorXd FinTracedModel::effect_off(const std::string& candidate) const {
  const auto& p = params_.at(candidate);
  Eigen::VectorXd off(static_cast<Eigen::Index>(p.size()));
  for (std::size_t i = 0; i < p.size(); ++i) off(static_cast<Eigen::Index>(i)) = p[i].value;
  return off;
}

std::vector<ScoreDirection> FinTracedModel::score_directions(const std::string& candidate) const {
  const auto& p = params_.at(candidate);
  const Eigen::VectorXd off = effect_off(candidate);
  std::vector<ScoreDirection> dirs;
  if (has_phase(candidate)) {
    const double h = setup_.relative_step * (p[0].upper - p[0].lower);
    for (double phase : {0.0, std::numbers::pi / 2}) {
      Eigen::VectorXd v = off;
      v(0) = off(0) + h;
      v(1) = phase;
      dirs.push_back({v, h});
    }
    return dirs;
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double h = setup_.relative_step * (p[i].upper - p[i].lower);
    Eigen::VectorXd v = off;
    v(static_cast<Eigen::Index>(i)) += v(static_cast<Eigen::Index>(i)) + h <= p[i].upper ? h : -h;
    dirs.push_back({v, v(static_cast<Eigen::Index>(i)) - off(static_cast<Eigen::Index>(i))});
  }
  return dirs;
}

Eigen::VectorXd FinTracedModel::effect_start(const std::string& candidate, const Eigen::VectorXd& step) const {
  if (!has_phase(candidate)) return TracedModel::effect_start(candidate, step);
  const auto& p = params_.at(candidate);
  Eigen::VectorXd v = effect_off(candidate);
  v(0) = std::clamp(v(0) + std::hypot(step(0), step(1)), p[0].lower, p[0].upper);
  v(1) = std::atan2(step(1), step(0));
  return v;
}

Eigen::VectorXd FinTracedModel::full_parameters(const std::vector<std::string>& effects,
                                                const Eigen::VectorXd& physical) const {
  const Eigen::Index nb = setup_.best.size(), nr = static_cast<Eigen::Index>(refit_index_.size());
  Eigen::VectorXd full(nb + physical.size() - nr);
  full.head(nb) = setup_.best;
  for (Eigen::Index i = 0; i < nr; ++i) full(refit_index_[static_cast<std::size_t>(i)]) = physical(i);
  full.tail(physical.size() - nr) = physical.tail(physical.size() - nr);
  (void)effects;
  return full;
}

std::shared_ptr<const ModelPrediction> FinTracedModel::objective(const std::vector<std::string>& effects) const {
  std::string key;
  for (const auto& e : effects) key += e + "|";
  {
    const std::lock_guard lock(mutex_);
    const auto it = objectives_.find(key);
    if (it != objectives_.end()) return it->second;
  }
  std::vector<nlohmann::json> specs;
  for (const auto& e : effects) specs.push_back(specs_.at(e));
  auto factory = std::make_shared<EffectModelFactory>(setup_.base, specs, setup_.layout);
  auto obj = std::make_shared<const ModelPrediction>(factory, setup_.target, setup_.run);
  const std::lock_guard lock(mutex_);
  if (te_rows_.empty() && rows_per_frame_ == 0) {
    const auto& nodes = obj->compared_nodes();
    rows_per_frame_ = 3 * static_cast<long>(nodes.size());
    mesh_nodes_ = obj->node_weights().size();
    for (int n : nodes) compared_.emplace_back(n, std::sqrt(obj->node_weights()(n)));
    for (int n : setup_.trailing_edge_nodes) {
      const auto it = std::lower_bound(nodes.begin(), nodes.end(), n);
      if (it == nodes.end() || *it != n) continue;  // a prescribed node: not compared
      const long at = 3 * (it - nodes.begin());
      for (int c = 0; c < 3; ++c) te_rows_.emplace_back(at + c, std::sqrt(obj->node_weights()(n)));
    }
  }
  return objectives_.emplace(key, obj).first->second;
}

Eigen::VectorXd FinTracedModel::residuals(const std::vector<std::string>& effects, const Eigen::VectorXd& physical) const {
  return objective(effects)->residuals(full_parameters(effects, physical));
}

std::vector<fem::RunFrame> FinTracedModel::run(const std::vector<std::string>& effects,
                                               const Eigen::VectorXd& physical) const {
  return objective(effects)->run(full_parameters(effects, physical));
}

double FinTracedModel::trailing_edge_rms(const Eigen::VectorXd& r) const {
  if (te_rows_.empty() || rows_per_frame_ == 0) return TracedModel::trailing_edge_rms(r);
  const long frames = static_cast<long>(r.size()) / rows_per_frame_;
  double sum = 0;
  for (long k = 0; k < frames; ++k)
    for (const auto& [row, sw] : te_rows_) {
      const double v = r(k * rows_per_frame_ + row) / sw;
      sum += v * v;
    }
  return std::sqrt(sum / (frames * static_cast<double>(te_rows_.size() / 3)));
}

Eigen::VectorXd FinTracedModel::node_rms(const Eigen::VectorXd& r) const {
  if (rows_per_frame_ == 0) return TracedModel::node_rms(r);
  Eigen::VectorXd rms = Eigen::VectorXd::Constant(mesh_nodes_, std::numeric_limits<double>::quiet_NaN());
  const long frames = static_cast<long>(r.size()) / rows_per_frame_;
  if (frames == 0) return rms;
  for (std::size_t j = 0; j < compared_.size(); ++j) {
    const auto [node, sw] = compared_[j];
    if (!(sw > 0)) continue;  // weight 0: the residual carries nothing of this node
    double sum = 0;
    for (long k = 0; k < frames; ++k) sum += r.segment(k * rows_per_frame_ + 3 * static_cast<long>(j), 3).squaredNorm();
    rms(node) = std::sqrt(sum / static_cast<double>(frames)) / sw;
  }
  return rms;
}

}  // namespace finverse::loop
