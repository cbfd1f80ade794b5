// The process's rank share; see rank_share.hpp.
#include "cfd/parallel/rank_share.hpp"

#include <algorithm>
#include <utility>
#include <vector>

namespace finverse::cfd {

namespace {
std::shared_ptr<const RankShare>& installed() {
  static std::shared_ptr<const RankShare> share;
  return share;
}
}  // namespace

void install_rank_share(std::shared_ptr<const RankShare> share) { installed() = std::move(share); }

const RankShare* rank_share() { return installed().get(); }

void allgather_lines(const RankShare& share, const LineRange& mine, std::size_t length,
                     const std::function<double*(int j, int k)>& line) {
  const auto p = static_cast<std::size_t>(share.size()), r = static_cast<std::size_t>(share.rank());
  // Every rank's range first, then the lines, each rank's packed in its range's order (j fastest).
  std::vector<LineRange> ranges(p);
  ranges[r] = mine;
  share.allgather(reinterpret_cast<unsigned char*>(ranges.data()), std::vector<std::size_t>(p, sizeof(LineRange)));
  std::vector<std::size_t> bytes(p), at(p + 1, 0);
  for (std::size_t q = 0; q < p; ++q) {
    const std::size_t lines =
        static_cast<std::size_t>(std::max(0, ranges[q].ny())) * static_cast<std::size_t>(std::max(0, ranges[q].nz()));
    at[q + 1] = at[q] + lines * length;
    bytes[q] = lines * length * sizeof(double);
  }
  std::vector<double> all(at[p]);
  const auto copy = [&](std::size_t q, bool pack) {
    const LineRange& g = ranges[q];
    double* v = all.data() + at[q];
    for (int k = g.k0; k < g.k1; ++k)
      for (int j = g.j0; j < g.j1; ++j, v += length) {
        double* l = line(j, k);
        if (pack) std::copy_n(l, length, v);
        else std::copy_n(v, length, l);
      }
  };
  copy(r, true);
  share.allgather(reinterpret_cast<unsigned char*>(all.data()), bytes);
  for (std::size_t q = 0; q < p; ++q)
    if (q != r) copy(q, false);
}

}  // namespace finverse::cfd
