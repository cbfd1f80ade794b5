// Conversion of a FitResult to the materials.h5 contract (see materials_file.hpp).
#include "fit/io/materials_file.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace finverse::fit::io {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

NdArray<double> vec(const Eigen::VectorXd& v) {
  return NdArray<double>({static_cast<std::size_t>(v.size())}, std::vector<double>(v.data(), v.data() + v.size()));
}
NdArray<double> scalar(double x) { return NdArray<double>({}, std::vector<double>{x}); }

}  // namespace

stage::Materials to_stage(const FitResult& r) {
  const auto& space = r.space;
  const std::size_t np = space.size(), nruns = r.runs.size();
  stage::Materials m;
  m.objective_kind = r.objective;
  m.lower = NdArray<double>({np});
  m.upper = NdArray<double>({np});
  for (std::size_t i = 0; i < np; ++i) {
    const auto& p = space[static_cast<int>(i)];
    m.names.push_back(p.name);
    m.units.push_back(p.unit);
    m.scale.push_back(to_string(p.scale));
    m.lower(i) = p.lower;
    m.upper(i) = p.upper;
  }
  if (const auto truth = space.truth(); truth.size() == static_cast<Eigen::Index>(np)) m.truth = vec(truth);
  m.best = vec(r.best_x);
  m.objective = scalar(r.best_objective);
  m.sum_of_squares = scalar(r.best_sum_of_squares);
  m.evaluations = NdArray<std::int64_t>({}, std::vector<std::int64_t>{r.evaluations});

  std::size_t ngen = 1;
  bool polished = false;
  for (const auto& run : r.runs) {
    ngen = std::max(ngen, run.history.size());
    polished = polished || run.polished_x.size() == static_cast<Eigen::Index>(np);
  }
  m.run_seed = NdArray<std::int64_t>({nruns});
  m.run_evaluations = NdArray<std::int64_t>({nruns});
  m.run_best = NdArray<double>({nruns, np});
  m.run_objective = NdArray<double>({nruns});
  m.run_generations = NdArray<std::int32_t>({nruns});
  m.run_converged = NdArray<std::int32_t>({nruns});
  m.run_history = NdArray<double>({nruns, ngen}, kNaN);
  m.run_history_evaluations = NdArray<double>({nruns, ngen}, kNaN);
  m.run_history_best = NdArray<double>({nruns, ngen, np}, kNaN);
  if (polished) {
    m.run_polished = NdArray<double>({nruns, np}, kNaN);
    m.run_polished_objective = NdArray<double>({nruns}, kNaN);
    m.run_polish_evaluations = NdArray<std::int64_t>({nruns}, 0);
  }
  for (std::size_t k = 0; k < nruns; ++k) {
    const auto& run = r.runs[k];
    m.run_method.push_back(run.method);
    m.run_seed(k) = run.seed;
    m.run_evaluations(k) = run.evaluations;
    m.run_objective(k) = run.best_objective;
    m.run_generations(k) = static_cast<std::int32_t>(run.history.size());
    m.run_converged(k) = run.converged ? 1 : 0;
    for (std::size_t i = 0; i < np; ++i) m.run_best(k, i) = run.best_x(static_cast<Eigen::Index>(i));
    for (std::size_t g = 0; g < run.history.size(); ++g) {
      const auto& h = run.history[g];
      m.run_history(k, g) = h.best;
      m.run_history_evaluations(k, g) = static_cast<double>(h.evaluations);
      if (h.best_x.size() == static_cast<Eigen::Index>(np))
        for (std::size_t i = 0; i < np; ++i) m.run_history_best(k, g, i) = h.best_x(static_cast<Eigen::Index>(i));
    }
    if (polished && run.polished_x.size() == static_cast<Eigen::Index>(np)) {
      for (std::size_t i = 0; i < np; ++i) m.run_polished(k, i) = run.polished_x(static_cast<Eigen::Index>(i));
      m.run_polished_objective(k) = run.polished_objective;
      m.run_polish_evaluations(k) = run.polish_evaluations;
    }
  }

  const auto& u = r.uncertainty;
  if (u.standard_error.size() == static_cast<Eigen::Index>(np)) {
    m.standard_error = vec(u.standard_error);
    m.ci95 = NdArray<double>({np, 2});
    for (std::size_t i = 0; i < np; ++i) {
      m.ci95(i, 0) = u.lower95(static_cast<Eigen::Index>(i));
      m.ci95(i, 1) = u.upper95(static_cast<Eigen::Index>(i));
    }
    m.correlation = NdArray<double>({np, np});
    for (std::size_t i = 0; i < np; ++i)
      for (std::size_t j = 0; j < np; ++j)
        m.correlation(i, j) = u.correlation(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
    m.singular_values = vec(u.singular_values);
    m.residual_variance = scalar(u.residual_variance);
    m.identified = NdArray<std::int32_t>({np});
    for (std::size_t i = 0; i < np; ++i) m.identified(i) = u.identified.at(i);
    m.verdict = u.verdict;
  } else {
    m.verdict.assign(np, "not assessed (no polish, no Jacobian)");
  }
  return m;
}

void write_materials(const std::filesystem::path& path, const FitResult& result, const Provenance& provenance) {
  auto m = to_stage(result);
  stage::write(path, m, provenance);
}

nlohmann::json fit_summary_json(const FitResult& r) {
  using nlohmann::json;
  const auto finite_or_null = [](double x) { return std::isfinite(x) ? json(x) : json(nullptr); };
  json j;
  j["objective_kind"] = r.objective;
  j["objective_m"] = r.best_objective;
  j["sum_of_squares_m2"] = r.best_sum_of_squares;
  j["evaluations"] = r.evaluations;
  j["wall_seconds"] = r.wall_seconds;
  j["threads"] = r.threads;
  const auto truth = r.space.truth();
  const bool have_u = r.uncertainty.standard_error.size() == r.space.size();
  if (have_u)
    j["misfit"] = {{"systematic", r.uncertainty.systematic_misfit},
                   {"correlation_length_m", r.uncertainty.misfit_correlation_length},
                   {"neighbour_correlation", r.uncertainty.misfit_neighbour_correlation},
                   {"effective_residuals", r.uncertainty.effective_residuals},
                   {"effective_channels", r.uncertainty.effective_channels}};
  for (int i = 0; i < r.space.size(); ++i) {
    const auto& p = r.space[i];
    json e{{"name", p.name}, {"unit", p.unit}, {"scale", to_string(p.scale)}, {"lower", p.lower},
           {"upper", p.upper}, {"best", r.best_x(i)}};
    if (truth.size() == r.space.size()) {
      e["truth"] = truth(i);
      e["error"] = (r.best_x(i) - truth(i)) / truth(i);
    }
    if (have_u) {
      e["standard_error_scaled"] = finite_or_null(r.uncertainty.standard_error(i));
      e["ci95"] = {finite_or_null(r.uncertainty.lower95(i)), finite_or_null(r.uncertainty.upper95(i))};
      e["identified"] = r.uncertainty.identified.at(static_cast<std::size_t>(i)) != 0;
      e["verdict"] = r.uncertainty.verdict.at(static_cast<std::size_t>(i));
    }
    j["parameters"].push_back(e);
  }
  for (const auto& run : r.runs) {
    j["runs"].push_back({{"method", run.method},
                         {"seed", run.seed},
                         {"objective_m", run.best_objective},
                         {"generations", run.history.size()},
                         {"converged", run.converged},
                         {"evaluations", run.evaluations},
                         {"cache_hits", run.cache_hits},
                         {"wall_seconds", run.wall_seconds},
                         {"polished_objective_m", run.polished_x.size() ? json(run.polished_objective) : json(nullptr)},
                         {"polish_evaluations", run.polish_evaluations},
                         {"polish_wall_seconds", run.polish_wall_seconds}});
  }
  return j;
}

}  // namespace finverse::fit::io
