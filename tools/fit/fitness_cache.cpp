// The exact-key objective cache (fitness_cache.hpp).
#include "fit/fitness_cache.hpp"

#include <cstring>

namespace finverse::fit {

FitnessCache::Key FitnessCache::key_of(const Eigen::VectorXd& z) {
  Key key(static_cast<std::size_t>(z.size()));
  std::memcpy(key.data(), z.data(), key.size() * sizeof(double));
  return key;
}

std::size_t FitnessCache::KeyHash::operator()(const Key& key) const {
  // FNV-1a over the 64-bit words, mixed: cheap and good enough for a few 10^4 entries.
  std::uint64_t h = 1469598103934665603ull;
  for (std::uint64_t w : key) {
    h ^= w + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    h *= 1099511628211ull;
  }
  return static_cast<std::size_t>(h);
}

std::optional<double> FitnessCache::find(const Eigen::VectorXd& z) {
  const Key key = key_of(z);
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = values_.find(key);
  if (it == values_.end()) {
    ++misses_;
    return std::nullopt;
  }
  ++hits_;
  return it->second;
}

std::optional<double> FitnessCache::peek(const Eigen::VectorXd& z) const {
  const Key key = key_of(z);
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = values_.find(key);
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

void FitnessCache::insert(const Eigen::VectorXd& z, double objective) {
  Key key = key_of(z);
  std::lock_guard<std::mutex> lock(mutex_);
  if (values_.emplace(key, objective).second) order_.push_back(std::move(key));
}

void FitnessCache::count_hit() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++hits_;
}

void FitnessCache::count_miss() {
  std::lock_guard<std::mutex> lock(mutex_);
  ++misses_;
}

void FitnessCache::restore_counts(long hits, long misses) {
  std::lock_guard<std::mutex> lock(mutex_);
  hits_ = hits;
  misses_ = misses;
}

long FitnessCache::hits() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return hits_;
}

long FitnessCache::misses() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return misses_;
}

std::size_t FitnessCache::size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return values_.size();
}

std::vector<std::pair<Eigen::VectorXd, double>> FitnessCache::entries() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<std::pair<Eigen::VectorXd, double>> out;
  out.reserve(order_.size());
  for (const Key& key : order_) {
    Eigen::VectorXd z(static_cast<Eigen::Index>(key.size()));
    std::memcpy(z.data(), key.data(), key.size() * sizeof(double));
    out.emplace_back(std::move(z), values_.at(key));
  }
  return out;
}

void FitnessCache::clear() {
  std::lock_guard<std::mutex> lock(mutex_);
  values_.clear();
  order_.clear();
  hits_ = misses_ = 0;
}

}  // namespace finverse::fit
