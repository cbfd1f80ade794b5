// Content identity of stage files and the check that one was made from another (see
// stage_identity.hpp).
#include "core/stage_identity.hpp"

#include <cstring>
#include <functional>

#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "core/sha256.hpp"

namespace finverse {

namespace {

template <class T> void append(std::string& buf, const std::vector<T>& v) {
  const auto* p = reinterpret_cast<const char*>(v.data());
  buf.append(p, p + v.size() * sizeof(T));
}

void digest_group(const h5::Group& g, const std::string& prefix, std::string& buf) {
  for (const auto& name : g.children()) {
    const std::string path = prefix + "/" + name;
    if (g.is_group(name)) {
      digest_group(g.group(name), path, buf);
      continue;
    }
    if (!g.is_dataset(name)) continue;
    const auto info = g.info(name);
    buf += path + " " + h5::to_string(info.dtype) + " " + shape_string(info.shape) + "\n";
    switch (info.dtype) {
      case h5::DType::f64:
      case h5::DType::f32: append(buf, g.read_f64(name).data); break;
      case h5::DType::i64: append(buf, g.read_i64(name).data); break;
      case h5::DType::i32: append(buf, g.read_i32(name).data); break;
      case h5::DType::u8: append(buf, g.read_u8(name).data); break;
      case h5::DType::str:
        for (const auto& s : g.read_strings(name)) buf += s + '\0';
        break;
      case h5::DType::other: break;
    }
  }
}

std::string shapes_text(const nlohmann::json& shapes) {
  std::string s;
  for (const auto& [k, v] : shapes.items()) s += (s.empty() ? "" : ", ") + k + " " + v.get<std::string>();
  return s.empty() ? "no points or time" : s;
}

}  // namespace

std::string content_digest(const std::filesystem::path& h5_file) {
  const auto f = h5::File::open_read(h5_file);
  std::string buf;
  digest_group(f, "", buf);
  return sha256_hex(buf);
}

nlohmann::json stage_identity(const std::filesystem::path& h5_file) {
  const auto f = h5::File::open_read(h5_file);
  nlohmann::json shapes = nlohmann::json::object();
  for (const char* d : {"points", "time"})
    if (f.is_dataset(d)) shapes[d] = shape_string(f.info(d).shape);
  std::string buf;
  digest_group(f, "", buf);
  return {{"schema", f.attr_string(".", "schema").value_or("")}, {"content_sha256", sha256_hex(buf)}, {"shapes", shapes}};
}

void check_made_from(const std::filesystem::path& product, const std::filesystem::path& input) {
  const auto f = h5::File::open_read(product);
  const auto inputs_text = f.attr_string(".", "inputs");
  if (!inputs_text) return;
  const auto inputs = nlohmann::json::parse(*inputs_text, nullptr, false);
  if (!inputs.is_array()) return;
  const auto id = stage_identity(input);
  const nlohmann::json* recorded = nullptr;
  for (const auto& e : inputs) {
    if (!e.is_object() || e.value("schema", "") != id["schema"] || !e.contains("content_sha256")) continue;
    if (e["content_sha256"] == id["content_sha256"]) return;
    recorded = &e;
  }
  if (!recorded) return;
  // A file derived from the recorded one (e.g. a twin's motion that fin-fem computed from the case's
  // motion.h5) records it among its own inputs: same lineage, accepted.
  const auto own = h5::File::open_read(input).attr_string(".", "inputs");
  const auto own_inputs = own ? nlohmann::json::parse(*own, nullptr, false) : nlohmann::json();
  if (own_inputs.is_array())
    for (const auto& e : own_inputs)
      if (e.is_object() && e.value("schema", "") == id["schema"] && e.value("content_sha256", "") == (*recorded)["content_sha256"])
        return;
  const std::string what = (*recorded).value("shapes", nlohmann::json::object()) == id["shapes"]
                               ? "same shapes (" + shapes_text(id["shapes"]) + "), other values"
                               : shapes_text((*recorded).value("shapes", nlohmann::json::object())) + " there, " +
                                     shapes_text(id["shapes"]) + " here";
  throw Error(product.string() + " was made from another " + id["schema"].get<std::string>() + " (" +
              (*recorded).value("path", "?") + ") than " + input.string() + ": " + what);
}

}  // namespace finverse
