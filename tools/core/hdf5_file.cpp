// Implementation of the HDF5 wrapper (see hdf5_file.hpp for the conventions it enforces).
#include "core/hdf5_file.hpp"

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>
#include <system_error>

#include "core/error.hpp"

namespace finverse {

namespace h5 {
namespace {

static_assert(sizeof(hid) == sizeof(hid_t), "hid must hold an hid_t");

template <class T> hid_t native_type();
template <> hid_t native_type<double>() { return H5T_NATIVE_DOUBLE; }
template <> hid_t native_type<float>() { return H5T_NATIVE_FLOAT; }
template <> hid_t native_type<std::int64_t>() { return H5T_NATIVE_INT64; }
template <> hid_t native_type<std::int32_t>() { return H5T_NATIVE_INT32; }
template <> hid_t native_type<std::uint8_t>() { return H5T_NATIVE_UINT8; }

// Stored file types are fixed little-endian so files are identical across machines.
template <class T> hid_t file_type();
template <> hid_t file_type<double>() { return H5T_IEEE_F64LE; }
template <> hid_t file_type<float>() { return H5T_IEEE_F32LE; }
template <> hid_t file_type<std::int64_t>() { return H5T_STD_I64LE; }
template <> hid_t file_type<std::int32_t>() { return H5T_STD_I32LE; }
template <> hid_t file_type<std::uint8_t>() { return H5T_STD_U8LE; }

DType classify(hid_t type) {
  switch (H5Tget_class(type)) {
    case H5T_FLOAT: return H5Tget_size(type) == 8 ? DType::f64 : H5Tget_size(type) == 4 ? DType::f32 : DType::other;
    case H5T_INTEGER: {
      const bool sign = H5Tget_sign(type) == H5T_SGN_2;
      const auto n = H5Tget_size(type);
      if (sign && n == 8) return DType::i64;
      if (sign && n == 4) return DType::i32;
      if (!sign && n == 1) return DType::u8;
      return DType::other;
    }
    case H5T_STRING: return DType::str;
    default: return DType::other;
  }
}

std::vector<std::size_t> space_shape(hid_t space) {
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> dims(std::max(rank, 0));
  if (rank > 0) H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  return {dims.begin(), dims.end()};
}

Id make_space(const std::vector<std::size_t>& shape) {
  if (shape.empty()) return Id(H5Screate(H5S_SCALAR));
  std::vector<hsize_t> dims(shape.begin(), shape.end());
  return Id(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr));
}

// Creation properties shared by groups and datasets: no timestamps, tracked attribute order off.
void untimed(hid_t plist) { H5Pset_obj_track_times(plist, false); }

Id vlen_string_type() {
  Id t(H5Tcopy(H5T_C_S1));
  H5Tset_size(t.get(), H5T_VARIABLE);
  H5Tset_cset(t.get(), H5T_CSET_UTF8);
  return t;
}

}  // namespace

std::string to_string(DType t) {
  switch (t) {
    case DType::f64: return "float64";
    case DType::f32: return "float32";
    case DType::i64: return "int64";
    case DType::i32: return "int32";
    case DType::u8: return "uint8";
    case DType::str: return "string";
    case DType::other: break;
  }
  return "other";
}

void quiet_hdf5_errors() {
  static std::once_flag once;
  std::call_once(once, [] { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); });
}

// ---------------------------------------------------------------------------------------------
// Id: close with the function that matches the identifier's type.
Id& Id::operator=(Id&& o) noexcept {
  if (this != &o) {
    reset();
    id_ = o.id_;
    o.id_ = -1;
  }
  return *this;
}
Id::~Id() { reset(); }
void Id::reset() {
  if (id_ < 0) return;
  if (H5Iis_valid(id_) > 0) {
    switch (H5Iget_type(id_)) {
      case H5I_FILE: H5Fclose(id_); break;
      case H5I_GROUP: H5Gclose(id_); break;
      case H5I_DATASET: H5Dclose(id_); break;
      case H5I_DATASPACE: H5Sclose(id_); break;
      case H5I_DATATYPE: H5Tclose(id_); break;
      case H5I_ATTR: H5Aclose(id_); break;
      case H5I_GENPROP_LST: H5Pclose(id_); break;
      default: H5Idec_ref(id_); break;
    }
  }
  id_ = -1;
}

// ---------------------------------------------------------------------------------------------
// Group
void Group::fail(const std::string& object, const std::string& what) const {
  throw Error(file_ + ": " + (object.empty() ? path_ : child_path(object)) + ": " + what);
}

std::string Group::child_path(const std::string& name) const {
  if (name.empty() || name == ".") return path_;
  if (name.front() == '/') return name;
  return path_ == "/" ? "/" + name : path_ + "/" + name;
}

bool Group::exists(const std::string& path) const {
  // H5Lexists must be asked one component at a time.
  std::string partial;
  std::size_t start = 0;
  while (start <= path.size()) {
    const auto end = path.find('/', start);
    const auto part = path.substr(start, end == std::string::npos ? std::string::npos : end - start);
    if (!part.empty()) {
      partial += (partial.empty() ? "" : "/") + part;
      if (H5Lexists(id_.get(), partial.c_str(), H5P_DEFAULT) <= 0) return false;
    }
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return !partial.empty();
}

bool Group::is_dataset(const std::string& path) const {
  if (!exists(path)) return false;
  Id obj(H5Oopen(id_.get(), path.c_str(), H5P_DEFAULT));
  return obj.valid() && H5Iget_type(obj.get()) == H5I_DATASET;
}

bool Group::is_group(const std::string& path) const {
  if (!exists(path)) return false;
  Id obj(H5Oopen(id_.get(), path.c_str(), H5P_DEFAULT));
  return obj.valid() && H5Iget_type(obj.get()) == H5I_GROUP;
}

std::vector<std::string> Group::children() const {
  std::vector<std::string> names;
  auto collect = [](hid_t, const char* name, const H5L_info_t*, void* out) -> herr_t {
    static_cast<std::vector<std::string>*>(out)->emplace_back(name);
    return 0;
  };
  hsize_t idx = 0;
  if (H5Literate(id_.get(), H5_INDEX_NAME, H5_ITER_INC, &idx, collect, &names) < 0) fail("", "cannot list members");
  std::sort(names.begin(), names.end());
  return names;
}

Group Group::create_group(const std::string& path) {
  if (is_group(path)) return group(path);
  ensure_parents(path);
  Id gcpl(H5Pcreate(H5P_GROUP_CREATE));
  untimed(gcpl.get());
  Id g(H5Gcreate2(id_.get(), path.c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT));
  if (!g.valid()) fail(path, "cannot create group");
  return Group(std::move(g), file_, child_path(path));
}

// Parents are created one level at a time (not with H5Pset_create_intermediate_group) so that
// they too carry no timestamps.
void Group::ensure_parents(const std::string& path) {
  const auto slash = path.rfind('/');
  if (slash == std::string::npos || slash == 0) return;
  std::string parent;
  std::size_t start = 0;
  while (start < slash) {
    const auto end = path.find('/', start);
    parent += (parent.empty() ? "" : "/") + path.substr(start, end - start);
    if (!exists(parent)) create_group(parent);
    start = end + 1;
  }
}

Group Group::group(const std::string& path) const {
  if (!is_group(path)) fail(path, "missing group");
  Id g(H5Gopen2(id_.get(), path.c_str(), H5P_DEFAULT));
  if (!g.valid()) fail(path, "cannot open group");
  return Group(std::move(g), file_, child_path(path));
}

template <class T>
void Group::write_numeric(const std::string& name, const NdArray<T>& a, const WriteOptions& o) {
  if (NdArray<T>::element_count(a.shape) != a.data.size())
    fail(name, "internal: data size " + std::to_string(a.data.size()) + " does not match shape " + shape_string(a.shape));
  ensure_parents(name);
  Id space = make_space(a.shape);
  Id dcpl(H5Pcreate(H5P_DATASET_CREATE));
  untimed(dcpl.get());
  if (o.compress && !a.shape.empty() && a.data.size() >= 4096) {
    // Chunks of about 256 KiB along the slowest dimension keep time slices cheap to read.
    std::vector<hsize_t> chunk(a.shape.begin(), a.shape.end());
    std::size_t row = a.data.size() / a.shape[0];
    chunk[0] = std::clamp<std::size_t>((256 * 1024 / sizeof(T)) / std::max<std::size_t>(row, 1), 1, a.shape[0]);
    if (row * sizeof(T) > (4u << 20)) chunk[0] = 1;
    H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data());
    H5Pset_shuffle(dcpl.get());
    H5Pset_deflate(dcpl.get(), 4);
  }
  Id d(H5Dcreate2(id_.get(), name.c_str(), file_type<T>(), space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT));
  if (!d.valid()) fail(name, "cannot create dataset (already exists?)");
  if (!a.data.empty() && H5Dwrite(d.get(), native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, a.data.data()) < 0)
    fail(name, "write failed");
  d.reset();
  if (!o.units.empty()) set_attr(name, "units", o.units);
}

void Group::write(const std::string& n, const NdArray<double>& a, const WriteOptions& o) { write_numeric(n, a, o); }
void Group::write(const std::string& n, const NdArray<float>& a, const WriteOptions& o) { write_numeric(n, a, o); }
void Group::write(const std::string& n, const NdArray<std::int64_t>& a, const WriteOptions& o) { write_numeric(n, a, o); }
void Group::write(const std::string& n, const NdArray<std::int32_t>& a, const WriteOptions& o) { write_numeric(n, a, o); }
void Group::write(const std::string& n, const NdArray<std::uint8_t>& a, const WriteOptions& o) { write_numeric(n, a, o); }

void Group::write_scalar(const std::string& name, double value, const std::string& units) {
  write(name, NdArray<double>({}, {value}), WriteOptions{units, false});
}

void Group::write(const std::string& name, const std::vector<std::string>& strings) {
  ensure_parents(name);
  Id type = vlen_string_type();
  Id space = make_space({strings.size()});
  Id dcpl(H5Pcreate(H5P_DATASET_CREATE));
  untimed(dcpl.get());
  Id d(H5Dcreate2(id_.get(), name.c_str(), type.get(), space.get(), H5P_DEFAULT, dcpl.get(), H5P_DEFAULT));
  if (!d.valid()) fail(name, "cannot create dataset (already exists?)");
  std::vector<const char*> ptrs;
  for (const auto& s : strings) ptrs.push_back(s.c_str());
  if (!ptrs.empty() && H5Dwrite(d.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data()) < 0)
    fail(name, "write failed");
}

DatasetInfo Group::info(const std::string& name) const {
  if (!is_dataset(name)) fail(name, "missing dataset");
  Id d(H5Dopen2(id_.get(), name.c_str(), H5P_DEFAULT));
  if (!d.valid()) fail(name, "cannot open dataset");
  Id type(H5Dget_type(d.get()));
  Id space(H5Dget_space(d.get()));
  return {classify(type.get()), space_shape(space.get())};
}

template <class T>
NdArray<T> Group::read_numeric(const std::string& name) const {
  const auto inf = info(name);
  if (inf.dtype == DType::str || inf.dtype == DType::other)
    fail(name, "expected a numeric dataset, found " + to_string(inf.dtype));
  NdArray<T> a(inf.shape);
  Id d(H5Dopen2(id_.get(), name.c_str(), H5P_DEFAULT));
  if (!a.data.empty() && H5Dread(d.get(), native_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, a.data.data()) < 0)
    fail(name, "read failed (truncated or corrupt file?)");
  return a;
}

NdArray<double> Group::read_f64(const std::string& n) const { return read_numeric<double>(n); }
NdArray<std::int64_t> Group::read_i64(const std::string& n) const { return read_numeric<std::int64_t>(n); }
NdArray<std::int32_t> Group::read_i32(const std::string& n) const { return read_numeric<std::int32_t>(n); }
NdArray<std::uint8_t> Group::read_u8(const std::string& n) const { return read_numeric<std::uint8_t>(n); }

double Group::read_scalar(const std::string& name) const {
  auto a = read_f64(name);
  if (a.size() != 1) fail(name, "expected a scalar, found shape " + shape_string(a.shape));
  return a.data[0];
}

std::vector<std::string> Group::read_strings(const std::string& name) const {
  const auto inf = info(name);
  if (inf.dtype != DType::str) fail(name, "expected a string dataset, found " + to_string(inf.dtype));
  Id d(H5Dopen2(id_.get(), name.c_str(), H5P_DEFAULT));
  Id ftype(H5Dget_type(d.get()));
  Id space(H5Dget_space(d.get()));
  const std::size_t n = NdArray<char>::element_count(inf.shape);
  std::vector<std::string> out;
  if (H5Tis_variable_str(ftype.get()) > 0) {
    Id mtype = vlen_string_type();
    std::vector<char*> ptrs(n, nullptr);
    if (n && H5Dread(d.get(), mtype.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, ptrs.data()) < 0) fail(name, "read failed");
    for (auto* p : ptrs) out.emplace_back(p ? p : "");
    if (n) H5Dvlen_reclaim(mtype.get(), space.get(), H5P_DEFAULT, ptrs.data());
  } else {
    const std::size_t len = H5Tget_size(ftype.get());
    std::vector<char> buf(n * len + 1, '\0');
    if (n && H5Dread(d.get(), ftype.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()) < 0) fail(name, "read failed");
    for (std::size_t i = 0; i < n; ++i) out.emplace_back(buf.data() + i * len, strnlen(buf.data() + i * len, len));
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// Attributes
namespace {
Id open_object(hid_t base, const std::string& object) {
  return Id(H5Oopen(base, object.empty() ? "." : object.c_str(), H5P_DEFAULT));
}
}  // namespace

void Group::set_attr(const std::string& object, const std::string& key, const std::string& value) {
  Id obj = open_object(id_.get(), object);
  if (!obj.valid()) fail(object, "cannot open object to set attribute '" + key + "'");
  if (H5Aexists(obj.get(), key.c_str()) > 0) H5Adelete(obj.get(), key.c_str());
  Id type = vlen_string_type();
  Id space(H5Screate(H5S_SCALAR));
  Id a(H5Acreate2(obj.get(), key.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT));
  const char* p = value.c_str();
  if (!a.valid() || H5Awrite(a.get(), type.get(), &p) < 0) fail(object, "cannot write attribute '" + key + "'");
}

void Group::set_attr(const std::string& object, const std::string& key, double value) {
  Id obj = open_object(id_.get(), object);
  if (!obj.valid()) fail(object, "cannot open object to set attribute '" + key + "'");
  if (H5Aexists(obj.get(), key.c_str()) > 0) H5Adelete(obj.get(), key.c_str());
  Id space(H5Screate(H5S_SCALAR));
  Id a(H5Acreate2(obj.get(), key.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT));
  if (!a.valid() || H5Awrite(a.get(), H5T_NATIVE_DOUBLE, &value) < 0) fail(object, "cannot write attribute '" + key + "'");
}

void Group::set_attr(const std::string& object, const std::string& key, std::int64_t value) {
  Id obj = open_object(id_.get(), object);
  if (!obj.valid()) fail(object, "cannot open object to set attribute '" + key + "'");
  if (H5Aexists(obj.get(), key.c_str()) > 0) H5Adelete(obj.get(), key.c_str());
  Id space(H5Screate(H5S_SCALAR));
  Id a(H5Acreate2(obj.get(), key.c_str(), H5T_STD_I64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT));
  if (!a.valid() || H5Awrite(a.get(), H5T_NATIVE_INT64, &value) < 0) fail(object, "cannot write attribute '" + key + "'");
}

bool Group::has_attr(const std::string& object, const std::string& key) const {
  Id obj = open_object(id_.get(), object);
  return obj.valid() && H5Aexists(obj.get(), key.c_str()) > 0;
}

std::vector<std::string> Group::attr_names(const std::string& object) const {
  Id obj = open_object(id_.get(), object);
  if (!obj.valid()) fail(object, "cannot open object");
  std::vector<std::string> names;
  auto collect = [](hid_t, const char* name, const H5A_info_t*, void* out) -> herr_t {
    static_cast<std::vector<std::string>*>(out)->emplace_back(name);
    return 0;
  };
  hsize_t idx = 0;
  H5Aiterate2(obj.get(), H5_INDEX_NAME, H5_ITER_INC, &idx, collect, &names);
  std::sort(names.begin(), names.end());
  return names;
}

DatasetInfo Group::attr_info(const std::string& object, const std::string& key) const {
  Id obj = open_object(id_.get(), object);
  if (!obj.valid() || H5Aexists(obj.get(), key.c_str()) <= 0) fail(object, "missing attribute '" + key + "'");
  Id a(H5Aopen(obj.get(), key.c_str(), H5P_DEFAULT));
  Id type(H5Aget_type(a.get()));
  Id space(H5Aget_space(a.get()));
  return {classify(type.get()), space_shape(space.get())};
}

std::optional<std::string> Group::attr_string(const std::string& object, const std::string& key) const {
  Id obj = open_object(id_.get(), object);
  if (!obj.valid() || H5Aexists(obj.get(), key.c_str()) <= 0) return std::nullopt;
  Id a(H5Aopen(obj.get(), key.c_str(), H5P_DEFAULT));
  Id type(H5Aget_type(a.get()));
  if (H5Tget_class(type.get()) != H5T_STRING) fail(object, "attribute '" + key + "' is not a string");
  if (H5Tis_variable_str(type.get()) > 0) {
    Id mtype = vlen_string_type();
    char* p = nullptr;
    if (H5Aread(a.get(), mtype.get(), &p) < 0) fail(object, "cannot read attribute '" + key + "'");
    std::string s = p ? p : "";
    H5free_memory(p);
    return s;
  }
  const std::size_t len = H5Tget_size(type.get());
  std::string buf(len, '\0');
  if (H5Aread(a.get(), type.get(), buf.data()) < 0) fail(object, "cannot read attribute '" + key + "'");
  return buf.substr(0, strnlen(buf.c_str(), len));
}

NdArray<double> Group::attr_f64(const std::string& object, const std::string& key) const {
  const auto inf = attr_info(object, key);
  if (inf.dtype == DType::str || inf.dtype == DType::other) fail(object, "attribute '" + key + "' is not numeric");
  Id obj = open_object(id_.get(), object);
  Id a(H5Aopen(obj.get(), key.c_str(), H5P_DEFAULT));
  NdArray<double> out(inf.shape);
  if (H5Aread(a.get(), H5T_NATIVE_DOUBLE, out.data.data()) < 0) fail(object, "cannot read attribute '" + key + "'");
  return out;
}

std::optional<double> Group::attr_double(const std::string& object, const std::string& key) const {
  if (!has_attr(object, key)) return std::nullopt;
  auto a = attr_f64(object, key);
  if (a.size() != 1) fail(object, "attribute '" + key + "' is not a scalar");
  return a.data[0];
}

std::optional<std::int64_t> Group::attr_int(const std::string& object, const std::string& key) const {
  if (!has_attr(object, key)) return std::nullopt;
  const auto inf = attr_info(object, key);
  if (inf.dtype != DType::i64 && inf.dtype != DType::i32 && inf.dtype != DType::u8)
    fail(object, "attribute '" + key + "' is not an integer");
  Id obj = open_object(id_.get(), object);
  Id a(H5Aopen(obj.get(), key.c_str(), H5P_DEFAULT));
  std::int64_t v = 0;
  if (H5Aread(a.get(), H5T_NATIVE_INT64, &v) < 0) fail(object, "cannot read attribute '" + key + "'");
  return v;
}

// ---------------------------------------------------------------------------------------------
// File
File File::create(const std::filesystem::path& final_path) {
  quiet_hdf5_errors();
  File f;
  f.final_ = final_path;
  f.temp_ = final_path;
  f.temp_ += ".tmp";
  f.file_ = final_path.string();
  std::error_code ec;
  if (final_path.has_parent_path()) std::filesystem::create_directories(final_path.parent_path(), ec);
  std::filesystem::remove(f.temp_, ec);
  Id fcpl(H5Pcreate(H5P_FILE_CREATE));
  untimed(fcpl.get());
  Id fapl(H5Pcreate(H5P_FILE_ACCESS));
  H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG);
  f.id_ = Id(H5Fcreate(f.temp_.c_str(), H5F_ACC_TRUNC, fcpl.get(), fapl.get()));
  if (!f.id_.valid()) throw Error(f.file_ + ": cannot create file (is the directory writable?)");
  f.writing_ = true;
  return f;
}

File File::open_read(const std::filesystem::path& path) {
  quiet_hdf5_errors();
  File f;
  f.final_ = path;
  f.file_ = path.string();
  if (!std::filesystem::exists(path)) throw Error(f.file_ + ": file not found");
  if (H5Fis_hdf5(path.c_str()) <= 0) throw Error(f.file_ + ": not an HDF5 file");
  Id fapl(H5Pcreate(H5P_FILE_ACCESS));
  H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG);
  f.id_ = Id(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get()));
  if (!f.id_.valid()) throw Error(f.file_ + ": cannot open HDF5 file (truncated or corrupt?)");
  return f;
}

void File::commit() {
  if (!writing_) return;
  if (H5Fflush(id_.get(), H5F_SCOPE_GLOBAL) < 0) throw Error(file_ + ": flush failed");
  id_.reset();
  std::error_code ec;
  std::filesystem::rename(temp_, final_, ec);
  if (ec) throw Error(file_ + ": cannot move temporary into place: " + ec.message());
  writing_ = false;
}

File::~File() {
  if (writing_) {
    // Not committed: an exception is unwinding. Leave nothing behind that looks complete.
    id_.reset();
    std::error_code ec;
    std::filesystem::remove(temp_, ec);
  }
}

}  // namespace h5
}  // namespace finverse
