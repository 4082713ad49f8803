// The cheapest one-to-one pairing of rows with columns (the assignment problem): which
// tracked person is which true person in the CLEAR MOT measure, and, for several people,
// which foreground region goes to which track. Hungarian method with potentials
// (Kuhn-Munkres, O(n^2 m) for n rows <= m columns); no library we use has one.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace jgpm {

// For each row of `cost` (rows x columns, finite), the column it is paired with, or -1:
// pairs whose cost exceeds `max_cost` are left out, and every row is paired when there
// are at least as many columns (else every column). The sum of the paired costs is the
// least over all such pairings before the `max_cost` cut. Throws std::invalid_argument
// for a non-finite cost.
std::vector<int> MinCostAssignment(const Eigen::MatrixXd& cost, double max_cost);

}  // namespace jgpm
