// HDF5 checkpoint write and read; see flow_checkpoint.hpp.
#include "cfd/io/flow_checkpoint.hpp"

#include "core/error.hpp"
#include "core/hdf5_file.hpp"

namespace finverse::cfd {

namespace {

h5::File open_checkpoint(const std::filesystem::path& path) {
  auto file = h5::File::open_read(path);
  if (file.attr_string(".", "schema").value_or("") != "finverse/cfd-checkpoint")
    throw Error(path.string() + ": not a flow-solver checkpoint (root attribute schema != finverse/cfd-checkpoint)");
  return file;
}

}  // namespace

void write_checkpoint(const std::filesystem::path& path, const FlowSolver& solver, const std::string& config,
                      const std::vector<StateArray>& run) {
  auto file = h5::File::create(path);
  file.set_attr(".", "schema", std::string("finverse/cfd-checkpoint"));
  file.set_attr(".", "schema_version", std::int64_t{1});
  file.set_attr(".", "config", config);
  auto g = file.create_group("state");
  for (const StateArray& a : solver.state()) {
    if (a.values.empty()) continue;  // e.g. Neumann sides: no boundary values
    g.write(a.name, NdArray<double>({a.values.size()}, a.values), h5::WriteOptions{"", false});
  }
  if (!run.empty()) {
    auto r = file.create_group("run");
    for (const StateArray& a : run)
      if (!a.values.empty()) r.write(a.name, NdArray<double>({a.values.size()}, a.values), h5::WriteOptions{"", false});
  }
  file.commit();
}

void read_checkpoint(const std::filesystem::path& path, FlowSolver& solver, std::vector<StateArray>* run) {
  auto file = open_checkpoint(path);
  auto g = file.group("state");
  std::vector<StateArray> state = solver.state();
  for (StateArray& a : state) {
    if (!g.exists(a.name)) {
      if (!a.values.empty()) throw Error(path.string() + ": dataset state/" + a.name + " missing");
      continue;
    }
    a.values = g.read_f64(a.name).data;
  }
  if (run) {
    const bool any = file.exists("run");
    for (StateArray& a : *run) {
      a.values.clear();
      if (any && file.exists("run/" + a.name)) a.values = file.group("run").read_f64(a.name).data;
    }
  }
  try {
    solver.restore(state);
  } catch (const Error& e) {
    throw Error(path.string() + ": " + e.what());
  }
}

std::string checkpoint_config(const std::filesystem::path& path) {
  return open_checkpoint(path).attr_string(".", "config").value_or("{}");
}

}  // namespace finverse::cfd
