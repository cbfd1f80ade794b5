// The cells a closed triangulated surface splits into separate fluid parts (cut_faces.hpp): the
// surface's pieces in a cell are grouped into sheets, two pieces joined where they run along the
// same mesh edge inside the cell (the part of an edge inside a box is one segment, so two pieces
// that both run along it share it). A cell with two or more sheets holds fluid on both sides of a
// thin body, which the cut-cell balance must not join (cut_cell_balance.cpp). Pieces that touch
// only at a point stay apart, so a doubtful cell counts as split, the staircase's choice; slivers
// (a triangle's edge through a corner of the cell) are left out.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "cfd/immersed/cut_faces.hpp"

namespace finverse::cfd {

std::vector<std::array<int, 3>> split_cells(const std::vector<SurfacePiece>& pieces, const SurfaceGeometry& body) {
  // A mesh edge is named by the two triangles that share it (the surface's own adjacency).
  const long long triangles = body.triangles();
  const auto edge_key = [&](int t, int e) {
    const long long a = t, b = body.neighbour(t, e);
    return std::min(a, b) * triangles + std::max(a, b);
  };
  // Pieces in cell order, so that each cell's are contiguous.
  std::vector<std::size_t> order(pieces.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return pieces[a].cell < pieces[b].cell; });
  std::vector<std::size_t> parent(pieces.size());
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  const auto root = [&](std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  std::vector<std::array<int, 3>> out;
  std::unordered_map<long long, std::size_t> along;  // mesh edge -> a piece of this cell running along it
  std::vector<bool> counts;
  for (std::size_t first = 0; first < order.size();) {
    std::size_t last = first;
    const auto& cell = pieces[order[first]].cell;
    while (last < order.size() && pieces[order[last]].cell == cell) ++last;
    along.clear();
    // A sliver where a triangle's edge runs through a corner of the cell is no sheet.
    const auto size = [&](std::size_t n) {
      const Vec3& a = pieces[order[n]].area_vector;
      return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    };
    double largest = 0;
    for (std::size_t n = first; n < last; ++n) largest = std::max(largest, size(n));
    counts.assign(last - first, false);
    for (std::size_t n = first; n < last; ++n) counts[n - first] = size(n) > 1e-9 * largest;
    for (std::size_t n = first; n < last; ++n) {
      if (!counts[n - first]) continue;
      const SurfacePiece& p = pieces[order[n]];
      for (int e = 0; e < 3; ++e) {
        if (!(p.edges & (1u << e))) continue;
        const auto [it, added] = along.try_emplace(edge_key(p.triangle, e), order[n]);
        if (!added) parent[root(order[n])] = root(it->second);
      }
    }
    std::size_t sheets = 0;
    for (std::size_t n = first; n < last; ++n) sheets += counts[n - first] && root(order[n]) == order[n];
    if (sheets >= 2) out.push_back(cell);
    first = last;
  }
  return out;
}

}  // namespace finverse::cfd
