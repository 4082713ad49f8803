#include "tracker/filter/assignment.h"

#include <limits>
#include <stdexcept>

namespace jgpm {
namespace {

// Rows <= columns: the row potentials u, column potentials v, and the row of each column
// (1-based, 0: none), grown one row at a time along shortest augmenting paths.
std::vector<int> Hungarian(const Eigen::MatrixXd& a) {
  const int n = static_cast<int>(a.rows()), m = static_cast<int>(a.cols());
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(n + 1, 0), v(m + 1, 0);
  std::vector<int> row_of(m + 1, 0), way(m + 1, 0);
  for (int i = 1; i <= n; ++i) {
    row_of[0] = i;
    int j0 = 0;
    std::vector<double> least(m + 1, inf);
    std::vector<bool> used(m + 1, false);
    do {
      used[j0] = true;
      const int i0 = row_of[j0];
      double delta = inf;
      int j1 = 0;
      for (int j = 1; j <= m; ++j) {
        if (used[j]) continue;
        const double reduced = a(i0 - 1, j - 1) - u[i0] - v[j];
        if (reduced < least[j]) {
          least[j] = reduced;
          way[j] = j0;
        }
        if (least[j] < delta) {
          delta = least[j];
          j1 = j;
        }
      }
      for (int j = 0; j <= m; ++j) {
        if (used[j]) {
          u[row_of[j]] += delta;
          v[j] -= delta;
        } else {
          least[j] -= delta;
        }
      }
      j0 = j1;
    } while (row_of[j0] != 0);
    do {  // flip the path
      const int j1 = way[j0];
      row_of[j0] = row_of[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  std::vector<int> column(n, -1);
  for (int j = 1; j <= m; ++j)
    if (row_of[j] != 0) column[row_of[j] - 1] = j - 1;
  return column;
}

}  // namespace

std::vector<int> MinCostAssignment(const Eigen::MatrixXd& cost, double max_cost) {
  if (!cost.allFinite()) throw std::invalid_argument("MinCostAssignment: a cost is not finite");
  std::vector<int> column(cost.rows(), -1);
  if (cost.rows() == 0 || cost.cols() == 0) return column;
  if (cost.rows() <= cost.cols()) {
    column = Hungarian(cost);
  } else {
    const std::vector<int> row = Hungarian(cost.transpose());
    for (int j = 0; j < static_cast<int>(row.size()); ++j) column[row[j]] = j;
  }
  for (int i = 0; i < cost.rows(); ++i)
    if (column[i] >= 0 && cost(i, column[i]) > max_cost) column[i] = -1;
  return column;
}

}  // namespace jgpm
