// fin-diff: compares two output files (or two directories of them) dataset by dataset.
//
//   fin-diff reference.h5 candidate.h5                      default tolerance: exact
//   fin-diff ref.h5 cand.h5 --atol 1e-10 --rtol 1e-8
//   fin-diff tests/regression/mesh/default results/mesh     directory; uses its tolerances.json
//   fin-diff ref.pvd cand.pvd --tolerances tol.json --all   every row, not only the differing ones
//   fin-diff ref.h5 cand.h5 --update                        rewrite the reference from the candidate
//
// Exit status: 0 equal within tolerance, 1 different, 2 error (unreadable file, bad flags).
#include <cstdio>
#include <filesystem>

#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/file_diff.hpp"
#include "core/log.hpp"

int main(int argc, char** argv) {
  using namespace finverse;
  CLI::App app{"fin-diff: compare two finverse output files (HDF5, VTK XML, .pvd) or directories"};
  cli::Standard standard(app, "fin-diff");
  std::filesystem::path reference, candidate, tolerance_file;
  double atol = 0, rtol = 0;
  bool update = false, all = false;
  app.add_option("reference", reference, "reference file or directory")->required();
  app.add_option("candidate", candidate, "candidate file or directory")->required();
  app.add_option("--tolerances", tolerance_file, "JSON tolerance file (default: <reference dir>/tolerances.json if present)");
  app.add_option("--atol", atol, "default absolute tolerance")->check(finverse::cli::non_negative());
  app.add_option("--rtol", rtol, "default relative tolerance")->check(finverse::cli::non_negative());
  app.add_flag("--update", update, "copy the candidate over the reference instead of comparing");
  app.add_flag("--all", all, "print every compared object, not only the differing ones");
  standard.log_level = "warn";  // a comparison prints its table, not a log

  return cli::run(app, standard, argc, argv, [&]() -> int {
    if (update) {
      update_reference(reference, candidate);
      std::printf("fin-diff: reference %s updated from %s\n", reference.c_str(), candidate.c_str());
      return kExitOk;
    }
    Tolerances tol(Tolerance{atol, rtol});
    if (tolerance_file.empty() && std::filesystem::is_directory(reference) &&
        std::filesystem::exists(reference / "tolerances.json"))
      tolerance_file = reference / "tolerances.json";
    if (!tolerance_file.empty()) {
      tol = Tolerances::load(tolerance_file);
      if (app.count("--atol") || app.count("--rtol")) tol.set_default(Tolerance{atol, rtol});
    }
    const auto rows = diff_paths(reference, candidate, tol);
    std::size_t bad = 0;
    for (const auto& r : rows) bad += !r.ok;
    if (bad || all) std::fputs(format_table(rows, all).c_str(), stdout);
    std::printf("fin-diff: %zu object%s compared, %zu different: %s\n", rows.size(), rows.size() == 1 ? "" : "s", bad,
                bad ? "DIFFERENT" : "equal within tolerance");
    return bad ? kExitDifferent : kExitOk;
  });
}
