// fin-fem: runs the structural FEM validation cases (DESIGN.md section 6) and writes
// <out-dir>/<case>/summary.json. Exit code 0 when every metric passes, 1 when one misses,
// 2 on error.
//
//   fin-fem elastica_beam --reference data/reference/structures.json
//   fin-fem cantilever_vibration
//   fin-fem sze_end_shear --reference data/reference/structures.json
//   fin-fem turek_hron_csm3 --reference data/reference/turek_hron.json --coarse
//   fin-fem hybrid_plate_static --case data/cases/hybrid_plate.json
//       --reference data/reference/hybrid_plate_calculix.json
//   fin-fem hybrid_plate_dynamic --case data/cases/hybrid_plate_small_heave.json
//       --reference data/reference/hybrid_plate_calculix.json --nx 32 --nz 32 [--history w.csv]
//
// File-driven mode (tools/fem/io/file_run.hpp): a structural run from stage files, writing the
// node positions over time in the finverse/motion schema plus a ParaView series; exit 0 or 2.
//   fin-fem run --mesh mesh.h5 --materials materials.json --loads loads.h5 --motion motion.h5
//       --analysis quasi_static --out response.h5 [--pvd response.pvd] [--effects effects.json]
//   fin-fem run --mesh mesh.h5 --materials M.json --root-drive drive.json --analysis dynamic
//       --periods 1 --frames-per-period 40 --out response.h5     (in vacuo, the analytic drive)
// (--loads also takes nodal_loads.h5: a structural load case without flow fields)
//   fin-fem effects [--check effects.json]   the candidate effects (tools/fem/effects) / check a list
//   fin-fem loads --mesh mesh.h5 --root-drive drive.json --periods 2 --frames-per-period 20
//       --out loads.h5      quasi-steady loads of the drive's rigid motion (fem/io/quasi_steady_loads.hpp)
#include <CLI/CLI.hpp>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <string>
#include <utility>

#include "core/cli.hpp"
#include "core/summary.hpp"
#include "fem/effects/structural_effect.hpp"
#include "fem/validation/cases.hpp"
#include "fem/validation/hybrid_plate.hpp"
#include "fem/validation/shell_cases.hpp"
#include "fem/validation/turek_hron_csm.hpp"
#include "fem_file_commands.hpp"

namespace {

namespace fv = finverse::fem::validation;
namespace fio = finverse::fem::io;

// Writes <out-dir>/<case>/summary.json with the run's timing and prints the metrics; exit code 0
// when every graded metric passes, 1 otherwise.
int finish(finverse::Summary summary, const std::string& name, const std::filesystem::path& out_dir,
           double wall_seconds) {
  summary.set_timing(wall_seconds, finverse::cli::threads_in_use());
  const auto path = out_dir / name / "summary.json";
  std::filesystem::create_directories(path.parent_path());
  summary.write(path);
  for (const auto& m : summary.metrics()) {
    std::cerr << "  " << m.name << " = " << m.value;
    if (m.reference) std::cerr << " (reference " << *m.reference << ", error " << m.error() << ")";
    if (auto p = m.pass()) std::cerr << (*p ? "  pass" : "  FAIL");
    std::cerr << "\n";
  }
  std::cerr << "fin-fem " << name << ": " << (summary.pass() ? "pass" : "FAIL") << ", " << wall_seconds
            << " s, wrote " << path.string() << "\n";
  return summary.pass() ? 0 : 1;
}

// The beam cases' subcommands: the elastica (static, large deflection) and the cantilever's
// vibration (frequencies and energy drift).
std::pair<CLI::App*, CLI::App*> add_beam_cases(CLI::App& app, fv::ElasticaOptions& elastica,
                                               fv::VibrationOptions& vibration, std::string& reference) {
  auto* el = app.add_subcommand("elastica_beam", "cantilever under a dead tip load, PL^2/EI = 1..20");
  el->add_option("--reference", reference, "structures.json with elastica_tip_load")->required();
  el->add_option("--elements", elastica.elements, "beam elements")->capture_default_str();
  auto* vib = app.add_subcommand("cantilever_vibration",
                                 "first three bending frequencies and energy drift of a cantilever");
  vib->add_option("--elements", vibration.elements, "beam elements")->capture_default_str();
  vib->add_option("--steps-per-period-spectrum", vibration.steps_per_period_spectrum,
                  "time steps per first-mode period in the spectral run")
      ->capture_default_str();
  vib->add_option("--periods-spectrum", vibration.periods_spectrum,
                  "first-mode periods simulated for the spectrum")
      ->capture_default_str();
  vib->add_option("--steps-per-period-energy", vibration.steps_per_period_energy,
                  "time steps per first-mode period in the energy run")
      ->capture_default_str();
  vib->add_option("--periods-energy", vibration.periods_energy,
                  "first-mode periods simulated for the energy drift")
      ->capture_default_str();
  return {el, vib};
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fin-fem: structural FEM validation cases (corotational beams, Newton, generalized-alpha)"};
  finverse::cli::Standard standard(app, "fin-fem");
  app.require_subcommand(1);
  std::string out_dir = "results/validation";
  std::string solver = "cholmod";
  app.add_option("--out-dir", out_dir, "directory that receives <case>/summary.json")->capture_default_str();
  app.add_option("--solver", solver, "sparse solver: cholmod or simplicial_ldlt")->capture_default_str();

  fv::ElasticaOptions elastica;
  fv::VibrationOptions vibration;
  std::string reference;
  // cantilever_vibration is the case run when no other subcommand was given.
  auto* el = add_beam_cases(app, elastica, vibration, reference).first;

  // Shell cases (corotational triangle) and the Turek-Hron CSM flag (plane-strain Q9 solid).
  fv::SzeEndShearOptions shear;
  fv::SzeEndMomentOptions moment;
  fv::SzeHemisphereOptions hemisphere;
  fv::ElasticaShellOptions elastica_shell;
  fv::CsmStaticOptions csm1, csm2;
  csm2.case_number = 2;
  fv::Csm3Options csm3;
  bool coarse = false;
  auto with_reference = [&](const char* name, const char* description, const char* what) {
    auto* sc = app.add_subcommand(name, description);
    sc->add_option("--reference", reference, what)->required();
    return sc;
  };
  auto* sh = with_reference("sze_end_shear", "Sze shell strip under end shear, 10 load levels",
                            "structures.json with sze_cantilever_end_shear");
  sh->add_option("--nx", shear.nx, "cells along the strip")->capture_default_str();
  sh->add_option("--ny", shear.ny, "cells across the strip")->capture_default_str();
  auto* mo = with_reference("sze_end_moment", "Sze shell strip rolled into a circle by an end moment",
                            "structures.json with sze_cantilever_end_moment");
  mo->add_option("--nx", moment.nx, "cells along the strip")->capture_default_str();
  mo->add_option("--ny", moment.ny, "cells across the strip")->capture_default_str();
  auto* he = with_reference("sze_hemisphere", "Sze open hemisphere under point loads, quarter model",
                            "structures.json with sze_open_hemisphere");
  he->add_option("--n-meridian", hemisphere.n_meridian, "cells along the meridian")->capture_default_str();
  he->add_option("--n-circumference", hemisphere.n_circumference, "cells around")->capture_default_str();
  auto* es = with_reference("elastica_shell", "elastica computed with a shell strip",
                            "structures.json with elastica_tip_load");
  es->add_option("--nx", elastica_shell.nx, "cells along the strip")->capture_default_str();
  auto* c1 = with_reference("turek_hron_csm1", "Turek-Hron CSM1: static flag under gravity, E = 1.4 MPa",
                            "turek_hron.json");
  auto* c2 = with_reference("turek_hron_csm2", "Turek-Hron CSM2: static flag under gravity, E = 5.6 MPa",
                            "turek_hron.json");
  auto* c3 = with_reference("turek_hron_csm3", "Turek-Hron CSM3: flag released under gravity, generalized-alpha",
                            "turek_hron.json");
  for (auto* sc : {c1, c2, c3}) sc->add_flag("--coarse", coarse, "the CI variant (coarser meshes, one time step)");

  // Hybrid plate (seed paper sec. 3.4) against the CalculiX reference.
  fv::HybridPlateOptions hybrid;
  auto* hs = with_reference("hybrid_plate_static", "hybrid plate under a dead pressure vs CalculiX",
                            "hybrid_plate_calculix.json (calculix_hybrid_plate.py --reference-out)");
  auto* hd = with_reference("hybrid_plate_dynamic", "hybrid plate heaved at the leading edge vs CalculiX",
                            "hybrid_plate_calculix.json (calculix_hybrid_plate.py --reference-out)");
  std::string hybrid_case;
  for (auto* sc : {hs, hd}) {
    sc->add_option("--case", hybrid_case, "data/cases/hybrid_plate.json")->required();
    sc->add_option("--nx", hybrid.nx, "cells along the chord")->capture_default_str();
    sc->add_option("--nz", hybrid.nz, "cells along the span")->capture_default_str();
  }
  hd->add_option("--periods", hybrid.periods, "heave periods simulated (0: the case's)")->capture_default_str();
  hd->add_option("--time-step", hybrid.time_step, "time step (0: the case's)")->capture_default_str();
  std::string hybrid_history;
  hd->add_option("--history", hybrid_history, "also write the tip histories (ours and CalculiX's) to this CSV");

  finverse::apps::FemRunCommand run_command;
  run_command.add(app);

  std::string effects_check;
  auto* ef = app.add_subcommand("effects", "list the candidate effects (names, parameters, ranges) as JSON, or check a list");
  ef->add_option("--check", effects_check, "effects JSON list to check (unknown name or value out of range: exit 2)");

  fio::FileLoadsOptions qs;
  auto* ld = finverse::apps::add_fem_loads_command(app, qs);

  return finverse::cli::run(app, standard, argc, argv, [&]() -> int {
    if (*ld) {
      const double largest = fio::write_quasi_steady_loads(qs, finverse::cli::effective_config(app));
      std::cerr << "fin-fem loads: largest nodal force " << largest << " N, wrote " << qs.out.string() << "\n";
      return 0;
    }
    if (*ef) {  // the candidate effects, or a list checked
      const auto out = effects_check.empty()
                           ? finverse::fem::effects_catalogue()
                           : finverse::fem::effects_to_json(finverse::fem::read_effects(effects_check));
      std::cout << out.dump(2) << "\n";
      return 0;
    }
    const auto start = std::chrono::steady_clock::now();
    const auto backend = finverse::fem::parse_solver_backend(solver);
    if (*run_command.rn) return run_command.execute(backend, finverse::cli::effective_config(app));
    auto seconds = [&] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    auto configure = [&](auto& options) {
      options.reference = reference;
      options.backend = backend;
      return options;
    };
    // The case runs first, then the clock is read: the order in which function arguments are
    // evaluated is unspecified.
    auto summary = [&]() -> finverse::Summary {
      if (*el) return fv::run_elastica(configure(elastica));
      if (*sh) return fv::run_sze_end_shear(configure(shear));
      if (*mo) return fv::run_sze_end_moment(configure(moment));
      if (*he) return fv::run_sze_hemisphere(configure(hemisphere));
      if (*es) return fv::run_elastica_shell(configure(elastica_shell));
      if (*c1 || *c2) {
        auto& o = *c1 ? csm1 : csm2;
        o.coarse = coarse;
        return fv::run_turek_hron_csm_static(configure(o));
      }
      if (*hs || *hd) {
        hybrid.case_file = hybrid_case;
        hybrid.history = hybrid_history;
        configure(hybrid);
        return *hs ? fv::run_hybrid_plate_static(hybrid) : fv::run_hybrid_plate_dynamic(hybrid);
      }
      if (*c3) {
        csm3.coarse = coarse;
        return fv::run_turek_hron_csm3(configure(csm3));
      }
      vibration.backend = backend;
      return fv::run_cantilever_vibration(vibration);
    }();
    const double wall = seconds();
    return finish(std::move(summary), app.get_subcommands().front()->get_name(), out_dir, wall);
  });
}
