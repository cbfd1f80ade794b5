// The written contract of a stage file (DESIGN.md section 4): its schema name and version and,
// for every dataset, the path, dtype, symbolic shape, units and whether it must be finite.
// check() validates a file against its contract and fails with one line naming the file and
// dataset; markdown() renders the contract for tools/core/CONTRACTS.md, which a test keeps in
// step with the code.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "core/hdf5_file.hpp"

namespace finverse::contract {

struct DatasetSpec {
  std::string path;               // relative to the root, e.g. "beams/thickness"
  h5::DType dtype = h5::DType::f64;
  std::vector<std::string> dims;  // symbols ("nf"), numbers ("3") or "sym+1"; {} = scalar
  std::string units;              // required `units` attribute; "" = none (indices, names)
  std::string description;
  bool required = true;
  bool finite = true;             // floating datasets: no NaN/Inf allowed
  std::string index_of = {};      // integer datasets of indices: each in [0, size of this dim symbol)
};

struct AttributeSpec {
  std::string name;
  std::string units;  // documentation only: attributes carry no units attribute of their own
  std::string description;
  bool required = false;
  bool is_string = false;
};

struct FileSpec {
  std::string schema;  // e.g. "finverse/mesh"
  int version = 1;
  std::string file_name;  // conventional name, e.g. "mesh.h5"
  std::string writer;     // the executable that produces it
  std::string description;
  std::vector<DatasetSpec> datasets;
  std::vector<AttributeSpec> attributes;  // root attributes besides the provenance ones

  const DatasetSpec* find(const std::string& path) const;
};

using Dims = std::map<std::string, std::size_t>;

// Every stage file's contract, in pipeline order.
const std::vector<FileSpec>& all();
const FileSpec& get(const std::string& schema);  // throws finverse::Error for an unknown schema

// Validates the provenance attributes, schema name/version, and every dataset. Returns the
// resolved dimension symbols (e.g. {"nf": 200, "nv": 412}).
Dims check(const h5::File& file, const FileSpec& spec);
// Validates one in-memory dataset shape against its spec while resolving dims; used by writers
// so that a producer cannot write a file its readers would reject.
void check_shape(const std::string& file, const DatasetSpec& d, const std::vector<std::size_t>& shape, Dims& dims);

std::string markdown(const FileSpec& spec);
std::string markdown_all();

}  // namespace finverse::contract
