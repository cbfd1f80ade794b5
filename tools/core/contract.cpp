// Contract checking and documentation (see contract.hpp).
#include "core/contract.hpp"

#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "core/provenance.hpp"

namespace finverse::contract {

const DatasetSpec* FileSpec::find(const std::string& path) const {
  for (const auto& d : datasets)
    if (d.path == path) return &d;
  return nullptr;
}

const FileSpec& get(const std::string& schema) {
  for (const auto& s : all())
    if (s.schema == schema) return s;
  throw Error("unknown schema '" + schema + "'");
}

namespace {

std::string dims_string(const std::vector<std::string>& dims) {
  std::string s = "[";
  for (std::size_t i = 0; i < dims.size(); ++i) s += (i ? "," : "") + dims[i];
  return s + "]";
}

// Resolves one symbolic dimension ("3", "nv", "nr+1") against the bindings so far, binding a
// new symbol on first use. Returns false when the extent contradicts an earlier binding.
bool resolve(const std::string& sym, std::size_t extent, Dims& dims, std::size_t& expected) {
  if (!sym.empty() && std::isdigit(static_cast<unsigned char>(sym[0]))) {
    expected = std::stoul(sym);
    return extent == expected;
  }
  std::string name = sym;
  std::size_t plus = 0;
  if (const auto p = sym.find('+'); p != std::string::npos) {
    name = sym.substr(0, p);
    plus = std::stoul(sym.substr(p + 1));
  }
  auto it = dims.find(name);
  if (it == dims.end()) {
    if (extent < plus) return false;
    dims[name] = extent - plus;
    expected = extent;
    return true;
  }
  expected = it->second + plus;
  return extent == expected;
}

std::string expected_shape(const std::vector<std::string>& syms, const Dims& dims) {
  std::string s = "[";
  for (std::size_t i = 0; i < syms.size(); ++i) {
    s += (i ? "," : "") + syms[i];
    std::string name = syms[i].substr(0, syms[i].find('+'));
    if (auto it = dims.find(name); it != dims.end()) {
      std::size_t plus = syms[i].find('+') == std::string::npos ? 0 : std::stoul(syms[i].substr(syms[i].find('+') + 1));
      s += "=" + std::to_string(it->second + plus);
    }
  }
  return s + "]";
}

}  // namespace

void check_shape(const std::string& file, const DatasetSpec& d, const std::vector<std::size_t>& shape, Dims& dims) {
  const auto where = file + ": /" + d.path + ": ";
  if (shape.size() != d.dims.size())
    throw Error(where + "expected shape " + expected_shape(d.dims, dims) + " (rank " + std::to_string(d.dims.size()) +
                "), found " + shape_string(shape));
  Dims trial = dims;
  for (std::size_t i = 0; i < shape.size(); ++i) {
    std::size_t expected = 0;
    if (!resolve(d.dims[i], shape[i], trial, expected))
      throw Error(where + "expected shape " + expected_shape(d.dims, dims) + ", found " + shape_string(shape));
  }
  dims = std::move(trial);
}

Dims check(const h5::File& file, const FileSpec& spec) {
  const auto& name = file.filename();
  const auto schema = file.attr_string(".", "schema");
  if (!schema) throw Error(name + ": missing root attribute 'schema' (expected " + spec.schema + ")");
  if (*schema != spec.schema) throw Error(name + ": schema is '" + *schema + "', expected '" + spec.schema + "'");
  const auto version = file.attr_int(".", "schema_version");
  if (!version) throw Error(name + ": missing root attribute 'schema_version'");
  if (*version != spec.version)
    throw Error(name + ": schema_version " + std::to_string(*version) + " of " + spec.schema + ", this build reads version " +
                std::to_string(spec.version));
  for (const auto& a : provenance_attribute_names())
    if (!file.has_attr(".", a)) throw Error(name + ": missing provenance attribute '" + a + "'");
  for (const auto& a : spec.attributes)
    if (a.required && !file.has_attr(".", a.name)) throw Error(name + ": missing root attribute '" + a.name + "'");

  Dims dims;
  for (const auto& d : spec.datasets) {
    const auto where = name + ": /" + d.path + ": ";
    if (!file.is_dataset(d.path)) {
      if (d.required) throw Error(where + "missing dataset (" + h5::to_string(d.dtype) + " " + dims_string(d.dims) + ")");
      continue;
    }
    const auto info = file.info(d.path);
    if (info.dtype != d.dtype)
      throw Error(where + "expected dtype " + h5::to_string(d.dtype) + ", found " + h5::to_string(info.dtype));
    check_shape(name, d, info.shape, dims);
    if (!d.units.empty()) {
      const auto units = file.attr_string(d.path, "units");
      if (!units) throw Error(where + "missing 'units' attribute (expected '" + d.units + "')");
      if (*units != d.units) throw Error(where + "units are '" + *units + "', expected '" + d.units + "'");
    }
    if (d.finite && (d.dtype == h5::DType::f64 || d.dtype == h5::DType::f32)) {
      const auto a = file.read_f64(d.path);
      for (std::size_t i = 0; i < a.size(); ++i)
        if (!std::isfinite(a.data[i]))
          throw Error(where + "non-finite value " + std::to_string(a.data[i]) + " at " + index_string(i, a.shape));
    }
  }
  // Indices within the sizes the shapes gave (a triangle naming vertex 999999 of 500).
  for (const auto& d : spec.datasets) {
    if (d.index_of.empty() || !file.is_dataset(d.path)) continue;
    const auto it = dims.find(d.index_of);
    if (it == dims.end()) continue;
    const auto a = file.read_i32(d.path);
    for (std::size_t i = 0; i < a.size(); ++i)
      if (a.data[i] < 0 || static_cast<std::size_t>(a.data[i]) >= it->second)
        throw Error(name + ": /" + d.path + ": index " + std::to_string(a.data[i]) + " at " + index_string(i, a.shape) +
                    " outside 0.." + std::to_string(static_cast<long>(it->second) - 1) + " (" + d.index_of + " = " +
                    std::to_string(it->second) + ")");
  }
  return dims;
}

std::string markdown(const FileSpec& spec) {
  std::ostringstream o;
  o << "## `" << spec.file_name << "` — schema `" << spec.schema << "` version " << spec.version << "\n\n";
  o << "Written by `" << spec.writer << "`. " << spec.description << "\n\n";
  o << "| dataset | dtype | shape | units | required | finite | meaning |\n|---|---|---|---|---|---|---|\n";
  for (const auto& d : spec.datasets)
    o << "| `/" << d.path << "` | " << h5::to_string(d.dtype) << " | `" << dims_string(d.dims) << "` | "
      << (d.units.empty() ? "—" : "`" + d.units + "`") << " | " << (d.required ? "yes" : "no") << " | "
      << ((d.dtype == h5::DType::f64 || d.dtype == h5::DType::f32) ? (d.finite ? "yes" : "no") : "—") << " | "
      << d.description << " |\n";
  if (!spec.attributes.empty()) {
    o << "\nRoot attributes besides provenance:\n\n| attribute | type | units | required | meaning |\n|---|---|---|---|---|\n";
    for (const auto& a : spec.attributes)
      o << "| `" << a.name << "` | " << (a.is_string ? "string" : "float64") << " | "
        << (a.units.empty() ? "—" : "`" + a.units + "`") << " | " << (a.required ? "yes" : "no") << " | "
        << a.description << " |\n";
  }
  o << "\n";
  return o.str();
}

std::string markdown_all() {
  std::ostringstream o;
  o << "# Stage file contracts\n\n"
       "Generated by `fin-contract --markdown` from tools/core/contract_specs.cpp; a unit test fails when\n"
       "this page and the code disagree. Every file also carries the root attributes `schema`,\n"
       "`schema_version`, `producer`, `config` (effective parameters, JSON) and `inputs` (JSON list of\n"
       "input paths with SHA-256). Units follow UDUNITS spelling; `1` means dimensionless. Shapes are\n"
       "row-major; a symbol takes one value throughout a file (`nr+1` is one more than `nr`).\n\n";
  for (const auto& s : all()) o << markdown(s);
  return o.str();
}

}  // namespace finverse::contract
