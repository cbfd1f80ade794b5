// fin-diff dispatcher (see file_diff.hpp).
#include "core/file_diff.hpp"

#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "core/h5_compare.hpp"
#include "core/vtk_compare.hpp"

namespace finverse {
namespace fs = std::filesystem;
namespace {

bool is_hdf5(const fs::path& p) {
  const auto e = p.extension().string();
  return e == ".h5" || e == ".hdf5" || e == ".hdf";
}

std::vector<std::pair<double, std::string>> read_pvd(const fs::path& p) {
  std::ifstream in(p);
  if (!in) throw Error(p.string() + ": cannot open .pvd collection");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  if (text.find("type=\"Collection\"") == std::string::npos) throw Error(p.string() + ": not a VTK Collection file");
  std::vector<std::pair<double, std::string>> entries;
  // Attributes of each <DataSet .../> tag, in any order.
  static const std::regex tag(R"re(<DataSet\s[^>]*>)re");
  static const std::regex timestep(R"re(timestep\s*=\s*"([^"]*)")re"), file(R"re(file\s*=\s*"([^"]*)")re");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), tag); it != std::sregex_iterator(); ++it) {
    const std::string t = it->str();
    std::smatch ts, fm;
    if (!std::regex_search(t, fm, file)) throw Error(p.string() + ": DataSet entry without a file attribute");
    const double time = std::regex_search(t, ts, timestep) ? std::stod(ts[1].str()) : 0.0;
    entries.emplace_back(time, fm[1].str());
  }
  return entries;
}

std::vector<Comparison> diff_pvd(const fs::path& ref, const fs::path& cand, const Tolerances& tol) {
  const auto r = read_pvd(ref), c = read_pvd(cand);
  std::vector<Comparison> out;
  NdArray<double> rt({r.size()}), ct({c.size()});
  std::vector<std::string> rf, cf;
  for (std::size_t i = 0; i < r.size(); ++i) rt.data[i] = r[i].first, rf.push_back(r[i].second);
  for (std::size_t i = 0; i < c.size(); ++i) ct.data[i] = c[i].first, cf.push_back(c[i].second);
  out.push_back(compare_values("timesteps", rt, ct, tol.for_object("timesteps")));
  out.push_back(compare_strings("files", rf, cf));
  if (rf != cf) return out;
  for (const auto& f : rf) {
    if (!is_vtk_xml(f)) continue;
    auto rows = compare_vtk(ref.parent_path() / f, cand.parent_path() / f, tol, f + ": ");
    out.insert(out.end(), rows.begin(), rows.end());
  }
  return out;
}

std::vector<Comparison> diff_file(const fs::path& ref, const fs::path& cand, const Tolerances& tol) {
  if (!fs::exists(ref)) throw Error(ref.string() + ": file not found");
  if (!fs::exists(cand)) throw Error(cand.string() + ": file not found");
  if (is_hdf5(ref)) return compare_hdf5(ref, cand, tol);
  if (is_vtk_xml(ref)) return compare_vtk(ref, cand, tol);
  if (ref.extension() == ".pvd") return diff_pvd(ref, cand, tol);
  throw Error(ref.string() + ": unknown file kind (expected .h5, .vtp/.vtu/.vtr/.vti/.vts or .pvd)");
}

// Comparable files below `dir`, relative to it. Frames of a .pvd are compared through it.
std::set<fs::path> comparable_files(const fs::path& dir) {
  std::set<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file() && is_comparable(e.path())) files.insert(fs::relative(e.path(), dir));
  std::set<fs::path> framed;
  for (const auto& f : files)
    if (f.extension() == ".pvd")
      for (const auto& [t, frame] : read_pvd(dir / f)) framed.insert((f.parent_path() / frame).lexically_normal());
  for (const auto& f : framed) files.erase(f);
  return files;
}

}  // namespace

bool is_comparable(const fs::path& p) { return is_hdf5(p) || is_vtk_xml(p) || p.extension() == ".pvd"; }

std::vector<Comparison> diff_paths(const fs::path& ref, const fs::path& cand, const Tolerances& tol) {
  if (!fs::is_directory(ref)) return diff_file(ref, cand, tol);
  if (!fs::is_directory(cand)) throw Error(cand.string() + ": expected a directory like the reference " + ref.string());
  const auto rf = comparable_files(ref), cf = comparable_files(cand);
  std::set<fs::path> all(rf.begin(), rf.end());
  all.insert(cf.begin(), cf.end());
  std::vector<Comparison> out;
  for (const auto& f : all) {
    const auto label = f.string();
    if (!rf.count(f)) { out.push_back(mismatch(label, "EXTRA", "file only in candidate")); continue; }
    if (!cf.count(f)) { out.push_back(mismatch(label, "MISSING", "file missing in candidate")); continue; }
    for (auto row : diff_file(ref / f, cand / f, tol)) {
      row.object = label + ": " + row.object;
      out.push_back(std::move(row));
    }
  }
  return out;
}

void update_reference(const fs::path& ref, const fs::path& cand) {
  auto copy_one = [](const fs::path& from, const fs::path& to) {
    std::error_code ec;
    fs::create_directories(to.parent_path().empty() ? fs::path(".") : to.parent_path(), ec);
    const auto tmp = temporary_for(to);
    fs::copy_file(from, tmp, fs::copy_options::overwrite_existing, ec);
    if (ec) throw Error(to.string() + ": cannot write reference: " + ec.message());
    commit_temporary(tmp, to);
  };
  if (!fs::is_directory(cand)) {
    if (!fs::exists(cand)) throw Error(cand.string() + ": file not found");
    if (cand.extension() == ".pvd") {
      for (const auto& [t, frame] : read_pvd(cand)) copy_one(cand.parent_path() / frame, ref.parent_path() / frame);
    }
    copy_one(cand, ref);
    return;
  }
  for (const auto& e : fs::recursive_directory_iterator(cand))
    if (e.is_regular_file() && is_comparable(e.path())) copy_one(e.path(), ref / fs::relative(e.path(), cand));
}

}  // namespace finverse
