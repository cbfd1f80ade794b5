// The residual analysis of fin-loop residual (residual_analysis.hpp).
#include "loop/residual_analysis.hpp"

#include <cmath>
#include <sstream>

namespace finverse::loop {

ResidualAnalysis analyse_residual(const SampledMotion& prediction, const SampledMotion& reconstruction,
                                  const Eigen::MatrixXd& rest, const std::vector<int>& root_nodes,
                                  const ResidualAnalysisOptions& options) {
  ResidualAnalysis a;
  a.field = residual_field(prediction, reconstruction, static_cast<int>(rest.rows()));
  a.regions = classify_fin_regions(rest, root_nodes);
  const int nv = a.field.node_count(), nf = a.field.frame_count();

  double sum = 0, count = 0;
  for (int i = 0; i < nv; ++i) {
    if (options.node_weights.size() && !(options.node_weights(i) > 0)) continue;
    sum += a.field.values.middleRows(3 * i, 3).squaredNorm();
    count += nf;
  }
  a.rms = count > 0 ? std::sqrt(sum / count) : 0.0;

  if (!options.period) {
    a.flags.push_back("no beat period (motion.h5 T or --period): no harmonics");
  } else if (nf < 2 * options.harmonics + 1) {
    a.flags.push_back(std::to_string(nf) + " frames cannot determine " + std::to_string(options.harmonics) +
                      " harmonics: none computed");
  } else {
    a.harmonics = fit_harmonics(a.field.times, a.field.values, *options.period, options.harmonics);
    if (!a.harmonics->whole_period)
      a.flags.push_back("harmonics and cycle mean from frames spanning less than one period");
    if (a.harmonics->condition > options.max_condition) {
      std::ostringstream s;
      s << "harmonic fit ill-conditioned (condition number " << a.harmonics->condition << ")";
      a.flags.push_back(s.str());
    }
  }

  a.modes = residual_modes(a.field, options.node_weights, options.modes);
  a.root = root_signal(reconstruction, a.regions);
  if (!(a.root.amplitude > 0)) a.flags.push_back("the root region does not move: no phase against the root");
  for (Eigen::Index m = 0; m < a.modes.shape.cols(); ++m) {
    a.mode_regions.push_back(region_energy_fractions(a.regions, a.modes.shape.col(m), options.node_weights));
    a.mode_phase.push_back(phase_character(a.modes.coefficient.col(m), a.root));
  }

  a.trailing_edge_nodes = options.trailing_edge_nodes;
  if (a.trailing_edge_nodes.empty())
    for (int i = 0; i < nv; ++i)
      if (a.regions.xi(i) >= 0.95) a.trailing_edge_nodes.push_back(i);
  a.trailing_edge = trailing_edge_error(a.field, reconstruction, a.trailing_edge_nodes);
  return a;
}

nlohmann::json residual_summary_json(const ResidualAnalysis& a) {
  nlohmann::json j;
  j["frames"] = a.field.frame_count();
  j["nodes"] = a.field.node_count();
  j["rms_m"] = a.rms;
  j["trailing_edge"] = {{"nodes", a.trailing_edge_nodes.size()},
                        {"rms_m", a.trailing_edge.rms},
                        {"excursion_m", a.trailing_edge.excursion},
                        {"rms_over_excursion", std::isfinite(a.trailing_edge.relative) ? nlohmann::json(a.trailing_edge.relative) : nlohmann::json()}};
  j["root_amplitude_m"] = a.root.amplitude;
  if (a.harmonics) {
    nlohmann::json h;
    h["period_s"] = a.harmonics->period;
    h["whole_period"] = a.harmonics->whole_period;
    h["condition"] = a.harmonics->condition;
    // Amplitudes from a fit over part of a period or an ill-conditioned one are not to be read.
    bool trusted = a.harmonics->whole_period;
    for (const auto& f : a.flags) trusted &= f.find("ill-conditioned") == std::string::npos;
    h["trusted"] = trusted;
    Eigen::VectorXd mean_norm(a.field.node_count());
    for (int i = 0; i < a.field.node_count(); ++i) mean_norm(i) = a.harmonics->mean.segment<3>(3 * i).norm();
    h["cycle_mean_max_m"] = mean_norm.maxCoeff();
    h["cycle_mean_rms_m"] = std::sqrt(mean_norm.squaredNorm() / mean_norm.size());
    for (int k = 1; k <= a.harmonics->order; ++k) {
      const Eigen::VectorXd amp = node_amplitude(*a.harmonics, k);
      Eigen::Index at = 0;
      amp.maxCoeff(&at);
      h["k" + std::to_string(k)] = {{"max_amplitude_m", amp(at)},
                                    {"rms_amplitude_m", std::sqrt(amp.squaredNorm() / amp.size())},
                                    {"node_of_max", at},
                                    {"phase_at_max_rad", node_phase(*a.harmonics, k)(at)}};
    }
    j["harmonics"] = h;
  }
  nlohmann::json modes = nlohmann::json::array();
  for (Eigen::Index m = 0; m < a.modes.shape.cols(); ++m) {
    nlohmann::json mj;
    mj["energy_fraction"] = a.modes.energy_fraction(m);
    nlohmann::json regions;
    int best = 0;
    for (int r = 0; r < kRegionCount; ++r) {
      regions[to_string(static_cast<Region>(r))] = a.mode_regions[m][r];
      if (a.mode_regions[m][r] > a.mode_regions[m][best]) best = r;
    }
    mj["region_fraction"] = regions;
    mj["dominant_region"] = to_string(static_cast<Region>(best));
    const auto& p = a.mode_phase[m];
    mj["rho_displacement"] = p.rho_displacement;
    mj["rho_velocity"] = p.rho_velocity;
    mj["rho_acceleration"] = p.rho_acceleration;
    mj["character"] = p.character;
    modes.push_back(mj);
  }
  j["modes"] = modes;
  j["flags"] = a.flags;
  return j;
}

}  // namespace finverse::loop
