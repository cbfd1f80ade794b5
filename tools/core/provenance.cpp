// Provenance attributes of output files (see provenance.hpp).
#include "core/provenance.hpp"

#include <unistd.h>

#include <fstream>

#include "core/sha256.hpp"
#include "core/stage_identity.hpp"
#include "core/version.hpp"

namespace finverse {

namespace {
// The HDF5 signature at offset 0 (files written by finverse have no user block).
bool starts_as_hdf5(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  char sig[8] = {};
  return in.read(sig, 8) && std::string(sig, 8) == std::string("\x89HDF\r\n\x1a\n", 8);
}
}  // namespace

std::string producer_string(const std::string& tool) {
  std::string s = std::string("finverse ") + version_string() + " (git " + git_describe() + ")";
  return tool.empty() ? s : tool + " " + s;
}

std::string host_name() {
  char buf[256] = {0};
  if (gethostname(buf, sizeof(buf) - 1) != 0) return "unknown";
  return buf;
}

const std::vector<std::string>& provenance_attribute_names() {
  static const std::vector<std::string> names = {"producer", "config", "inputs"};
  return names;
}

nlohmann::json hash_inputs(const std::vector<std::filesystem::path>& inputs) {
  auto arr = nlohmann::json::array();
  for (const auto& p : inputs) {
    nlohmann::json e{{"path", p.string()}, {"sha256", sha256_file(p)}};
    // A stage file's schema and content identity: what its consumers check (stage_identity.hpp).
    if (starts_as_hdf5(p)) e.update(stage_identity(p));
    arr.push_back(e);
  }
  return arr;
}

void write_provenance(h5::Group& root, const std::string& schema, int schema_version, const Provenance& p) {
  root.set_attr(".", "schema", schema);
  root.set_attr(".", "schema_version", static_cast<std::int64_t>(schema_version));
  root.set_attr(".", "producer", producer_string(p.tool));
  root.set_attr(".", "config", p.config.dump());
  root.set_attr(".", "inputs", hash_inputs(p.inputs).dump());
}

}  // namespace finverse
