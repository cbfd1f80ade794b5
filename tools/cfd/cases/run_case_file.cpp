// Case files to subcommands, and the flow case's run; see run_case_file.hpp.
#include "cfd/cases/run_case_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cfd/cases/case_file.hpp"
#include "cfd/cases/flow_case_report.hpp"
#include "core/cli.hpp"
#include "core/error.hpp"
#include "core/log.hpp"

namespace finverse::cfd::cases {

namespace {
namespace fs = std::filesystem;

std::string fmt(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}
}  // namespace

std::vector<std::string> expand_case_file(
    std::vector<std::string> args,
    const std::function<std::optional<std::vector<std::string>>(const std::string& name)>& flags_of) {
  const auto run = std::find(args.begin() + 1, args.end(), "run");
  if (run == args.end() || run + 1 == args.end()) return args;
  const bool coarse = std::find(args.begin(), run, "--coarse") != run;
  const fs::path file = *(run + 1);
  // Not a file (a flag's value that reads "run", or a missing file): the parser reports it.
  if (!fs::is_regular_file(file)) return args;
  const CaseFile cf = read_case_file(file, coarse);
  if (cf.kind == "flow") return args;
  const auto known = flags_of(cf.kind);
  if (!known) throw Error(file.string() + ": case: '" + cf.kind + "' is neither flow nor a validation case");
  for (const std::string& a : cf.arguments)
    if (a.rfind("--", 0) == 0 && std::find(known->begin(), known->end(), a) == known->end()) {
      std::string key = a.substr(2);  // as the file writes it
      std::replace(key.begin(), key.end(), '-', '_');
      throw Error(file.string() + ": " + key + ": not an option of case " + cf.kind);
    }
  std::vector<std::string> out(args.begin(), run);
  out.push_back(cf.kind);
  out.insert(out.end(), cf.arguments.begin(), cf.arguments.end());
  out.insert(out.end(), run + 2, args.end());
  return out;
}

int run_flow_case_file(const fs::path& file, bool coarse, const fs::path& out_dir) {
  const CaseFile cf = read_case_file(file, coarse);
  const auto& spec = cf.flow;
  // Expected steps: dt ~ cfl h / (1.6 U), the fastest flow past a bluff body, or time.dt_max.
  double dt = spec.cfl * spec.h / (1.6 * spec.reference_speed);
  if (spec.dt_max > 0) dt = std::min(dt, spec.dt_max);
  const double steps = spec.t_end / dt;
  log::Progress progress(spec.name + " step", static_cast<std::size_t>(std::ceil(steps)));
  FlowCaseResult r;
  try {
    r = run_flow_case(spec, [&](const StepStats& st, double cx) {
      progress.update(static_cast<std::size_t>(st.step), "t " + fmt("%.4f", st.time) + "  C_x " + fmt("%.4f", cx) +
                                                             "  Poisson " + std::to_string(st.poisson_iterations) +
                                                             " it");
    });
  } catch (const Error& e) {
    // The solver's message names the step and the measure; the file names the case.
    throw Error(file.string() + ": " + e.what());
  }
  progress.finish("t " + fmt("%.4f", r.time.back()));
  const fs::path dir = out_dir / spec.name;
  fs::create_directories(dir);
  write_force_history(dir / "forces.csv", spec, r);
  Summary s = flow_case_summary(spec, r);
  s.parameters()["case_file"] = file.string();
  s.set_timing(r.cpu_seconds, cli::threads_in_use());
  s.write(dir / "summary.json");
  log::info(spec.name + ": " + std::to_string(r.cells[0]) + " x " + std::to_string(r.cells[1]) + " x " +
            std::to_string(r.cells[2]) + " cells, " + std::to_string(r.steps) + " steps; wrote " +
            (dir / "summary.json").string() + " and forces.csv");
  return kExitOk;
}

}  // namespace finverse::cfd::cases
