// A dense row-major n-dimensional array: the in-memory form of every HDF5 dataset we read or
// write. Deliberately minimal; numerical code maps it onto Eigen where it needs algebra.
#pragma once

#include <cstddef>
#include <functional>
#include <numeric>
#include <string>
#include <vector>

namespace finverse {

template <class T>
struct NdArray {
  using value_type = T;
  std::vector<std::size_t> shape;
  std::vector<T> data;

  NdArray() = default;
  explicit NdArray(std::vector<std::size_t> s, T fill = T{})
      : shape(std::move(s)), data(element_count(shape), fill) {}
  NdArray(std::vector<std::size_t> s, std::vector<T> values) : shape(std::move(s)), data(std::move(values)) {}

  static std::size_t element_count(const std::vector<std::size_t>& s) {
    return std::accumulate(s.begin(), s.end(), std::size_t{1}, std::multiplies<>());
  }
  std::size_t size() const { return data.size(); }
  std::size_t rank() const { return shape.size(); }
  std::size_t dim(std::size_t i) const { return shape.at(i); }

  T& operator()(std::size_t i) { return data[i]; }
  const T& operator()(std::size_t i) const { return data[i]; }
  T& operator()(std::size_t i, std::size_t j) { return data[i * shape[1] + j]; }
  const T& operator()(std::size_t i, std::size_t j) const { return data[i * shape[1] + j]; }
  T& operator()(std::size_t i, std::size_t j, std::size_t k) { return data[(i * shape[1] + j) * shape[2] + k]; }
  const T& operator()(std::size_t i, std::size_t j, std::size_t k) const {
    return data[(i * shape[1] + j) * shape[2] + k];
  }
  bool operator==(const NdArray&) const = default;
};

// "[3,412,3]": how shapes appear in messages.
std::string shape_string(const std::vector<std::size_t>& shape);
// The multi-index of a flat row-major position, as "[2,7,1]".
std::string index_string(std::size_t flat, const std::vector<std::size_t>& shape);

}  // namespace finverse
