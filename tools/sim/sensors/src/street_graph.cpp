#include "street_graph.hpp"

#include <algorithm>
#include <deque>

namespace twinslam::sim::detail {

std::vector<GridNode> StreetGraph::shortest_path(const GridNode& a, const GridNode& b,
                                                 const std::vector<bool>& blocked) const {
  if (!contains(a) || !contains(b)) return {};
  std::vector<int> previous(static_cast<std::size_t>(size()), -1);
  std::deque<GridNode> queue{a};
  previous[index(a)] = index(a);
  while (!queue.empty() && previous[index(b)] < 0) {
    const GridNode n = queue.front();
    queue.pop_front();
    for (const GridNode& step : kSteps) {
      const GridNode m = n + step;
      if (!contains(m) || previous[index(m)] >= 0 || (blocked[index(m)] && m != b)) continue;
      previous[index(m)] = index(n);
      queue.push_back(m);
    }
  }
  if (previous[index(b)] < 0) return {};
  std::vector<GridNode> path{b};
  while (path.back() != a) {
    const int p = previous[index(path.back())];
    path.push_back({p / ny(), p % ny()});
  }
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace twinslam::sim::detail
