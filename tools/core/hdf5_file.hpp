// RAII wrapper over the HDF5 C API (Debian has no HighFive): files, groups, datasets and
// attributes, with the conventions of DESIGN.md section 3 built in:
//   - object time tracking off, so the same content gives the same bytes;
//   - deflate + shuffle compression for datasets large enough to gain from it;
//   - atomic creation: File::create writes `<name>.tmp` and commit() renames it into place,
//     so a writer that dies leaves nothing under the final name;
//   - every failure becomes a one-line finverse::Error naming the file and object.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/nd_array.hpp"

namespace finverse::h5 {

using hid = std::int64_t;  // hid_t without pulling hdf5.h into every translation unit

enum class DType { f64, f32, i64, i32, u8, str, other };
std::string to_string(DType t);

// Owns one HDF5 identifier and closes it with the matching H5*close.
class Id {
 public:
  Id() = default;
  explicit Id(hid id) : id_(id) {}
  Id(const Id&) = delete;
  Id& operator=(const Id&) = delete;
  Id(Id&& o) noexcept : id_(o.id_) { o.id_ = -1; }
  Id& operator=(Id&& o) noexcept;
  ~Id();
  hid get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  void reset();

 private:
  hid id_ = -1;
};

struct DatasetInfo {
  DType dtype = DType::other;
  std::vector<std::size_t> shape;
};

struct WriteOptions {
  std::string units;     // stored as the dataset's `units` attribute when not empty
  bool compress = true;  // deflate+shuffle when the dataset has >= 4096 elements
};

class Group {
 public:
  // Children. `path` may be nested ("a/b"); create_group makes missing parents.
  Group create_group(const std::string& path);
  Group group(const std::string& path) const;
  bool exists(const std::string& path) const;
  bool is_dataset(const std::string& path) const;
  bool is_group(const std::string& path) const;
  std::vector<std::string> children() const;  // sorted names of direct children

  // Datasets. Shapes are row-major; rank 0 is a scalar.
  void write(const std::string& name, const NdArray<double>& a, const WriteOptions& o = {});
  void write(const std::string& name, const NdArray<float>& a, const WriteOptions& o = {});
  void write(const std::string& name, const NdArray<std::int64_t>& a, const WriteOptions& o = {});
  void write(const std::string& name, const NdArray<std::int32_t>& a, const WriteOptions& o = {});
  void write(const std::string& name, const NdArray<std::uint8_t>& a, const WriteOptions& o = {});
  void write(const std::string& name, const std::vector<std::string>& strings);
  void write_scalar(const std::string& name, double value, const std::string& units = "");

  DatasetInfo info(const std::string& name) const;
  // Reads convert to the requested type (HDF5 converts numeric types); the contract checker
  // is where stored dtypes are enforced.
  NdArray<double> read_f64(const std::string& name) const;
  NdArray<std::int64_t> read_i64(const std::string& name) const;
  NdArray<std::int32_t> read_i32(const std::string& name) const;
  NdArray<std::uint8_t> read_u8(const std::string& name) const;
  std::vector<std::string> read_strings(const std::string& name) const;
  double read_scalar(const std::string& name) const;

  // Attributes on this group (object ".") or on a child object.
  void set_attr(const std::string& object, const std::string& key, const std::string& value);
  void set_attr(const std::string& object, const std::string& key, double value);
  void set_attr(const std::string& object, const std::string& key, std::int64_t value);
  bool has_attr(const std::string& object, const std::string& key) const;
  std::vector<std::string> attr_names(const std::string& object) const;
  std::optional<std::string> attr_string(const std::string& object, const std::string& key) const;
  std::optional<double> attr_double(const std::string& object, const std::string& key) const;
  std::optional<std::int64_t> attr_int(const std::string& object, const std::string& key) const;
  // Attribute type and size, for comparisons that must not assume a type.
  DatasetInfo attr_info(const std::string& object, const std::string& key) const;
  NdArray<double> attr_f64(const std::string& object, const std::string& key) const;

  const std::string& filename() const { return file_; }
  const std::string& path() const { return path_; }
  std::string child_path(const std::string& name) const;  // absolute path of a child
  hid id() const { return id_.get(); }

 protected:
  Group() = default;
  Group(Id id, std::string file, std::string path) : id_(std::move(id)), file_(std::move(file)), path_(std::move(path)) {}
  template <class T>
  void write_numeric(const std::string& name, const NdArray<T>& a, const WriteOptions& o);
  template <class T>
  NdArray<T> read_numeric(const std::string& name) const;
  void ensure_parents(const std::string& path);  // untimed intermediate groups
  [[noreturn]] void fail(const std::string& object, const std::string& what) const;

  Id id_;
  std::string file_;
  std::string path_ = "/";
};

class File : public Group {
 public:
  // New file written to `<final>.tmp`; it appears under `final` only on commit().
  static File create(const std::filesystem::path& final_path);
  static File open_read(const std::filesystem::path& path);

  File(File&& o) noexcept
      : Group(std::move(o)), final_(std::move(o.final_)), temp_(std::move(o.temp_)), writing_(o.writing_) {
    o.writing_ = false;
  }
  File& operator=(File&&) = delete;
  ~File();

  // Flushes, closes and renames the temporary into place. Groups obtained from this file must
  // not be used afterwards.
  void commit();
  const std::filesystem::path& final_path() const { return final_; }

 private:
  File() = default;
  std::filesystem::path final_;
  std::filesystem::path temp_;
  bool writing_ = false;
};

// Silences HDF5's own error-stack printing (we report through finverse::Error). Idempotent.
void quiet_hdf5_errors();

}  // namespace finverse::h5
