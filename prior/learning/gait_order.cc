#include "prior/learning/gait_order.h"

#include <algorithm>
#include <cstdint>
#include <limits>

#include "io/base/error.h"

namespace jgpm {
namespace {

constexpr int kMaxExactNodes = 21;  // 2^20 x 20 states, about 100 MB and 2 s

// Held-Karp: dp[S][j] = shortest path from node 0 through the set S of other nodes,
// ending at j in S.
std::vector<int> ExactTour(const Eigen::MatrixXd& d) {
  const int n = static_cast<int>(d.rows());
  if (n <= 3) {
    std::vector<int> order(n);
    for (int i = 0; i < n; ++i) order[i] = i;
    return order;
  }
  const int m = n - 1;  // nodes 1..n-1 are bits 0..m-1
  const size_t subsets = size_t{1} << m;
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<float> dp(subsets * m, inf);
  std::vector<uint8_t> parent(subsets * m, 0);
  for (int j = 0; j < m; ++j) dp[(size_t{1} << j) * m + j] = static_cast<float>(d(0, j + 1));
  for (size_t s = 1; s < subsets; ++s) {
    for (int j = 0; j < m; ++j) {
      const float here = dp[s * m + j];
      if (!(s >> j & 1) || here == inf) continue;
      for (int k = 0; k < m; ++k) {
        if (s >> k & 1) continue;
        const size_t next = s | (size_t{1} << k);
        const float cost = here + static_cast<float>(d(j + 1, k + 1));
        if (cost < dp[next * m + k]) {
          dp[next * m + k] = cost;
          parent[next * m + k] = static_cast<uint8_t>(j);
        }
      }
    }
  }
  const size_t full = subsets - 1;
  int last = 0;
  float best = inf;
  for (int j = 0; j < m; ++j) {
    const float cost = dp[full * m + j] + static_cast<float>(d(j + 1, 0));
    if (cost < best) best = cost, last = j;
  }
  std::vector<int> order;
  size_t s = full;
  for (int j = last; s != 0;) {
    order.push_back(j + 1);
    const int previous = parent[s * m + j];
    s &= ~(size_t{1} << j);
    j = previous;
  }
  order.push_back(0);
  std::reverse(order.begin(), order.end());
  return order;
}

// Nearest-neighbour tours from every start, each improved by 2-opt; the best, rotated to
// start at node 0.
std::vector<int> HeuristicTour(const Eigen::MatrixXd& d) {
  const int n = static_cast<int>(d.rows());
  std::vector<int> best;
  double best_length = std::numeric_limits<double>::infinity();
  for (int start = 0; start < n; ++start) {
    std::vector<int> tour{start};
    std::vector<bool> used(n, false);
    used[start] = true;
    for (int step = 1; step < n; ++step) {
      int next = -1;
      for (int k = 0; k < n; ++k) {
        if (!used[k] && (next < 0 || d(tour.back(), k) < d(tour.back(), next))) next = k;
      }
      used[next] = true;
      tour.push_back(next);
    }
    for (bool improved = true; improved;) {
      improved = false;
      for (int i = 0; i + 2 < n; ++i) {
        for (int j = i + 2; j < n; ++j) {
          const int a = tour[i], b = tour[i + 1], c = tour[j], e = tour[(j + 1) % n];
          if (a == e) continue;
          if (d(a, c) + d(b, e) < d(a, b) + d(c, e) - 1e-12) {
            std::reverse(tour.begin() + i + 1, tour.begin() + j + 1);
            improved = true;
          }
        }
      }
    }
    const double length = PathLength(d, tour, true);
    if (length < best_length) best_length = length, best = tour;
  }
  std::rotate(best.begin(), std::find(best.begin(), best.end(), 0), best.end());
  return best;
}

std::vector<int> Tour(const Eigen::MatrixXd& d) {
  JGPM_CHECK(d.allFinite());  // NaN would leave the dynamic programme without a path
  return d.rows() <= kMaxExactNodes ? ExactTour(d) : HeuristicTour(d);
}

}  // namespace

Eigen::MatrixXd GaitDistances(const std::vector<Eigen::MatrixXd>& gaits) {
  const int n = static_cast<int>(gaits.size());
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      JGPM_CHECK(gaits[i].rows() == gaits[j].rows() && gaits[i].cols() == gaits[j].cols());
      d(i, j) = d(j, i) = std::sqrt((gaits[i] - gaits[j]).squaredNorm() / gaits[i].size());
    }
  }
  return d;
}

double PathLength(const Eigen::MatrixXd& d, const std::vector<int>& order, bool closed) {
  double length = 0;
  for (size_t i = 1; i < order.size(); ++i) length += d(order[i - 1], order[i]);
  if (closed && order.size() > 1) length += d(order.back(), order.front());
  return length;
}

std::vector<int> ShortestClosedPath(const Eigen::MatrixXd& distances) {
  JGPM_CHECK(distances.rows() == distances.cols());
  return Tour(distances);
}

std::vector<int> ShortestOpenPath(const Eigen::MatrixXd& distances) {
  JGPM_CHECK(distances.rows() == distances.cols());
  // A tour through the nodes and a dummy node at distance 0 from all of them, cut at the
  // dummy, is a shortest open path.
  const int n = static_cast<int>(distances.rows());
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(n + 1, n + 1);
  d.topLeftCorner(n, n) = distances;
  std::vector<int> tour = Tour(d);
  std::rotate(tour.begin(), std::find(tour.begin(), tour.end(), n), tour.end());
  tour.erase(tour.begin());
  return tour;
}

}  // namespace jgpm
