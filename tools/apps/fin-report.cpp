// fin-report: the report of one case (issue 33 "Deliver" 3): reads the case's stage files, grades
// the scores the present files allow and writes <out-dir>/summary.json and <out-dir>/figures.json
// (the figure data that tools/scripts/report_figures.py turns into PNGs and index.html).
//
//   fin-report --case tiny --truth truth.h5 --kinematics kinematics.h5 --mesh mesh.h5
//              --motion motion.h5 --loads loads.h5 --materials materials.h5
//              --truth-materials data/cases/trout_fin_materials.json [--fsi fsi.h5] [--loop loop.h5]
//              [--scope "what the scores can test"] --out-dir report
// --loop (fin-loop trace's loop.h5, with --mesh) adds the "Closing the loop" section.
// Every input is optional: a section whose file is not given is marked "not available" with the
// missing file named. A given file that does not exist or breaks its contract, or files that
// disagree (loads from another motion, materials for another mesh): one line, exit 2.
#include <cstdio>
#include <filesystem>

#include "core/atomic_file.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/stage_files.hpp"
#include "core/stage_identity.hpp"
#include "fem/io/material_spec.hpp"
#include "report/fin_report.hpp"
#include "report/modulus_scores.hpp"

namespace {

template <class S> void read_if(const std::filesystem::path& p, std::optional<S>& out) {
  if (!p.empty()) out = finverse::stage::read<S>(p);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace finverse;
  CLI::App app{"fin-report: scores and figure data of one case"};
  cli::Standard standard(app, "fin-report");
  std::filesystem::path truth, kinematics, mesh, motion, loads, materials, fsi, loop, truth_materials, out_dir;
  report::ReportInputs in;
  app.add_option("--case", in.case_name, "case name (for the report's title)")->required();
  app.add_option("--truth", truth, "truth.h5 (fin-synth)")->check(CLI::ExistingFile);
  app.add_option("--kinematics", kinematics, "kinematics.h5 (fin-track)")->check(CLI::ExistingFile);
  app.add_option("--mesh", mesh, "mesh.h5 (fin-mesh)")->check(CLI::ExistingFile);
  app.add_option("--motion", motion, "motion.h5 (fin-mesh)")->check(CLI::ExistingFile);
  app.add_option("--loads", loads, "loads.h5 (fin-cfd)")->check(CLI::ExistingFile);
  app.add_option("--materials", materials, "materials.h5 (fin-fit)")->check(CLI::ExistingFile);
  app.add_option("--fsi", fsi, "fsi.h5 (fin-fsi), when the case has one")->check(CLI::ExistingFile);
  app.add_option("--loop", loop, "loop.h5 (fin-loop trace): residual maps, decision trail, errors; needs --mesh")
      ->check(CLI::ExistingFile);
  app.add_option("--truth-materials", truth_materials,
                 "materials file (fin-fem format) of the truth, used when truth.h5 records none")
      ->check(CLI::ExistingFile);
  app.add_option("--chord", in.chord, "chord [m] (default: mesh.h5's chord attribute)");
  app.add_option("--scope", in.scope,
                 "what this case's scores can test, shown above them (e.g. a coarse case: the grading, not the method)");
  app.add_option("--out-dir", out_dir, "directory of summary.json and figures.json")->required();

  return cli::run(app, standard, argc, argv, [&]() -> int {
    read_if(truth, in.truth);
    read_if(kinematics, in.kinematics);
    read_if(mesh, in.mesh);
    read_if(motion, in.motion);
    read_if(loads, in.loads);
    read_if(materials, in.materials);
    read_if(fsi, in.fsi);
    read_if(loop, in.loop);
    in.loop_source = loop.string();
    if (!loop.empty() && mesh.empty()) throw Error("--loop " + loop.string() + ": needs --mesh (the residual maps' planform)");
    // Stages that disagree (issue 33 "Bad input"): each product against the inputs it records.
    const std::vector<std::pair<std::filesystem::path, std::filesystem::path>> made_from{
        {motion, kinematics}, {motion, mesh}, {loads, mesh},      {loads, motion}, {materials, mesh},
        {materials, motion},  {materials, loads}, {fsi, mesh}, {fsi, materials}, {loop, mesh}};
    for (const auto& [product, input] : made_from)
      if (!product.empty() && !input.empty()) check_made_from(product, input);
    if (in.truth && !report::truth_parameters(*in.truth).empty()) {
      in.truth_materials = report::truth_parameters(*in.truth);
      in.truth_materials_source = truth.string() + " (materials)";
    } else if (!truth_materials.empty() && in.materials) {
      in.truth_materials = report::truth_parameters(fem::io::read_material_spec(truth_materials), in.materials->names);
      in.truth_materials_source = truth_materials.string() +
                                  (in.truth ? " (truth.h5 records no materials: its motion is prescribed, so this "
                                              "truth is the case's intended one, not the motion's cause)"
                                            : "");
    }
    const auto r = report::build_report(in);
    std::filesystem::create_directories(out_dir);
    write_text_atomic(out_dir / "figures.json", r.figures.dump() + "\n");
    write_text_atomic(out_dir / "summary.json", report::summary_json(in, r).dump(2) + "\n");
    int met = 0, missed = 0, na = 0;
    for (const auto& s : r.scores)
      met += s.status == report::Status::met, missed += s.status == report::Status::missed,
          na += s.status == report::Status::not_available;
    std::fprintf(stderr, "fin-report: %s: %d met, %d missed, %d not available -> %s\n", in.case_name.c_str(), met,
                 missed, na, (out_dir / "summary.json").c_str());
    return kExitOk;
  });
}
