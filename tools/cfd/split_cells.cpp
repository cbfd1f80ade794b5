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

#include "cfd/cut_faces.hpp"

namespace finverse::cfd {

std::vector<std::array<int, 3>> split_cells(const std::vector<SurfacePiece>& pieces,
                                            const std::vector<std::array<int, 3>>& triangles) {
  // Mesh edges by their sorted vertex pair.
  std::unordered_map<long long, int> edge_id;
  std::vector<std::array<int, 3>> tri_edge(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int e = 0; e < 3; ++e) {
      const long long a = triangles[t][static_cast<std::size_t>(e)], b = triangles[t][static_cast<std::size_t>((e + 1) % 3)];
      const long long key = std::min(a, b) * (1LL << 31) + std::max(a, b);
      const auto [it, added] = edge_id.try_emplace(key, static_cast<int>(edge_id.size()));
      tri_edge[t][static_cast<std::size_t>(e)] = it->second;
    }
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
  std::unordered_map<int, std::size_t> along;  // mesh edge -> a piece of this cell running along it
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
    std::vector<bool> counts(last - first);
    for (std::size_t n = first; n < last; ++n) counts[n - first] = size(n) > 1e-9 * largest;
    for (std::size_t n = first; n < last; ++n) {
      if (!counts[n - first]) continue;
      const SurfacePiece& p = pieces[order[n]];
      for (int e = 0; e < 3; ++e) {
        if (!(p.edges & (1u << e))) continue;
        const auto [it, added] = along.try_emplace(tri_edge[static_cast<std::size_t>(p.triangle)][static_cast<std::size_t>(e)], order[n]);
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
