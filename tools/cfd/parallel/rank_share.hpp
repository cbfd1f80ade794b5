// Loops that every rank of a whole-flow MPI run would otherwise compute alike, split over the ranks
// (issue 48, deliverable 2; docs/studies/flow_mpi.md, "The immersed surface's set-up on ranks").
//
// In a whole-flow run (rank_pressure_system.hpp) every rank holds the whole grid and rebuilds the
// immersed surface each step: the ghost cells' probes, image points and stencils, one independent
// piece of work per item. shared_for_each() gives each rank a contiguous chunk of the items, runs
// the chunk (OpenMP inside), and gathers the chunks onto every rank in rank order, so every rank
// ends with the whole array, each item computed by the same code on the same inputs: the same bits
// as one process. A failure on any rank's chunk is the first failing item's message on every rank.
//
// The interface carries no MPI: finverse_cfd stays MPI-free, and FlowRanks installs the MPI
// implementation (mpi_rank_share.hpp). Without one installed, the loop runs whole here.
#pragma once

#include <algorithm>
#include <cstddef>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "cfd/grid/line_range.hpp"
#include "core/error.hpp"

namespace finverse::cfd {

class RankShare {
 public:
  virtual ~RankShare() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  // Collective: rank r's `bytes[r]` bytes, which sit at their place in `data` on rank r, to every
  // rank, concatenated in rank order.
  virtual void allgather(unsigned char* data, const std::vector<std::size_t>& bytes) const = 0;
  // Collective: the message of the lowest rank with failed = true on every rank, or "" when none failed.
  virtual std::string first_failure(bool failed, const std::string& message) const = 0;
  // Collective: the largest of the ranks' values (exact, so the same in any order).
  virtual double max(double value) const = 0;
};

// The share of the process's whole-flow ranks (nullptr: none, the loops run whole).
void install_rank_share(std::shared_ptr<const RankShare> share);
const RankShare* rank_share();

// fn(items[m]) for every m in place. With a share installed: this rank's chunk of nearly n / size
// items, then the chunks gathered (T trivially copyable). Throws finverse::Error with the first
// failing item's message (lowest index) on every rank.
template <class T, class Fn>
void shared_for_each(std::vector<T>& items, Fn fn) {
  static_assert(std::is_trivially_copyable_v<T>, "shared_for_each: items travel as bytes");
  const RankShare* share = rank_share();
  const std::size_t n = items.size();
  const auto p = static_cast<std::size_t>(share ? share->size() : 1), r = static_cast<std::size_t>(share ? share->rank() : 0);
  const auto edge = [&](std::size_t q) { return n / p * q + std::min(q, n % p); };  // the first n mod p chunks one longer
  const long m0 = static_cast<long>(edge(r)), m1 = static_cast<long>(edge(r + 1));
  long failed_at = std::numeric_limits<long>::max();
  std::string error;
#pragma omp parallel for schedule(dynamic, 16)
  for (long m = m0; m < m1; ++m) {
    try {
      fn(items[static_cast<std::size_t>(m)]);
    } catch (const std::exception& e) {
#pragma omp critical(shared_for_each_error)
      if (m < failed_at) failed_at = m, error = *e.what() ? e.what() : "an item of a shared loop failed";
    }
  }
  if (!share) {
    if (!error.empty()) throw Error(error);
    return;
  }
  const std::string first = share->first_failure(!error.empty(), error);
  if (!first.empty()) throw Error(first);
  std::vector<std::size_t> bytes(p);
  for (std::size_t q = 0; q < p; ++q) bytes[q] = (edge(q + 1) - edge(q)) * sizeof(T);
  share->allgather(reinterpret_cast<unsigned char*>(items.data()), bytes);
}

// Collective: each rank's `mine` lines of an array onto every rank, in place (line(j, k): where
// line (j, k)'s `length` values start). The ranks' ranges may overlap where their values agree
// (a face two blocks share); lines in no rank's range keep their values.
void allgather_lines(const RankShare& share, const LineRange& mine, std::size_t length,
                     const std::function<double*(int j, int k)>& line);

}  // namespace finverse::cfd
