// Exact-key cache of objective values over scaled parameter vectors (DESIGN.md section 5.4): a
// GA re-creates individuals often (an offspring that neither crossover nor mutation touched is a
// copy of its parent), and an FEM evaluation costs seconds. The key is the vector's bit pattern,
// so a hit returns exactly what an evaluation would have; results never depend on the cache.
// Thread-safe; counts hits and misses of find().
#pragma once

#include <cstdint>
#include <mutex>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace finverse::fit {

class FitnessCache {
 public:
  // Counting look-up: a hit or a miss is recorded.
  std::optional<double> find(const Eigen::VectorXd& z);
  // Look-up that records nothing (for re-reading values already counted).
  std::optional<double> peek(const Eigen::VectorXd& z) const;
  void insert(const Eigen::VectorXd& z, double objective);
  // Counts kept by the caller, for look-ups made with peek() (a duplicate inside one batch is a
  // hit the cache has not seen yet).
  void count_hit();
  void count_miss();
  void restore_counts(long hits, long misses);  // from a checkpoint

  long hits() const;
  long misses() const;
  std::size_t size() const;
  // Every entry in insertion order (checkpoints store it so that counts survive a restart).
  std::vector<std::pair<Eigen::VectorXd, double>> entries() const;
  void clear();

 private:
  using Key = std::vector<std::uint64_t>;
  struct KeyHash {
    std::size_t operator()(const Key& key) const;
  };
  static Key key_of(const Eigen::VectorXd& z);

  mutable std::mutex mutex_;
  std::unordered_map<Key, double, KeyHash> values_;
  std::vector<Key> order_;  // insertion order, for entries()
  long hits_ = 0, misses_ = 0;
};

}  // namespace finverse::fit
