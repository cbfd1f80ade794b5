// Provenance carried by every output file (DESIGN.md section 3, "Files"): root attributes
// `schema`, `schema_version`, `producer`, `config` (effective parameters as JSON) and `inputs`
// (input files with their SHA-256). Nothing time- or host-dependent goes into HDF5 files, so
// identical runs give identical bytes.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/hdf5_file.hpp"

namespace finverse {

struct Provenance {
  std::string tool;                                // executable name, e.g. "fin-mesh"
  nlohmann::json config = nlohmann::json::object();  // effective parameters
  std::vector<std::filesystem::path> inputs;       // hashed when written
};

// "finverse 0.1.0 (git 1a2b3c4)", prefixed with the tool name when given.
std::string producer_string(const std::string& tool = "");
std::string host_name();

// Root attributes that the file-diff ignores: they describe how a file was made, not what it holds.
const std::vector<std::string>& provenance_attribute_names();

void write_provenance(h5::Group& root, const std::string& schema, int schema_version, const Provenance& p);

// JSON array [{"path": ..., "sha256": ...}] of the given files.
nlohmann::json hash_inputs(const std::vector<std::filesystem::path>& inputs);

}  // namespace finverse
