// The fin run's checkpoint write, read and configuration check (see fin_flow_checkpoint.hpp).
#include "cfd/io/fin_flow_checkpoint.hpp"

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "cfd/io/flow_checkpoint.hpp"
#include "core/error.hpp"
#include "core/sha256.hpp"

namespace finverse::cfd::io {

namespace {

// Raw bytes of trivially copyable values, appended in a fixed order for the fingerprint.
template <class T>
void append(std::string& bytes, const T* data, std::size_t count) {
  const std::size_t n = count * sizeof(T);
  const std::size_t at = bytes.size();
  bytes.resize(at + n);
  if (n) std::memcpy(bytes.data() + at, data, n);
}
template <class T>
void append(std::string& bytes, const std::vector<T>& v) {
  const auto n = static_cast<std::uint64_t>(v.size());
  append(bytes, &n, 1);
  append(bytes, v.data(), v.size());
}
void append(std::string& bytes, double v) { append(bytes, &v, 1); }

}  // namespace

std::string fin_input_fingerprint(const FinInput& in) {
  std::string b;
  append(b, in.rest);
  append(b, in.mid_triangles);
  append(b, in.frame_time);
  append(b, in.layout.wrap.value_or(-1.0));
  append(b, in.period.value_or(-1.0));
  append(b, in.chord.value_or(-1.0));
  append(b, in.reference_area);
  const ThinBody& body = in.motion->body();
  append(b, body.triangles);
  append(b, body.source_node);
  append(b, body.offset_sign);
  append(b, body.thickness);
  append(b, static_cast<double>(body.normal_sign));
  append(b, static_cast<double>(body.node_count));
  for (double t : in.frame_time) append(b, in.motion->mid_surface(t).x);
  return sha256_hex(b);
}

nlohmann::json fin_flow_config(const FinFlowOptions& o, const FinInput& in) {
  nlohmann::json opt = {{"--reynolds", o.reynolds},
                        {"--speed", o.speed},
                        {"--viscosity", o.viscosity},
                        {"--rho", o.rho},
                        {"--chord", o.chord},
                        {"--cells-per-chord", o.cells_per_chord},
                        {"--core-margin", o.core_margin},
                        {"--wake", o.wake},
                        {"--upstream", o.upstream},
                        {"--downstream", o.downstream},
                        {"--lateral", o.lateral},
                        {"--spanwise", o.spanwise},
                        {"--stretch-ratio", o.stretch_ratio},
                        {"--cfl", o.cfl},
                        {"--periods", o.periods},
                        {"--output-periods", o.output_periods},
                        {"--output-interval", o.output_interval},
                        {"--poisson-rtol", o.poisson_rtol},
                        {"--staircase-balance", !o.cut_cells},
                        {"--sample-loads", o.sample_loads}};
  // The sheet's options only when it is used, so a closed-body run's configuration is as before.
  if (o.surface != "closed") {
    opt["--surface"] = o.surface;
    opt["--kernel"] = o.kernel;
    opt["--marker-spacing"] = o.marker_spacing;
    opt["--raw-sheet-force"] = o.raw_sheet_force;
    opt["--sheet-loads-mean"] = o.sheet_loads_mean;
  }
  if (o.motion_harmonics > 0) opt["--motion-harmonics"] = o.motion_harmonics;
  return {{"case", "fin"}, {"options", opt}, {"input", fin_input_fingerprint(in)}};
}

void check_fin_restart(const std::filesystem::path& file, const nlohmann::json& now) {
  const std::string where = file.string() + ": cannot restart: ";
  nlohmann::json stored;
  try {
    stored = nlohmann::json::parse(checkpoint_config(file));
  } catch (const nlohmann::json::exception&) {
    throw Error(where + "the root attribute config is not JSON");
  }
  if (!stored.is_object() || stored.value("case", std::string()) != "fin")
    throw Error(where + "not a checkpoint of fin-cfd fin (config case = " +
                (stored.is_object() && stored.contains("case") ? stored["case"].dump() : std::string("none")) + ")");
  for (const auto& [flag, value] : now["options"].items()) {
    const auto& s = stored["options"];
    if (!s.contains(flag)) throw Error(where + "the checkpoint does not record " + flag);
    if (s[flag] != value)
      throw Error(where + "it was written with " + flag + " " + s[flag].dump() + ", this run has " + flag + " " +
                  value.dump());
  }
  if (stored.value("input", std::string()) != now["input"].get<std::string>())
    throw Error(where + "it was written for different inputs (mesh/motion fingerprint " +
                stored.value("input", std::string("none")).substr(0, 12) + "..., these inputs " +
                now["input"].get<std::string>().substr(0, 12) + "...)");
}

void write_fin_checkpoint(const std::filesystem::path& path, const FlowSolver& solver, const nlohmann::json& config,
                          const FinRunCounters& c, const LoadsRecord& r, const LoadsWindow& w) {
  write_checkpoint(path, solver, config.dump(),
                   {{"counters", {static_cast<double>(c.step), static_cast<double>(c.poisson_iterations), c.max_cfl}},
                    {"loads_time", r.times()},
                    {"loads_nodal_force", r.nodal()},
                    {"loads_force_total", r.totals()},
                    {"loads_pressure_jump", r.jumps()},
                    {"loads_window", w.state()}});
}

FinRunCounters read_fin_checkpoint(const std::filesystem::path& path, FlowSolver& solver, const nlohmann::json& config,
                                   LoadsRecord& r, LoadsWindow& w) {
  check_fin_restart(path, config);
  std::vector<StateArray> run = {{"counters", {}},
                                 {"loads_time", {}},
                                 {"loads_nodal_force", {}},
                                 {"loads_force_total", {}},
                                 {"loads_pressure_jump", {}},
                                 {"loads_window", {}}};
  read_checkpoint(path, solver, &run);
  if (run[0].values.size() != 3) throw Error(path.string() + ": dataset run/counters missing or not of 3 values");
  FinRunCounters c;
  c.step = std::lround(run[0].values[0]);
  c.poisson_iterations = std::lround(run[0].values[1]);
  c.max_cfl = run[0].values[2];
  if (c.step != solver.steps())
    throw Error(path.string() + ": run/counters step " + std::to_string(c.step) + " differs from the solver's " +
                std::to_string(solver.steps()));
  try {
    r.restore(std::move(run[1].values), std::move(run[2].values), std::move(run[3].values), std::move(run[4].values));
    w.restore(run[5].values);
  } catch (const Error& e) {
    throw Error(path.string() + ": " + e.what());
  }
  return c;
}

}  // namespace finverse::cfd::io
