// HDF5 file comparison (see h5_compare.hpp).
#include "core/h5_compare.hpp"

#include <algorithm>
#include <set>

#include "core/hdf5_file.hpp"
#include "core/provenance.hpp"

namespace finverse {
namespace {

// All datasets below `g`, as absolute paths, and all groups (attributes live on both).
void walk(const h5::Group& g, std::vector<std::string>& datasets, std::vector<std::string>& groups) {
  for (const auto& name : g.children()) {
    const auto path = g.child_path(name);
    if (g.is_dataset(name)) {
      datasets.push_back(path);
    } else if (g.is_group(name)) {
      groups.push_back(path);
      walk(g.group(name), datasets, groups);
    }
  }
}

bool is_text(h5::DType t) { return t == h5::DType::str; }

void compare_attributes(const h5::File& ref, const h5::File& cand, const std::string& object, const Tolerances& tol,
                        std::vector<Comparison>& out) {
  const auto& ignored_root = provenance_attribute_names();
  auto names_of = [&](const h5::File& f) {
    auto n = f.attr_names(object);
    if (object == "/")
      n.erase(std::remove_if(n.begin(), n.end(),
                             [&](const std::string& a) { return std::count(ignored_root.begin(), ignored_root.end(), a) > 0; }),
              n.end());
    return n;
  };
  const auto rn = names_of(ref), cn = names_of(cand);
  std::set<std::string> all(rn.begin(), rn.end());
  all.insert(cn.begin(), cn.end());
  for (const auto& a : all) {
    const std::string label = (object == "/" ? "" : object) + "@" + a;
    if (tol.ignored(label)) continue;
    const bool in_ref = std::count(rn.begin(), rn.end(), a) > 0, in_cand = std::count(cn.begin(), cn.end(), a) > 0;
    if (!in_cand) { out.push_back(mismatch(label, "MISSING", "attribute missing in candidate")); continue; }
    if (!in_ref) { out.push_back(mismatch(label, "EXTRA", "attribute only in candidate")); continue; }
    const auto ri = ref.attr_info(object, a), ci = cand.attr_info(object, a);
    if (is_text(ri.dtype) != is_text(ci.dtype)) {
      out.push_back(mismatch(label, "DTYPE", h5::to_string(ri.dtype) + " vs " + h5::to_string(ci.dtype)));
    } else if (is_text(ri.dtype)) {
      out.push_back(compare_strings(label, {ref.attr_string(object, a).value_or("")}, {cand.attr_string(object, a).value_or("")}));
    } else {
      out.push_back(compare_values(label, ref.attr_f64(object, a), cand.attr_f64(object, a), tol.for_object(label)));
    }
  }
}

}  // namespace

std::vector<Comparison> compare_hdf5(const std::filesystem::path& reference, const std::filesystem::path& candidate,
                                     const Tolerances& tolerances) {
  const auto ref = h5::File::open_read(reference);
  const auto cand = h5::File::open_read(candidate);
  std::vector<std::string> rd, rg, cd, cg;
  walk(ref, rd, rg);
  walk(cand, cd, cg);
  std::vector<Comparison> out;

  compare_attributes(ref, cand, "/", tolerances, out);
  std::set<std::string> groups(rg.begin(), rg.end());
  groups.insert(cg.begin(), cg.end());
  for (const auto& g : groups) {
    if (tolerances.ignored(g)) continue;
    if (!ref.is_group(g)) out.push_back(mismatch(g, "EXTRA", "group only in candidate"));
    else if (!cand.is_group(g)) out.push_back(mismatch(g, "MISSING", "group missing in candidate"));
    else compare_attributes(ref, cand, g, tolerances, out);
  }

  std::set<std::string> datasets(rd.begin(), rd.end());
  datasets.insert(cd.begin(), cd.end());
  for (const auto& d : datasets) {
    if (tolerances.ignored(d)) continue;
    if (!ref.is_dataset(d)) { out.push_back(mismatch(d, "EXTRA", "dataset only in candidate")); continue; }
    if (!cand.is_dataset(d)) { out.push_back(mismatch(d, "MISSING", "dataset missing in candidate")); continue; }
    const auto ri = ref.info(d), ci = cand.info(d);
    if (ri.dtype != ci.dtype) {
      out.push_back(mismatch(d, "DTYPE", h5::to_string(ri.dtype) + " vs " + h5::to_string(ci.dtype)));
    } else if (ri.shape != ci.shape) {
      out.push_back(mismatch(d, "SHAPE", shape_string(ri.shape) + " vs " + shape_string(ci.shape)));
    } else if (is_text(ri.dtype)) {
      out.push_back(compare_strings(d, ref.read_strings(d), cand.read_strings(d)));
    } else if (ri.dtype == h5::DType::other) {
      out.push_back(mismatch(d, "DTYPE", "unsupported dataset type"));
    } else {
      out.push_back(compare_values(d, ref.read_f64(d), cand.read_f64(d), tolerances.for_object(d)));
    }
    compare_attributes(ref, cand, d, tolerances, out);
  }
  return out;
}

}  // namespace finverse
