// The report's "Closing the loop" section from loop.h5 (see loop_section.hpp).
#include "report/loop_section.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.hpp"

namespace finverse::report {
namespace {

using nlohmann::json;
using loop::io::LoopFile;
const std::string kPrefix = "closing the loop: ";

json num(double x) { return std::isfinite(x) ? json(x) : json(nullptr); }

json values(const std::vector<double>& v) {
  json a = json::array();
  for (double x : v) a.push_back(num(x));
  return a;
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= s.size() && !s.empty()) {
    const auto end = s.find(',', start);
    out.push_back(s.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return out;
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

// Before (the refitted base) and after (the last accepted effect) of one error measure: the
// errors/* datasets when present, else the first step's "before" and the last accepted "after".
struct BeforeAfter {
  double before = NAN, after = NAN;
};

BeforeAfter before_after(const NdArray<double>& state, const NdArray<double>& step_before,
                         const NdArray<double>& step_after, const NdArray<std::int32_t>& accepted) {
  BeforeAfter b;
  if (state.data.size() == 3) return {state.data[LoopFile::kBase], state.data[LoopFile::kFinal]};
  if (step_before.data.empty()) return b;
  b.before = b.after = step_before.data.front();
  for (std::size_t s = 0; s < accepted.data.size(); ++s)
    if (accepted.data[s]) b.after = step_after.data[s];
  return b;
}

}  // namespace

LoopSection loop_section(const LoopFile& loop, const stage::Mesh& mesh, const std::string& source) {
  const std::size_t ns = loop.tried.size(), nc = loop.candidates.size(), nv = mesh.points.dim(0);
  auto need = [&](bool ok, const std::string& what) {
    if (!ok) throw Error(source + ": " + what);
  };
  for (const auto* a : {&loop.bic_before, &loop.bic_after, &loop.held_before, &loop.held_after, &loop.te_before,
                        &loop.te_after})
    need(a->data.size() == ns, "steps/* of different lengths: expected one value per step (" + std::to_string(ns) + ")");
  need(loop.accepted.data.size() == ns && loop.parameter_names.size() == ns, "steps/accepted or parameter_names: expected " +
                                                                             std::to_string(ns) + " steps");
  need(loop.score.data.size() == ns * nc && loop.p_value.data.size() == ns * nc,
       "steps/score: expected [steps, candidates] = [" + std::to_string(ns) + ", " + std::to_string(nc) + "]");
  need(loop.magnitude.data.size() == 2 * ns && loop.lower95.data.size() == 2 * ns && loop.upper95.data.size() == 2 * ns,
       "steps/magnitude: expected [steps, 2]");
  const bool maps = !loop.node_rms_before.data.empty() && !loop.node_rms_after.data.empty();
  if (maps)
    need(loop.node_rms_before.data.size() == nv,
         "its residual maps have " + std::to_string(loop.node_rms_before.data.size()) + " nodes, mesh.h5 " +
             std::to_string(nv) + ": a loop.h5 of another mesh");

  LoopSection out;
  auto& fig = out.figure;
  std::vector<std::string> added;
  for (std::size_t s = 0; s < ns; ++s)
    if (loop.accepted.data[s]) added.push_back(loop.tried[s]);
  fig = {{"candidates", loop.candidates}, {"added", added}, {"stop_reason", loop.stop_reason.value_or("")},
         {"held_out_kind", loop.held_out_kind.value_or("")}, {"excursion", num(loop.excursion.value_or(NAN))}};

  // The decision trail: one row per step.
  json trail = json::array();
  for (std::size_t s = 0; s < ns; ++s) {
    std::vector<std::size_t> order;
    for (std::size_t c = 0; c < nc; ++c)
      if (std::isfinite(loop.score.data[s * nc + c])) order.push_back(c);  // NaN: added earlier
    std::stable_sort(order.begin(), order.end(),
                     [&](auto a, auto b) { return loop.score.data[s * nc + a] > loop.score.data[s * nc + b]; });
    json ranking = json::array();
    for (auto c : order)
      ranking.push_back({{"candidate", loop.candidates[c]}, {"score", loop.score.data[s * nc + c]},
                         {"p_value", num(loop.p_value.data[s * nc + c])}});
    json magnitude = json::array();
    const auto names = split(loop.parameter_names[s]);
    for (std::size_t i = 0; i < std::min<std::size_t>(2, names.size()); ++i)
      magnitude.push_back({{"name", names[i]}, {"value", num(loop.magnitude.data[2 * s + i])},
                           {"lower95", num(loop.lower95.data[2 * s + i])}, {"upper95", num(loop.upper95.data[2 * s + i])}});
    const bool tried = !loop.tried[s].empty(), accepted = loop.accepted.data[s] != 0;
    std::string verdict = "added";
    if (!tried) verdict = "nothing significant (score test)";
    else if (!accepted) {
      std::vector<std::string> why;
      if (!(loop.bic_after.data[s] < loop.bic_before.data[s])) why.push_back("BIC did not improve");
      if (!(loop.held_after.data[s] < loop.held_before.data[s])) why.push_back("held-out error did not fall");
      verdict = "rejected: " + join(why);
    }
    trail.push_back({{"step", s + 1}, {"ranking", ranking}, {"tried", loop.tried[s]}, {"accepted", accepted},
                     {"verdict", verdict}, {"magnitude", magnitude},
                     {"trailing_edge", {num(loop.te_before.data[s]), num(loop.te_after.data[s])}},
                     {"bic", {num(loop.bic_before.data[s]), num(loop.bic_after.data[s])}},
                     {"held_out", {num(loop.held_before.data[s]), num(loop.held_after.data[s])}}});
  }
  fig["trail"] = trail;

  // Before/after errors and their factor.
  const auto te = before_after(loop.state_trailing_edge, loop.te_before, loop.te_after, loop.accepted);
  const auto held = before_after(loop.state_held_out, loop.held_before, loop.held_after, loop.accepted);
  const auto bic = before_after(loop.state_bic, loop.bic_before, loop.bic_after, loop.accepted);
  const double te_factor = te.before / te.after, held_factor = held.before / held.after;
  fig["errors"] = {{"trailing_edge", {num(te.before), num(te.after), num(te_factor)}},
                   {"held_out", {num(held.before), num(held.after), num(held_factor)}},
                   {"bic", {num(bic.before), num(bic.after), num(bic.after - bic.before)}}};
  const std::string with = added.empty() ? "no effect added" : "with " + join(added);
  const double exc = loop.excursion.value_or(0);
  auto of_excursion = [&](double v) {
    if (!(exc > 0) || !std::isfinite(v)) return std::string();
    char text[64];
    std::snprintf(text, sizeof text, "%.3g of the trailing-edge excursion", v / exc);
    return std::string(text);
  };
  auto& sc = out.scores;
  sc.push_back(info(kPrefix + "effects added", static_cast<double>(added.size()), "",
                    (added.empty() ? "none" : join(added)) + "; stop: " + loop.stop_reason.value_or("?")));
  sc.push_back(info(kPrefix + "trailing-edge residual RMS, before (refitted base)", te.before, "m", of_excursion(te.before)));
  sc.push_back(info(kPrefix + "trailing-edge residual RMS, after", te.after, "m", with + "; " + of_excursion(te.after)));
  sc.push_back(info(kPrefix + "trailing-edge residual RMS, factor before / after", te_factor));
  sc.push_back(info(kPrefix + "held-out RMS error, before", held.before, "m", loop.held_out_kind.value_or("")));
  sc.push_back(info(kPrefix + "held-out RMS error, after", held.after, "m", with));
  sc.push_back(info(kPrefix + "held-out RMS error, factor before / after", held_factor));
  sc.push_back(info(kPrefix + "BIC, before", bic.before));
  sc.push_back(info(kPrefix + "BIC, after", bic.after, "", with));
  sc.push_back(info(kPrefix + "BIC change (after - before)", bic.after - bic.before, "", "negative: the data favour the added effects"));

  // The residual maps on the planform (x, z), one colour scale for both.
  if (maps) {
    double vmax = 0;
    for (const auto* a : {&loop.node_rms_before, &loop.node_rms_after})
      for (double v : a->data)
        if (std::isfinite(v)) vmax = std::max(vmax, v);
    fig["points"] = mesh.points.data;
    fig["triangles"] = mesh.triangles.data;
    fig["vmax"] = vmax;
    fig["maps"] = json::array({{{"label", "before: refitted base, no effect"}, {"rms", values(loop.node_rms_before.data)}},
                               {{"label", "after: " + with}, {"rms", values(loop.node_rms_after.data)}}});
  } else {
    fig["maps_missing"] = source + " has no nodes/rms_before (written before fin-loop recorded per-node maps)";
  }
  return out;
}

}  // namespace finverse::report
