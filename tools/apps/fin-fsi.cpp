// fin-fsi: coupled flow-structure runs (issue 32; DESIGN.md 5.3). Parses flags, calls the library
// (tools/fsi/validation), writes fsi.h5 and summary.json. Exit 0 when every graded metric passes,
// 1 when one misses, 2 on error (bad input, a diverged coupling naming the step).
//
//   fin-fsi turek_hron --case FSI1 --reference data/reference/turek_hron.json
//       --acceleration iqn-ils --cells-per-diameter 16 --out fsi.h5 --summary summary.json
//       [--checkpoint ckpt.h5 --checkpoint-every N] [--restart ckpt.h5 [--restart-new-coupling]]
//   fin-fsi --threads N fin --mesh mesh.h5 --materials (M.json | materials.h5 [--base-materials M.json])
//       (--root-drive drive.json | --motion motion.h5) --out fsi.h5 [fin-cfd fin's flow flags]
//       [--effects effects.json]
//       [--periods P --output-periods 1] [--summary s.json]
//   fin-fsi hessenthaler_plane --reference data/reference/hessenthaler2017.json --youngs-modulus E
//       --out-dir DIR [--name N]   (issue 34: the Phase I flow, plane version only)
//   fin-fsi flap --flow junction_flow.yaml --reference hessenthaler2017.json --centreline
//       phaseI_centreline.csv --youngs-modulus E [--h 0.002] [--loads flap_loads.h5]   (issue 49: 3-D)
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "cfd/io/fin_flow_case.hpp"
#include "core/atomic_file.hpp"
#include "core/cli.hpp"
#include "flow_ranks_launch.hpp"
#include "summary_command.hpp"
#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "core/provenance.hpp"
#include "core/stage_identity.hpp"
#include "fem/io/material_spec.hpp"
#include "fem/io/root_drive_file.hpp"
#include "fsi/fin_fsi_flags.hpp"
#include "fsi/fin_fsi_run.hpp"
#include "core/summary.hpp"
#include "core/summary_print.hpp"
#include "fsi/validation/case_flags.hpp"
#include "fsi/validation/seed_table1.hpp"
#ifdef FINVERSE_FSI_HAS_FIT
#include "fit/fin_parameters.hpp"
#endif


namespace {

namespace fv = finverse::fsi::validation;

// fin-fsi turek_hron: the 2-D flag behind the cylinder (FSI1, FSI2, FSI3). One block per
// subcommand: its options, then what it runs.
struct TurekHronCommand {
  fv::TurekHronFsiOptions o;
  std::string reference, out, summary_path;
  bool strict = false;
  bool iterations = false;
  CLI::App* th = nullptr;

  void add(CLI::App& app) {
    th = app.add_subcommand("turek_hron", "Turek-Hron FSI1 (steady), FSI2, FSI3 (periodic)");
    th->add_option("--reference", reference, "turek_hron.json")->required();
    fv::add_turek_hron_flags(*th, o);
    th->add_option("--out", out, "fsi.h5 to write (optional)");
    th->add_option("--summary", summary_path, "summary.json to write")->required();
    th->add_flag("--strict", strict, "stop at the iteration cap (default: accept the best iterate)");
    th->add_flag("--iterations", iterations, "a progress line per coupling iteration too");
  }

  int run() {
    o.reference = reference;
    o.fsi_h5 = out;
    o.progress = [](const std::string& line) { std::cerr << line << "\n"; };
    o.progress_iterations = iterations;
    o.accept_at_cap = !strict;
    fv::TurekHronFsiRun run = fv::run_turek_hron_fsi(o);
    finverse::Summary& s = run.summary;
    s.set_timing(run.wall_seconds, finverse::cli::threads_in_use());
    s.write(summary_path);
    finverse::print_metrics(s, std::cerr);
    std::ifstream reference_file(reference);
    for (const auto& line : fv::seed_table1_lines(nlohmann::json::parse(reference_file), o.case_name, s))
      std::cerr << line << "\n";
    std::cerr << "fin-fsi turek_hron " << o.case_name << ": " << (s.pass() ? "pass" : "missed") << ", "
              << run.wall_seconds << " s, wrote " << summary_path << "\n";
    return s.pass() ? 0 : 1;
  }
};

// fin-fsi pitching_plate: the 3-D flexible plate pitching about its leading edge (seed sec. 3.2),
// every K of --K in one run (and --rigid), one summary.json.
struct PitchingPlateCommand {
  fv::PitchingPlateOptions o;
  std::string summary_path;
  CLI::App* pp = nullptr;

  void add(CLI::App& app) {
    pp = app.add_subcommand("pitching_plate", "flexible plate pitching in a stream (W/L 0.54, 12 deg, f = 1)");
    fv::add_pitching_plate_flags(*pp, o);
    pp->add_option("--summary", summary_path, "summary.json to write")->required();
  }

  int run() {
    o.progress = [](const std::string& line) { std::cerr << line << "\n"; };
    fv::PitchingPlateRun run = fv::run_pitching_plate(o);
    finverse::Summary& s = run.summary;
    s.set_timing(run.wall_seconds, finverse::cli::threads_in_use());
    s.write(summary_path);
    finverse::print_metrics(s, std::cerr);
    std::cerr << "fin-fsi pitching_plate: " << (s.pass() ? "pass" : "missed") << ", " << run.wall_seconds
              << " s, wrote " << summary_path << "\n";
    return s.pass() ? 0 : 1;
  }
};

// fin-fsi fin: the fin's coupled run from mesh.h5, its materials and a root drive (analytic or
// the tracked root motion) to fsi.h5 (tools/fsi/fin_fsi_run.hpp).
struct FinCommand {
  finverse::fsi::FinFsiOptions o;
  std::string mesh, materials, base_materials, root_drive, motion, out, summary_path, effects;
  CLI::App* fin = nullptr;

  void add(CLI::App& app) {
    fin = app.add_subcommand("fin", "the fin's coupled flow-structure run (mesh, materials, root drive -> fsi.h5)");
    fin->add_option("--mesh", mesh, "mesh.h5 (fin-mesh)")->required()->check(CLI::ExistingFile);
    fin->add_option("--materials", materials, "materials JSON (fin-fem) or materials.h5 (fin-fit: its best values)")
        ->required()
        ->check(CLI::ExistingFile);
    fin->add_option("--base-materials", base_materials,
                    "with a materials.h5: the materials JSON fin-fit started from (default: the one its config names)")
        ->check(CLI::ExistingFile);
    fin->add_option("--effects", effects, "candidate effects the structure runs with: JSON list (tools/fem/effects)");
    auto* rd = fin->add_option("--root-drive", root_drive, "root drive JSON (heave + per-ray pitch)")
                   ->check(CLI::ExistingFile);
    auto* mo = fin->add_option("--motion", motion, "motion.h5: drive the root by its tracked root motion (per ray)")
                   ->check(CLI::ExistingFile);
    rd->excludes(mo);
    fin->add_option("--out", out, "fsi.h5 to write")->required();
    fin->add_option("--summary", summary_path, "also write a summary JSON (C_T, TE excursion, iterations, timing)");
    o.flow.output_interval = 0;
    for (const auto& n : finverse::cfd::io::fin_flow_flags(o.flow))
      fin->add_option(n.flag, *n.value, n.help)->capture_default_str();
    finverse::fsi::add_fin_fsi_flags(*fin, o);
  }

  // The base materials JSON of a materials.h5: --base-materials, else the "materials" entry of
  // its config (fin-fit's effective flags).
  std::string base_of(const std::string& h5) const {
    if (!base_materials.empty()) return base_materials;
    const auto f = finverse::h5::File::open_read(h5);
    const auto config = f.attr_string(".", "config");
    std::string found;
    if (config) {
      const std::function<void(const nlohmann::json&)> walk = [&](const nlohmann::json& j) {
        if (!j.is_object()) return;
        for (const auto& [k, v] : j.items()) {
          if (k == "materials" && v.is_string() && found.empty()) found = v.get<std::string>();
          walk(v);
        }
      };
      walk(nlohmann::json::parse(*config, nullptr, false));
    }
    if (found.empty() || !std::filesystem::exists(found))
      throw finverse::Error(h5 + ": config names no readable base materials file (" + found +
                            "); give --base-materials M.json");
    return found;
  }

  int run() {
    namespace fs = finverse::fsi;
    fs::FinFsiInputs in;
    in.mesh = finverse::stage::read<finverse::stage::Mesh>(mesh);
    in.mesh_name = mesh;
    in.materials_name = materials;
    std::vector<std::filesystem::path> inputs{mesh, materials};
    nlohmann::json materials_config = {{"materials", materials}};
    if (std::filesystem::path(materials).extension() == ".h5") {
#ifdef FINVERSE_FSI_HAS_FIT
      finverse::check_made_from(materials, mesh);
      const std::string base = base_of(materials);
      inputs.push_back(base);
      in.materials = finverse::fem::io::read_material_spec(base);
      const auto fit = finverse::stage::read<finverse::stage::Materials>(materials);
      const Eigen::VectorXd best = Eigen::Map<const Eigen::VectorXd>(fit.best.data.data(),
                                                                     static_cast<Eigen::Index>(fit.best.data.size()));
      const auto factory = std::make_shared<finverse::fit::FinModelFactory>(in.mesh, in.materials, fit.names,
                                                                            finverse::fit::FinDrive{}, mesh);
      in.build_model = [factory, best]() { return std::move(*factory->build(best)); };
      materials_config["base_materials"] = base;
      for (std::size_t k = 0; k < fit.names.size(); ++k) materials_config["fitted"][fit.names[k]] = fit.best.data[k];
#else
      throw finverse::Error(materials + ": a materials.h5 needs the fit area (built without it)");
#endif
    } else {
      in.materials = finverse::fem::io::read_material_spec(materials);
    }
    if (!root_drive.empty()) {
      in.drive = finverse::fem::io::read_root_drive(root_drive);
      inputs.push_back(root_drive);
    } else if (!motion.empty()) {
      finverse::check_made_from(motion, mesh);
      in.motion = finverse::stage::read<finverse::stage::Motion>(motion);
      in.motion_name = motion;
      inputs.push_back(motion);
    } else {
      throw finverse::Error("fin-fsi fin: expected --root-drive drive.json or --motion motion.h5");
    }
    if (!effects.empty()) {
      std::ifstream ein(effects);
      if (!ein) throw finverse::Error(effects + ": cannot open the effects file");
      in.effects = nlohmann::json::parse(ein, nullptr, false);
      if (in.effects.is_discarded()) throw finverse::Error(effects + ": not valid JSON");
      in.effects_name = effects;
      inputs.push_back(effects);
    }
    // On MPI ranks every rank runs the whole coupled step (the pressure solve shared) and rank 0
    // alone speaks and writes files.
    const bool writer = finverse::cli::mpi_launch_rank() == 0;
    o.progress = [writer](const std::string& line) {
      if (writer) std::cerr << line << "\n";
    };
    // As fin-cfd fin: checkpoints go next to --out unless --checkpoint names the file.
    if (o.checkpoint_every > 0 && o.checkpoint.empty())
      o.checkpoint = std::filesystem::path(out).parent_path() / (std::filesystem::path(out).stem().string() + ".checkpoint.h5");
    if (!writer) o.checkpoint.clear(), o.paraview_dir.clear();
    fs::FinFsiResult r = fs::run_fin_fsi(in, o);
    if (!writer) return 0;
    nlohmann::json config = r.config;
    config["inputs"] = materials_config;
    config["threads"] = finverse::cli::threads_in_use();
    finverse::stage::write(out, r.fsi, finverse::Provenance{"fin-fsi", config, inputs});
    nlohmann::json summary = r.summary();
    summary["config"] = config;
    summary["trusted"] = r.steps_at_cap * 20 <= r.steps;  // at most 5 % of the steps at the cap
    if (!summary_path.empty()) finverse::write_text_atomic(summary_path, summary.dump(2) + "\n");
    if (!summary["trusted"].get<bool>())
      std::cerr << "fin-fsi fin: WARNING: " << r.steps_at_cap << " of " << r.steps
                << " steps ended at the coupling cap (best iterate accepted): the result is not converged\n";
    std::cerr << "fin-fsi fin: mean C_T over the last period " << r.ct_mean << ", peak " << r.ct_peak
              << "; trailing-edge peak-to-peak " << r.te_peak_to_peak_mean << " c (rays " << r.te_peak_to_peak_min
              << " .. " << r.te_peak_to_peak_max << "); coupling iterations mean " << r.iterations_mean << ", max "
              << r.iterations_max << "; " << r.wall_seconds << " s, wrote " << out << "\n";
    return 0;
  }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fin-fsi: implicit partitioned flow-structure coupling (Aitken, IQN-ILS)"};
  finverse::cli::Standard standard(app, "fin-fsi");
  standard.mpi = true;  // fin-fsi fin; the other subcommands refuse ranks below
  app.require_subcommand(1);
  TurekHronCommand turek_hron;
  turek_hron.add(app);
  PitchingPlateCommand pitching_plate;
  pitching_plate.add(app);
  FinCommand fin;
  fin.add(app);
  // hessenthaler_plane: the Phase I flow as a 2-D section (a label, not the 3-D experiment).
  SummaryCommand<fv::HessenthalerPlaneOptions> hessenthaler_plane;
  hessenthaler_plane.add(app, "hessenthaler_plane", "Hessenthaler 2017 Phase I flow, plane version (issue 34)",
                         "loop_hessenthaler_phase_I_plane", fv::add_hessenthaler_plane_flags,
                         fv::run_hessenthaler_plane_fsi);
  // flap: Phase I in 3-D, the flap as a sheet in the junction of a case file.
  SummaryCommand<fv::HessenthalerPhaseIOptions> flap;
  flap.add(app, "flap", "Hessenthaler 2017 Phase I in 3-D: the flap in the junction (issue 49)", "flap_phase1",
           fv::add_hessenthaler_phase1_flags, fv::run_hessenthaler_phase1);
  return finverse::cli::run(app, standard, argc, argv, [&]() -> int {
    if (turek_hron.th->parsed()) return turek_hron.run();
    if (pitching_plate.pp->parsed()) return pitching_plate.run();
    if (fin.fin->parsed()) return on_flow_ranks("fin-fsi", [&] { return fin.run(); });
    if (finverse::cli::mpi_launch_size() > 1)
      throw finverse::Error("fin-fsi " + app.get_subcommands().front()->get_name() +
                            " does not run on MPI ranks (fin-fsi fin does); run it without mpirun");
    if (hessenthaler_plane.cmd->parsed()) return hessenthaler_plane.run();
    if (flap.cmd->parsed()) return flap.run();
    return 2;
  });
}
