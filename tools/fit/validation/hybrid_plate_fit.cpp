// Hybrid-plate fit validations (see hybrid_plate_fit.hpp).
#include "fit/validation/hybrid_plate_fit.hpp"

#include <chrono>
#include <cmath>
#include <memory>
#include <random>
#include <sstream>

#include "core/elapsed.hpp"
#include "core/log.hpp"
#include "fem/validation/hybrid_plate_model.hpp"
#include "fit/dynamic_objective.hpp"
#include "fit/errors.hpp"
#include "fit/io/materials_file.hpp"
#include "fit/io/tracking_noise.hpp"
#include "fit/quasi_static_objective.hpp"
#include "fit/validation/hybrid_plate_setup.hpp"
#include "fit/validation/hybrid_plate_twin.hpp"
#include "fit/validation/thin_airfoil_loads.hpp"

namespace finverse::fit::validation {

namespace {

constexpr const char* kTable3Source = "seed paper Table 3 (Liu et al.)";

FitOptions with_progress(FitOptions f, const std::string& label) {
  f.progress = [label](int run, const std::string& method, const GenerationRecord& g, double eta) {
    std::ostringstream s;
    s << label << ": run " << run + 1 << " (" << method << ") generation " << g.generation << " best " << g.best
      << " evaluations " << g.evaluations << " ETA " << log::format_duration(eta);
    log::info(s.str());
  };
  return f;
}

// tolerance 0: the errors are reported, not graded.
void report_fit(Summary& s, const std::string& prefix, const FitResult& r, double tolerance,
                const std::string& paper_note) {
  const Eigen::VectorXd truth = r.space.truth();
  for (int i = 0; i < r.space.size(); ++i) {
    if (tolerance > 0)
      s.relative(prefix + "_" + r.space[i].name, r.best_x(i), truth(i), tolerance, paper_note);
    else
      s.info(prefix + "_" + r.space[i].name + "_error", (r.best_x(i) - truth(i)) / truth(i));
    s.info(prefix + "_" + r.space[i].name + "_identified", r.uncertainty.identified.empty() ? 0 : r.uncertainty.identified[i]);
  }
  s.info(prefix + "_objective", r.best_objective, "chord");
  s.info(prefix + "_evaluations", static_cast<double>(r.evaluations));
  s.info(prefix + "_wall_seconds", r.wall_seconds, "s");
}

}  // namespace

Summary run_hybrid_plate_fit(const HybridPlateFitOptions& o) {
  Summary s("validation", "fit_hybrid_plate",
            "hybrid plate twin (shell + 3 beams, heaved, thin-airfoil loads): E_s, E_b1..3, nu fitted back by eq. (1) "
            "and eq. (2)");
  const HybridPlateTwinRun t = make_hybrid_plate_twin(o, true);
  const ParameterSpace space = hybrid_plate_space(*t.factory);
  s.parameters() = {{"grid", {o.nx, o.nz}}, {"periods", o.periods}, {"steps_per_period", o.steps_per_period},
                    {"qs_steps_per_period", o.qs_steps_per_period},
                    {"compared_frames", o.compared_frames}, {"instants", o.instants}, {"runs", o.fit.runs},
                    {"population", o.fit.population}, {"max_generations", o.fit.max_generations},
                    {"seed", o.fit.seed}, {"loads", "thin-airfoil pressure of the rigid heave (C(k) = 1) + added mass"},
                    {"load_density", o.load_scale}};

  int substeps = 1;
  DynamicObjectiveOptions dy;
  dy.start_time = 0;
  dy.substeps = 0;
  TargetMotion compared = last_period_frames(t, o, &substeps);
  dy.substeps = substeps;
  const DynamicObjective dynamic(t.factory, compared, dy);
  auto t0 = std::chrono::steady_clock::now();
  const FitResult rd = run_fit(space, dynamic, with_progress(o.fit, "fit_hybrid_plate eq. (1)"), "dynamic");
  const double wall_dynamic = seconds_since(t0);
  report_fit(s, "dynamic", rd, 0.01, std::string(kTable3Source) + ": errors up to 7.9 %; goal 1 %");

  QuasiStaticOptions qs;
  qs.instants = mid_swing_instants(t, o);
  qs.dt = t.qs_dt;
  const QuasiStaticObjective quasi(t.factory, t.qs_truth, qs);
  t0 = std::chrono::steady_clock::now();
  const FitResult rq = run_fit(space, quasi, with_progress(o.fit, "fit_hybrid_plate eq. (2)"), "quasi_static");
  const double wall_quasi = seconds_since(t0);
  // The paper's form drops the plate's inertia, against a dynamic truth (its bias is the point).
  report_fit(s, "quasi_static", rq, 0, std::string(kTable3Source) + ": errors up to 19.5 %");

  // Eq. (2) with inertia (issue 45 goal 5): the same fit with M times the truth's measured
  // acceleration change as a known load.
  qs.inertia = true;
  const QuasiStaticObjective inertial(t.factory, t.qs_truth, qs);
  const FitResult ri =
      run_fit(space, inertial, with_progress(o.fit, "fit_hybrid_plate eq. (2) with inertia"), "quasi_static");
  report_fit(s, "quasi_static_inertia", ri, 0.05,
             std::string(kTable3Source) + ": the paper's eq. (2) errs up to 19.5 %; issue 45 goal 5 %");
  if (!o.materials_out.empty())
    io::write_materials(o.materials_out, rq, Provenance{"fin-fit", s.parameters(), {o.case_file}});

  s.at_most("quasi_static_over_dynamic_wall_time", wall_quasi / wall_dynamic, 1.0 / 25,
            std::string(kTable3Source) + ": quasi-static about 25x faster");
  s.info("dynamic_evaluations_per_second", rd.evaluations / std::max(1e-9, rd.wall_seconds), "1/s");
  s.info("quasi_static_evaluations_per_second", rq.evaluations / std::max(1e-9, rq.wall_seconds), "1/s");
  return s;
}

Summary run_hybrid_plate_noise(const HybridPlateFitOptions& o) {
  Summary s("validation", "fit_noise",
            "hybrid plate twin with the target perturbed at fin-track's accuracy: parameter errors and 95 % interval "
            "coverage over noise seeds");
  const HybridPlateTwinRun t = make_hybrid_plate_twin(o, true);
  const ParameterSpace space = hybrid_plate_space(*t.factory);
  const Eigen::VectorXd truth = space.truth();
  const double sigma = io::sigma_for_mean_error(o.noise_over_chord * t.plate.chord);
  std::vector<int> covered(space.size(), 0), identified(space.size(), 0);
  std::vector<double> abs_error(space.size(), 0.0);
  for (int seed = 0; seed < o.noise_seeds; ++seed) {
    TargetMotion noisy = o.noise_objective == "dynamic" ? t.truth : t.qs_truth;
    std::mt19937_64 rng(1000 + seed);
    std::normal_distribution<double> n(0, sigma);
    for (auto& frame : noisy.positions)
      for (auto& x : frame) x += fem::Vec3(n(rng), n(rng), n(rng));
    FitResult r;
    FitOptions f = with_progress(o.fit, "fit_noise seed " + std::to_string(seed));
    if (o.noise_objective == "dynamic") {
      int substeps = 1;
      HybridPlateTwinRun view = t;
      view.truth = noisy;
      DynamicObjectiveOptions dy;
      TargetMotion compared = last_period_frames(view, o, &substeps);
      dy.substeps = substeps;
      r = run_fit(space, DynamicObjective(t.factory, compared, dy), f, "dynamic");
    } else {
      QuasiStaticOptions qs;
      qs.instants = mid_swing_instants(t, o);
      qs.dt = t.qs_dt;
      r = run_fit(space, QuasiStaticObjective(t.factory, noisy, qs), f, "quasi_static");
    }
    for (int i = 0; i < space.size(); ++i) {
      abs_error[i] += std::abs(r.best_x(i) - truth(i)) / truth(i) / o.noise_seeds;
      const bool in = r.uncertainty.lower95.size() == space.size() && r.uncertainty.lower95(i) <= truth(i) &&
                      truth(i) <= r.uncertainty.upper95(i);
      covered[i] += in ? 1 : 0;
      identified[i] += r.uncertainty.identified.empty() ? 0 : r.uncertainty.identified[i];
      s.info("seed" + std::to_string(seed) + "_" + space[i].name + "_error", (r.best_x(i) - truth(i)) / truth(i));
    }
  }
  for (int i = 0; i < space.size(); ++i) {
    s.info(space[i].name + "_mean_abs_error", abs_error[i]);
    // A parameter the noisy data cannot constrain gets an interval that covers anything: the
    // coverage means something only beside how often the parameter was identified.
    s.info(space[i].name + "_identified_fraction", static_cast<double>(identified[i]) / o.noise_seeds);
    s.at_most(space[i].name + "_interval_misses", 1.0 - static_cast<double>(covered[i]) / o.noise_seeds, 0.2,
              "issue 31: the 95 % interval covers the truth in >= 80 % of the seeds");
  }
  s.parameters() = {{"seeds", o.noise_seeds}, {"noise_over_chord", o.noise_over_chord},
                    {"sigma_per_component", sigma}, {"objective", o.noise_objective}, {"runs", o.fit.runs}};
  return s;
}

Summary run_hybrid_plate_identifiability(const HybridPlateFitOptions& o) {
  Summary s("validation", "fit_identifiability",
            "eq. (2) on the hybrid plate with the loads removed: the modulus scale must be reported not identified");
  const HybridPlateTwinRun t = make_hybrid_plate_twin(o, false);
  const ParameterSpace space = hybrid_plate_space(*t.factory);
  QuasiStaticOptions qs;
  qs.instants = mid_swing_instants(t, o);
  qs.dt = t.qs_dt;
  const FitResult r = run_fit(space, QuasiStaticObjective(t.factory, t.qs_truth, qs),
                              with_progress(o.fit, "fit_identifiability"), "quasi_static");
  int moduli = 0, identified_moduli = 0;
  for (int i = 0; i < space.size(); ++i) {
    if (space[i].scale != Scale::log10) continue;
    ++moduli;
    identified_moduli += r.uncertainty.identified.at(i);
    s.parameters()["verdict"][space[i].name] = r.uncertainty.verdict.at(i);
  }
  s.absolute("moduli_reported_identified", identified_moduli, 0, 0,
             "DESIGN.md 5.4: with the displacement drive alone the modulus scale is not identifiable");
  s.info("moduli", moduli);
  return s;
}

}  // namespace finverse::fit::validation
