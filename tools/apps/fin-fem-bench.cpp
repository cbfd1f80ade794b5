// fin-fem-bench: the structural FEM benchmark (results/bench/fem.json, issue 3): wall time of
// finverse against CalculiX on the Sze end-shear strip and on the hybrid plate, each code on the
// coarsest of its meshes that reaches 1 % of the reference, and the cost of one Newton iteration
// against the number of DOFs with its fitted growth exponent. CalculiX is run just before by
// tools/scripts/calculix_sze_strip.py and calculix_hybrid_plate.py (rules/bench_fem.smk), whose
// JSON outputs this program reads: both sides are measured in the same run on the same machine.
// Exit 0 when every goal is met, 1 when one is missed, 2 on error.
//
//   fin-fem-bench --structures data/reference/structures.json --case data/cases/hybrid_plate.json
//       --plate-reference data/reference/hybrid_plate_calculix.json --peer-sze ccx_sze.json
//       --peer-plate ccx_plate.json --json results/bench/fem.json
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/summary.hpp"
#include "fem/validation/hybrid_plate.hpp"
#include "fem/validation/hybrid_plate_model.hpp"
#include "fem/validation/newton_scaling.hpp"
#include "fem/validation/shell_cases.hpp"

namespace {

namespace fv = finverse::fem::validation;

nlohmann::json read_json(const std::string& path, const char* flag) {
  std::ifstream in(path);
  if (!in) throw finverse::Error(std::string(flag) + ": cannot open " + path);
  try {
    return nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw finverse::Error(std::string(flag) + ": " + path + " is not valid JSON: " + e.what());
  }
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Largest relative error of a validation case's relative metrics.
double worst_error(const finverse::Summary& r) {
  double e = 0;
  for (const auto& m : r.metrics())
    if (m.kind == "relative") e = std::max(e, m.error());
  return e;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fin-fem-bench: finverse vs CalculiX wall time, Newton-iteration scaling"};
  finverse::cli::Standard standard(app, "fin-fem-bench");
  std::string structures, case_file, plate_reference, peer_sze, peer_plate, json_out;
  std::vector<int> sze_meshes{8, 16, 32}, plate_meshes{8, 12, 16, 24, 32}, scaling{16, 32, 48, 64, 96};
  double accuracy = 0.01, goal = 0.5;
  app.add_option("--structures", structures, "structures.json (Sze end-shear table)")->required();
  app.add_option("--case", case_file, "data/cases/hybrid_plate.json")->required();
  app.add_option("--plate-reference", plate_reference, "hybrid_plate_calculix.json")->required();
  app.add_option("--peer-sze", peer_sze, "output of calculix_sze_strip.py")->required();
  app.add_option("--peer-plate", peer_plate, "output of calculix_hybrid_plate.py --analysis static")->required();
  app.add_option("--json", json_out, "results/bench/fem.json")->required();
  app.add_option("--sze-meshes", sze_meshes, "cells along the strip tried, coarsest first")->capture_default_str();
  app.add_option("--plate-meshes", plate_meshes, "plate grids tried, coarsest first")->capture_default_str();
  app.add_option("--scaling", scaling, "plate grids of the Newton-iteration scaling")->capture_default_str();
  app.add_option("--accuracy", accuracy, "a mesh counts when within this of the reference")->capture_default_str();

  return finverse::cli::run(app, standard, argc, argv, [&]() -> int {
    finverse::Summary s("bench", "fem",
                        "Structural FEM: wall time of finverse vs CalculiX (NLGEOM, S8R/B32R) on the "
                        "Sze end-shear strip and the hybrid plate, each on its coarsest mesh within "
                        "1 % of the reference; cost of a Newton iteration against DOFs");
    const auto start = std::chrono::steady_clock::now();
    auto& par = s.parameters();

    // Sze strip: ours, coarsest passing mesh (two triangles per cell, 2 cells across).
    double ours_sze = NAN;
    for (int nx : sze_meshes) {
      fv::SzeEndShearOptions o;
      o.reference = structures;
      o.nx = nx;
      o.tolerance = accuracy;
      const auto t0 = std::chrono::steady_clock::now();
      const finverse::Summary r = fv::run_sze_end_shear(o);
      const double t = seconds_since(t0);
      par["finverse_sze"].push_back({{"nx", nx}, {"ny", o.ny}, {"wall_s", t}, {"max_error", worst_error(r)}});
      std::cerr << "finverse sze strip " << nx << "x" << o.ny << ": " << t << " s, max error "
                << worst_error(r) << "\n";
      if (r.pass()) {
        ours_sze = t;
        par["finverse_sze_mesh"] = {nx, o.ny};
        break;
      }
    }
    const nlohmann::json psze = read_json(peer_sze, "--peer-sze");
    double peer_sze_t = NAN;
    for (const auto& r : psze.at("runs"))
      if (r.contains("wall_s") && r.at("max_relative_error").get<double>() <= accuracy) {
        peer_sze_t = r.at("wall_s").get<double>();
        par["calculix_sze_mesh"] = {r.at("nx"), r.at("ny")};
        break;
      }
    par["calculix_sze_runs"] = psze.at("runs").size();
    par["calculix_sze_command"] = psze.value("command", "");

    // Hybrid plate static: ours and CalculiX's coarsest meshes within 1 % of the converged
    // CalculiX tips.
    const nlohmann::json pref = read_json(plate_reference, "--plate-reference");
    const auto& tips = pref.at("static").at("tips_y");
    double ours_plate = NAN;
    for (int n : plate_meshes) {
      fv::HybridPlateOptions o;
      o.case_file = case_file;
      o.reference = plate_reference;
      o.nx = o.nz = n;
      o.tolerance = accuracy;
      const auto t0 = std::chrono::steady_clock::now();
      const finverse::Summary r = fv::run_hybrid_plate_static(o);
      const double t = seconds_since(t0);
      par["finverse_plate"].push_back({{"n", n}, {"wall_s", t}, {"max_error", worst_error(r)}});
      std::cerr << "finverse hybrid plate " << n << "x" << n << ": " << t << " s, max error "
                << worst_error(r) << "\n";
      for (const auto& m : r.metrics())
        if (m.reference) std::cerr << "  " << m.name << " " << m.value << " (CalculiX " << *m.reference << ")\n";
      if (r.pass()) {
        ours_plate = t;
        par["finverse_plate_mesh"] = n;
        break;
      }
    }
    const nlohmann::json pplate = read_json(peer_plate, "--peer-plate");
    double peer_plate_t = NAN;
    for (const auto& r : pplate.at("runs")) {
      if (r.at("analysis") != "static") continue;
      double e = 0;
      for (const auto& [name, u] : r.at("series").back().at("u").items())
        e = std::max(e, std::abs(u.at(1).get<double>() - tips.at(name).get<double>()) /
                            std::abs(tips.at(name).get<double>()));
      par["calculix_plate"].push_back({{"n", r.at("nx")}, {"wall_s", r.at("wall_s")}, {"max_error", e}});
      if (e <= accuracy && std::isnan(peer_plate_t)) {
        peer_plate_t = r.at("wall_s").get<double>();
        par["calculix_plate_mesh"] = r.at("nx");
      }
    }
    par["calculix_plate_command"] = pplate.value("command", "");

    const std::string src = "issue 3: finverse <= 0.5 x CalculiX, same machine, same run";
    s.info("sze_finverse_seconds", ours_sze, "s");
    s.info("sze_calculix_seconds", peer_sze_t, "s");
    s.at_most("sze_time_ratio", ours_sze / peer_sze_t, goal, src);
    s.info("plate_finverse_seconds", ours_plate, "s");
    s.info("plate_calculix_seconds", peer_plate_t, "s");
    s.at_most("plate_time_ratio", ours_plate / peer_plate_t, goal, src);

    // Newton-iteration cost against DOFs.
    const fv::HybridPlateCase c = fv::read_hybrid_plate_case(case_file);
    const auto pts = fv::newton_scaling(c, scaling, finverse::fem::SolverBackend::cholmod);
    for (const auto& p : pts) {
      par["newton_scaling"].push_back({{"n", p.n}, {"free_dofs", p.free_dofs}, {"iterations", p.iterations},
                                       {"seconds_per_iteration", p.seconds_per_iteration}});
      std::cerr << "newton scaling " << p.n << "x" << p.n << ": " << p.free_dofs << " DOFs, "
                << p.seconds_per_iteration << " s per iteration\n";
    }
    s.info("largest_dofs", pts.empty() ? 0.0 : pts.back().free_dofs);
    s.info("seconds_per_iteration_at_largest", pts.empty() ? NAN : pts.back().seconds_per_iteration, "s");
    s.info("newton_iteration_growth_exponent", fv::growth_exponent(pts));
    s.set_timing(seconds_since(start), finverse::cli::threads_in_use());
    s.write(json_out);
    for (const auto& m : s.metrics())
      std::cerr << "  " << m.name << " = " << m.value << "\n";
    return s.pass() ? 0 : 1;
  });
}
