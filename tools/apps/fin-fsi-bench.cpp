// fin-fsi-bench: results/bench/fsi.json (issue 32 "Benchmark") from the summaries of the fin-fsi
// turek_hron runs that rules/bench.smk makes (FSI2 and FSI3 restarted on their limit cycle with
// Aitken and IQN-ILS, and the FSI3 flow with the flag held rigid); tools/fsi/validation/
// fsi_bench.hpp. Exit 0 when every goal is met, 1 when one is missed, 2 on error.
//
//   fin-fsi-bench --fsi3-iqn-ils a.json --fsi3-aitken b.json --fsi2-iqn-ils c.json
//       --fsi2-aitken d.json --fsi3-rigid e.json [--fin-coupled f.json --fin-flow g.json] --out results/bench/fsi.json
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "core/cli.hpp"
#include "core/summary_print.hpp"
#include "fsi/validation/fsi_bench.hpp"

int main(int argc, char** argv) {
  CLI::App app{"fin-fsi-bench: coupling iterations and coupled-step cost of Turek-Hron FSI2/FSI3"};
  finverse::cli::Standard standard(app, "fin-fsi-bench");
  finverse::fsi::validation::FsiBenchInputs in;
  std::string out;
  app.add_option("--fsi3-iqn-ils", in.fsi3_iqn_ils, "summary.json of the FSI3 restart with IQN-ILS")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--fsi3-aitken", in.fsi3_aitken, "... with Aitken")->required()->check(CLI::ExistingFile);
  app.add_option("--fsi2-iqn-ils", in.fsi2_iqn_ils, "... FSI2 with IQN-ILS")->required()->check(CLI::ExistingFile);
  app.add_option("--fsi2-aitken", in.fsi2_aitken, "... FSI2 with Aitken")->required()->check(CLI::ExistingFile);
  app.add_option("--fsi3-rigid", in.fsi3_rigid, "... the FSI3 flow with the flag held rigid")
      ->required()
      ->check(CLI::ExistingFile);
  auto* fin_coupled = app.add_option("--fin-coupled", in.fin_coupled, "fin-fsi fin's summary.json (the fsi stage's run)")
                          ->check(CLI::ExistingFile);
  auto* fin_flow = app.add_option("--fin-flow", in.fin_flow, "fin-cfd fin's summary.json on the same grid (the flow alone)")
                       ->check(CLI::ExistingFile);
  fin_coupled->needs(fin_flow);
  fin_flow->needs(fin_coupled);
  app.add_option("--out", out, "fsi.json to write")->required();
  return finverse::cli::run(app, standard, argc, argv, [&]() -> int {
    const finverse::Summary b = finverse::fsi::validation::fsi_bench(in);
    b.write(out);
    finverse::print_metrics(b, std::cerr);
    std::cerr << "fin-fsi-bench: " << (b.pass() ? "every goal met" : "a goal missed") << ", wrote " << out << "\n";
    return b.pass() ? 0 : 1;
  });
}
