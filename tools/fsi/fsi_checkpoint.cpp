// Checkpoints of a coupled run; see fsi_checkpoint.hpp.
#include "fsi/fsi_checkpoint.hpp"

#include <map>

#include "cfd/io/flow_checkpoint.hpp"
#include "core/error.hpp"

namespace finverse::fsi {

namespace {

constexpr const char* kKind = "fin-fsi coupled run";
constexpr std::size_t kStatisticsValues = 6;

std::vector<double> values(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

Eigen::VectorXd vector(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

// The names of the `run` arrays, besides the acceleration's, the case's history and the frames'.
const std::vector<std::string>& run_names() {
  static const std::vector<std::string> names = {"coupling_state",         "coupling_previous",  "coupling_input",
                                                 "coupling_counters",  //
                                                 "structure_position",     "structure_rotation", "structure_velocity",
                                                 "structure_acceleration", "structure_time",     "structure_old_terms",
                                                 "structure_scalars",      "structure_load",     "statistics"};
  return names;
}

}  // namespace

void write_fsi_checkpoint(const std::filesystem::path& path, const cfd::FlowSolver& flow, const nlohmann::json& config,
                          const FsiRunState& s) {
  nlohmann::json c = config;
  c["checkpoint_kind"] = kKind;
  std::vector<cfd::StateArray> run;
  const auto add = [&](const std::string& name, std::vector<double> v) { run.push_back({name, std::move(v)}); };
  add("coupling_state", values(s.coupling_state));
  add("coupling_previous", values(s.coupling_previous));
  add("coupling_input", values(s.coupling_input));
  add("coupling_counters", {s.time, static_cast<double>(s.steps)});
  std::vector<double> position, rotation;
  for (const auto& p : s.structure.configuration.position) position.insert(position.end(), p.data(), p.data() + 3);
  for (const auto& r : s.structure.configuration.rotation) rotation.insert(rotation.end(), r.data(), r.data() + 9);
  add("structure_position", std::move(position));
  add("structure_rotation", std::move(rotation));
  add("structure_velocity", values(s.structure.velocity));
  add("structure_acceleration", values(s.structure.acceleration));
  add("structure_time", {s.structure.time});
  add("structure_old_terms", values(s.integrator.old_terms));
  add("structure_scalars", {s.integrator.force_scale, s.integrator.initialized ? 1.0 : 0.0});
  add("structure_load", values(s.interface_load));
  std::vector<double> statistics;
  for (const StepStatistics& t : s.statistics)
    statistics.insert(statistics.end(), {static_cast<double>(t.step), t.time, static_cast<double>(t.iterations),
                                         t.residual, t.absolute_residual, t.converged ? 1.0 : 0.0});
  add("statistics", std::move(statistics));
  nlohmann::json history = nlohmann::json::array();
  for (const auto& [name, v] : s.history) {
    history.push_back(name);
    add("history_" + name, v);
  }
  c["checkpoint_history_arrays"] = history;
  // The acceleration's arrays under their own names, listed in the config (HDF5 names are free).
  nlohmann::json carried = nlohmann::json::array();
  for (const auto& [name, v] : s.acceleration) {
    carried.push_back(name);
    add("acceleration_" + name, v);
  }
  c["checkpoint_acceleration_arrays"] = carried;
  for (const auto& [name, v] : s.frames) add(name, v);
  cfd::write_checkpoint(path, flow, c.dump(), run);
}

nlohmann::json check_fsi_checkpoint_config(const std::filesystem::path& path, const nlohmann::json& config,
                                           const std::set<std::string>& may_differ) {
  nlohmann::json stored;
  try {
    stored = nlohmann::json::parse(cfd::checkpoint_config(path));
  } catch (const nlohmann::json::exception&) {
    throw Error("fsi restart: " + path.string() + ": its config attribute is not JSON");
  }
  if (stored.value("checkpoint_kind", "") != kKind)
    throw Error("fsi restart: " + path.string() + " is not a checkpoint of a coupled run (fin-fsi)");
  for (const auto& [key, value] : config.items()) {
    if (may_differ.count(key)) continue;
    if (!stored.contains(key))
      throw Error("fsi restart: " + path.string() + " has no option '" + key + "' (written by another version)");
    if (stored[key] != value)
      throw Error("fsi restart: " + path.string() + " was written with " + key + " = " + stored[key].dump() +
                  ", this run has " + value.dump() + " (a restart must keep the options)");
  }
  return stored;
}

FsiRunState read_fsi_checkpoint(const std::filesystem::path& path, cfd::FlowSolver& flow) {
  const nlohmann::json config = nlohmann::json::parse(cfd::checkpoint_config(path));
  std::vector<cfd::StateArray> run;
  for (const std::string& n : run_names()) run.push_back({n, {}});
  const std::vector<std::string> carried = config.value("checkpoint_acceleration_arrays", std::vector<std::string>{});
  for (const std::string& n : carried) run.push_back({"acceleration_" + n, {}});
  const std::vector<std::string> history = config.value("checkpoint_history_arrays", std::vector<std::string>{});
  for (const std::string& n : history) run.push_back({"history_" + n, {}});
  const std::vector<std::string> frame_names = FsiOutput::array_names();
  for (const std::string& n : frame_names) run.push_back({n, {}});
  cfd::read_checkpoint(path, flow, &run);
  std::map<std::string, std::vector<double>> a;
  for (cfd::StateArray& r : run) a[r.name] = std::move(r.values);

  const auto bad = [&](const std::string& what) { return Error("fsi restart: " + path.string() + ": " + what); };
  FsiRunState s;
  s.coupling_state = vector(a["coupling_state"]);
  s.coupling_previous = vector(a["coupling_previous"]);
  s.coupling_input = vector(a["coupling_input"]);
  if (a["coupling_counters"].size() != 2) throw bad("run/coupling_counters must hold [time, steps]");
  s.time = a["coupling_counters"][0];
  s.steps = static_cast<long>(a["coupling_counters"][1]);
  const std::vector<double>&position = a["structure_position"], &rotation = a["structure_rotation"];
  const std::size_t nodes = position.size() / 3;
  if (position.size() != 3 * nodes || rotation.size() != 9 * nodes || a["structure_time"].size() != 1 ||
      a["structure_scalars"].size() != 2)
    throw bad("the structure's arrays do not fit one another");
  for (std::size_t i = 0; i < nodes; ++i) {
    s.structure.configuration.position.emplace_back(position[3 * i], position[3 * i + 1], position[3 * i + 2]);
    s.structure.configuration.rotation.push_back(Eigen::Map<const Eigen::Matrix3d>(rotation.data() + 9 * i));
  }
  s.structure.velocity = vector(a["structure_velocity"]);
  s.structure.acceleration = vector(a["structure_acceleration"]);
  s.structure.time = a["structure_time"][0];
  s.integrator.old_terms = vector(a["structure_old_terms"]);
  s.integrator.force_scale = a["structure_scalars"][0];
  s.integrator.initialized = a["structure_scalars"][1] != 0;
  s.interface_load = vector(a["structure_load"]);
  const std::vector<double>& statistics = a["statistics"];
  if (statistics.size() % kStatisticsValues != 0) throw bad("run/statistics must hold 6 values per step");
  for (std::size_t k = 0; k < statistics.size(); k += kStatisticsValues) {
    const double* t = statistics.data() + k;
    StepStatistics st;
    st.step = static_cast<long>(t[0]);
    st.time = t[1];
    st.iterations = static_cast<int>(t[2]);
    st.residual = t[3];
    st.absolute_residual = t[4];
    st.converged = t[5] != 0;
    s.statistics.push_back(st);
  }
  for (const std::string& n : history) s.history[n] = std::move(a["history_" + n]);
  for (const std::string& n : carried) s.acceleration[n] = a["acceleration_" + n];
  for (const std::string& n : frame_names) s.frames[n] = a[n];
  return s;
}

}  // namespace finverse::fsi
