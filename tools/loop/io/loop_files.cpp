// residual.h5, loop.h5 and the inputs of fin-loop (loop_files.hpp).
#include "loop/io/loop_files.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "core/error.hpp"
#include "loop/io/loop_file.hpp"

namespace finverse::loop::io {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct ResidualFile {
  static constexpr const char* kSchema = "finverse/residual";
  NdArray<double> time, residual, root_displacement, mean, amplitude, phase;
  stage::Strings region_names, character;
  NdArray<std::int32_t> node_region;
  NdArray<double> energy, shape, coefficient, region_fraction, rho;
  std::optional<double> period;
  std::optional<std::string> prediction_kind, flags;
  template <class V> void fields(V&& v) {
    v("time", time);
    v("residual", residual);
    v("regions/names", region_names);
    v("regions/node_region", node_region);
    v("root/displacement", root_displacement);
    v("harmonics/mean", mean);
    v("harmonics/amplitude", amplitude);
    v("harmonics/phase", phase);
    v("modes/energy_fraction", energy);
    v("modes/shape", shape);
    v("modes/coefficient", coefficient);
    v("modes/region_fraction", region_fraction);
    v("modes/rho", rho);
    v("modes/character", character);
  }
  template <class A> void attributes(A&& a) {
    a("T", period);
    a("prediction_kind", prediction_kind);
    a("flags", flags);
  }
};

NdArray<double> array(std::vector<std::size_t> shape, double fill = 0) {
  NdArray<double> a;
  std::size_t n = 1;
  for (auto s : shape) n *= s;
  a.shape = std::move(shape);
  a.data.assign(n, fill);
  return a;
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ",") + x;
  return s;
}

}  // namespace

SampledMotion sampled_motion(const NdArray<double>& time, const NdArray<double>& points, const std::string& source) {
  SampledMotion m;
  m.source = source;
  const std::size_t nf = time.data.size();
  if (points.shape.size() != 3 || points.dim(0) != nf || points.dim(2) != 3)
    throw Error(source + ": /points: expected [nf, nv, 3] with nf = /time's length");
  const std::size_t stride = points.dim(1) * 3;
  m.times = time.data;
  for (std::size_t k = 0; k < nf; ++k)
    m.positions.push_back(Eigen::Map<const Eigen::VectorXd>(points.data.data() + k * stride,
                                                            static_cast<Eigen::Index>(stride)));
  return m;
}

Eigen::MatrixXd rest_positions(const stage::Mesh& mesh) {
  const std::size_t nv = mesh.points.dim(0);
  Eigen::MatrixXd p(nv, 3);
  for (std::size_t i = 0; i < nv; ++i)
    for (std::size_t c = 0; c < 3; ++c) p(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(c)) = mesh.points(i, c);
  return p;
}

std::vector<int> ray_tip_nodes(const stage::Mesh& mesh) {
  std::map<int, std::pair<double, int>> tip;  // ray -> (largest s, node)
  const std::size_t nb = mesh.beam_elements.shape.empty() ? 0 : mesh.beam_elements.dim(0);
  for (std::size_t e = 0; e < nb; ++e)
    for (std::size_t end = 0; end < 2; ++end) {
      const double s = mesh.beam_s(e, end);
      const int node = mesh.beam_elements(e, end);
      auto [it, fresh] = tip.emplace(mesh.beam_ray.data[e], std::make_pair(s, node));
      if (!fresh && s > it->second.first) it->second = {s, node};
    }
  std::vector<int> nodes;
  for (const auto& [ray, t] : tip) nodes.push_back(t.second);
  return nodes;
}

void write_residual(const std::filesystem::path& path, const ResidualAnalysis& a, std::optional<double> period,
                    const std::string& prediction_kind, const Provenance& provenance) {
  const std::size_t nf = static_cast<std::size_t>(a.field.frame_count()), nv = static_cast<std::size_t>(a.field.node_count());
  const std::size_t nm = static_cast<std::size_t>(a.modes.shape.cols());
  ResidualFile f;
  f.time.shape = {nf};
  f.time.data = a.field.times;
  f.residual = array({nf, nv, 3});
  for (std::size_t k = 0; k < nf; ++k)
    for (std::size_t r = 0; r < 3 * nv; ++r) f.residual.data[k * 3 * nv + r] = a.field.values(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(k));
  for (int r = 0; r < kRegionCount; ++r) f.region_names.push_back(to_string(static_cast<Region>(r)));
  f.node_region.shape = {nv};
  for (auto r : a.regions.region) f.node_region.data.push_back(static_cast<std::int32_t>(r));
  f.root_displacement.shape = {nf};
  f.root_displacement.data.assign(a.root.displacement.data(), a.root.displacement.data() + nf);
  if (a.harmonics) {
    const auto& h = *a.harmonics;
    const std::size_t nk = static_cast<std::size_t>(h.order);
    f.mean = array({nv, 3});
    for (std::size_t r = 0; r < 3 * nv; ++r) f.mean.data[r] = h.mean(static_cast<Eigen::Index>(r));
    f.amplitude = array({nk, nv});
    f.phase = array({nk, nv});
    for (std::size_t k = 0; k < nk; ++k) {
      const Eigen::VectorXd amp = node_amplitude(h, static_cast<int>(k + 1)), ph = node_phase(h, static_cast<int>(k + 1));
      for (std::size_t i = 0; i < nv; ++i) {
        f.amplitude.data[k * nv + i] = amp(static_cast<Eigen::Index>(i));
        f.phase.data[k * nv + i] = ph(static_cast<Eigen::Index>(i));
      }
    }
  }
  f.energy = array({nm});
  f.shape = array({nm, nv, 3});
  f.coefficient = array({nf, nm});
  f.region_fraction = array({nm, static_cast<std::size_t>(kRegionCount)});
  f.rho = array({nm, 3});
  for (std::size_t m = 0; m < nm; ++m) {
    const auto mi = static_cast<Eigen::Index>(m);
    f.energy.data[m] = a.modes.energy_fraction(mi);
    for (std::size_t r = 0; r < 3 * nv; ++r) f.shape.data[m * 3 * nv + r] = a.modes.shape(static_cast<Eigen::Index>(r), mi);
    for (std::size_t k = 0; k < nf; ++k) f.coefficient.data[k * nm + m] = a.modes.coefficient(static_cast<Eigen::Index>(k), mi);
    for (int r = 0; r < kRegionCount; ++r) f.region_fraction.data[m * kRegionCount + r] = a.mode_regions[m][r];
    f.rho.data[m * 3 + 0] = a.mode_phase[m].rho_displacement;
    f.rho.data[m * 3 + 1] = a.mode_phase[m].rho_velocity;
    f.rho.data[m * 3 + 2] = a.mode_phase[m].rho_acceleration;
    f.character.push_back(a.mode_phase[m].character);
  }
  f.period = period;
  f.prediction_kind = prediction_kind;
  if (!a.flags.empty()) f.flags = nlohmann::json(a.flags).dump();
  stage::write(path, f, provenance);
}

void write_loop(const std::filesystem::path& path, const TraceRecord& rec, const Provenance& provenance) {
  const auto& r = rec.result;
  const std::size_t ns = r.steps.size(), nc = rec.candidates.size();
  LoopFile f;
  f.candidates = rec.candidates;
  f.accepted.shape = {ns};
  f.score = array({ns, nc}, kNaN);
  f.p_value = array({ns, nc}, kNaN);
  f.projected = array({ns, nc}, kNaN);
  f.magnitude = array({ns, 2}, kNaN);
  f.lower95 = array({ns, 2}, kNaN);
  f.upper95 = array({ns, 2}, kNaN);
  f.bic_before = array({ns});
  f.bic_after = array({ns}, kNaN);
  f.held_before = array({ns});
  f.held_after = array({ns}, kNaN);
  f.te_before = array({ns});
  f.te_after = array({ns}, kNaN);
  for (std::size_t s = 0; s < ns; ++s) {
    const auto& st = r.steps[s];
    f.tried.push_back(st.tried);
    f.accepted.data.push_back(st.accepted ? 1 : 0);
    for (const auto& c : st.scores) {
      const auto it = std::find(rec.candidates.begin(), rec.candidates.end(), c.name);
      const std::size_t j = static_cast<std::size_t>(it - rec.candidates.begin());
      if (j >= nc) continue;
      f.score.data[s * nc + j] = c.score.statistic;
      f.p_value.data[s * nc + j] = c.score.p_value;
      f.projected.data[s * nc + j] = c.score.projected_fraction;
    }
    f.parameter_names.push_back(join(st.effect_parameter_names));
    for (Eigen::Index i = 0; i < std::min<Eigen::Index>(2, st.magnitude.size()); ++i) {
      f.magnitude.data[s * 2 + static_cast<std::size_t>(i)] = st.magnitude(i);
      f.lower95.data[s * 2 + static_cast<std::size_t>(i)] = st.lower95(i);
      f.upper95.data[s * 2 + static_cast<std::size_t>(i)] = st.upper95(i);
    }
    f.bic_before.data[s] = st.before.bic;
    f.held_before.data[s] = st.before.held_out_rms;
    f.te_before.data[s] = st.before.trailing_edge_rms;
    if (!st.tried.empty()) {
      f.bic_after.data[s] = st.after.bic;
      f.held_after.data[s] = st.after.held_out_rms;
      f.te_after.data[s] = st.after.trailing_edge_rms;
    }
  }
  // Per-node maps: the refitted base, the final model and after each step's refit.
  const std::size_t nv = static_cast<std::size_t>(r.base.node_rms.size());
  auto node_array = [](const Eigen::VectorXd& v) {
    NdArray<double> a;
    a.shape = {static_cast<std::size_t>(v.size())};
    a.data.assign(v.data(), v.data() + v.size());
    return a;
  };
  if (nv > 0) {
    f.node_rms_before = node_array(r.base.node_rms);
    f.node_rms_after = node_array(r.final_state.node_rms.size() ? r.final_state.node_rms : r.base.node_rms);
    f.step_node_rms_after = array({ns, nv}, kNaN);
    for (std::size_t s = 0; s < ns; ++s) {
      const auto& m = r.steps[s].after.node_rms;
      if (r.steps[s].tried.empty() || static_cast<std::size_t>(m.size()) != nv) continue;
      std::copy(m.data(), m.data() + m.size(), f.step_node_rms_after.data.begin() + static_cast<std::ptrdiff_t>(s * nv));
    }
  }
  f.state_trailing_edge = array({3});
  f.state_held_out = array({3});
  f.state_bic = array({3});
  for (const auto& [k, st] : {std::pair{LoopFile::kInitial, &r.base_initial}, std::pair{LoopFile::kBase, &r.base},
                              std::pair{LoopFile::kFinal, &r.final_state}}) {
    f.state_trailing_edge.data[k] = st->trailing_edge_rms;
    f.state_held_out.data[k] = st->held_out_rms;
    f.state_bic.data[k] = st->bic;
  }
  f.names = r.space.names();
  f.values.shape = {static_cast<std::size_t>(r.parameters.size())};
  f.values.data.assign(r.parameters.data(), r.parameters.data() + r.parameters.size());
  f.held_out.shape = {rec.split.held_out.size()};
  f.held_out.data.assign(rec.split.held_out.begin(), rec.split.held_out.end());
  f.stop_reason = r.stop_reason;
  f.held_out_kind = rec.split.kind;
  f.excursion = rec.excursion;
  stage::write(path, f, provenance);
}

nlohmann::json trace_summary_json(const TraceRecord& rec) {
  const auto& r = rec.result;
  nlohmann::json j;
  j["candidates"] = rec.candidates;
  j["held_out"] = {{"kind", rec.split.kind}, {"frames", rec.split.held_out}};
  j["trailing_edge_excursion_m"] = rec.excursion;
  auto state = [&](const ModelState& s) {
    return nlohmann::json{{"bic", s.bic},
                          {"held_out_rms_m", s.held_out_rms},
                          {"trailing_edge_rms_m", s.trailing_edge_rms},
                          {"trailing_edge_rms_over_excursion", rec.excursion > 0 ? s.trailing_edge_rms / rec.excursion : 0.0},
                          {"parameters", s.parameters}};
  };
  j["initial"] = state(r.base_initial);
  j["base"] = state(r.base);
  j["final"] = state(r.final_state);
  nlohmann::json steps = nlohmann::json::array();
  for (const auto& st : r.steps) {
    nlohmann::json sj;
    nlohmann::json ranking = nlohmann::json::array();
    for (const auto& c : st.scores)
      ranking.push_back({{"candidate", c.name},
                         {"score", c.score.statistic},
                         {"dof", c.score.degrees_of_freedom},
                         {"p_value", c.score.p_value},
                         {"projected_fraction", c.score.projected_fraction},
                         {"failure", c.failure}});
    sj["ranking"] = ranking;
    sj["tried"] = st.tried;
    sj["accepted"] = st.accepted;
    sj["before"] = state(st.before);
    if (!st.tried.empty()) {
      sj["after"] = state(st.after);
      nlohmann::json mags = nlohmann::json::array();
      for (std::size_t i = 0; i < st.effect_parameter_names.size(); ++i) {
        const auto k = static_cast<Eigen::Index>(i);
        auto num = [](double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(); };
        mags.push_back({{"name", st.effect_parameter_names[i]},
                        {"value", st.magnitude(k)},
                        {"lower95", num(st.lower95(k))},
                        {"upper95", num(st.upper95(k))}});
      }
      sj["magnitude"] = mags;
    }
    sj["model_evaluations"] = st.evaluations;
    steps.push_back(sj);
  }
  j["steps"] = steps;
  j["added"] = r.added;
  j["stop_reason"] = r.stop_reason;
  nlohmann::json params;
  for (int i = 0; i < r.space.size(); ++i) params[r.space[i].name] = r.parameters(i);
  j["parameters"] = params;
  j["model_evaluations"] = r.evaluations;
  return j;
}

}  // namespace finverse::loop::io
