// Levenberg-Marquardt for least squares over a chain of latent points with a shared border:
// parameters p = (x_1 .. x_T, s), each x_t a 3-vector, whose residuals couple x_t with at most
// its neighbours x_{t-1}, x_{t+1}, and any x_t with the M border parameters s. The
// Gauss-Newton normal equations J^T J dp = -J^T r then have the shape
//
//   [ A    B ] [dx]   [-g_x]     A: block tridiagonal (3 x 3 blocks), 3T x 3T
//   [ B^T  C ] [ds] = [-g_s]     B: 3T x M, dense;  C: M x M, dense
//
// and are solved by eliminating the chain: A's sparse Cholesky (Eigen, O(T)), then the
// M x M Schur complement C - B^T A^-1 B (dense Cholesky), O(T M^2 + M^3) per step.
//
// Why not Ceres: sequence inference with posture adaptation (prior/model/inference.h) is this
// shape with M = 2 D = 86 style parameters each touching all T frames. Ceres forms J^T J
// and factors it generically; its linear solver took 7.5 of 43.5 ms per inference there
// (12 solves), and none of its solvers (sparse normal Cholesky with Eigen or SuiteSparse,
// dense normal Cholesky, DENSE_SCHUR with the style eliminated, CGNR) was faster without
// changing the result. This solver assembles the blocks directly from the model's Jacobians.
//
// The iteration follows Ceres's Levenberg-Marquardt defaults, so a problem solved either
// way takes the same steps (tests/prior/numerics/chain_least_squares_test.cc checks it): Jacobi
// column scaling fixed at the start, damping diag(J^T J)/radius clamped to [1e-6, 1e32],
// radius 1e4 at the start, grown by 1/max(1/3, 1 - (2 rho - 1)^3) on a step whose actual
// over predicted decrease rho exceeds 1e-3, else shrunk by 2, 4, 8, ...; it stops at
// max_iterations (rejected steps count), or when |cost change| <= 1e-6 cost, the step's
// norm <= 1e-8 (|p| + 1e-8), or the gradient's max norm <= 1e-10.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "prior/numerics/termination.h"

namespace jgpm {

// J^T J and J^T r at one point, blocked as above. `cost` is 1/2 |r|^2.
struct ChainNormalEquations {
  std::vector<Eigen::Matrix3d> diagonal;  // A_tt, T of them
  std::vector<Eigen::Matrix3d> lower;     // A_{t,t-1} (rows of x_t, columns of x_{t-1}), T - 1
  Eigen::MatrixXd border;                 // B, 3T x M
  Eigen::MatrixXd corner;                 // C, M x M (both triangles)
  Eigen::VectorXd gradient;               // J^T r, 3T + M
  double cost = 0;

  // Zero blocks for T frames and M border parameters.
  void Reset(int frames, int border_size);
  int NumFrames() const { return static_cast<int>(diagonal.size()); }
  int BorderSize() const { return static_cast<int>(corner.rows()); }
  Eigen::VectorXd Diagonal() const;  // of J^T J
  // The whole matrix, dense (for tests and small problems).
  Eigen::MatrixXd Dense() const;
};

class ChainLeastSquares {
 public:
  virtual ~ChainLeastSquares() = default;
  virtual int NumFrames() const = 0;
  virtual int BorderSize() const = 0;
  // 1/2 |r(p)|^2; false if it is not finite.
  virtual bool Cost(const Eigen::VectorXd& p, double* cost) = 0;
  // The normal equations at p; false if they are not finite.
  virtual bool Linearize(const Eigen::VectorXd& p, ChainNormalEquations* equations) = 0;
};

// Solves (J^T J + diag(damping)) dp = -J^T r by the elimination above. False if the matrix
// is not positive definite.
bool SolveChainNormalEquations(const ChainNormalEquations& equations, const Eigen::VectorXd& damping,
                               Eigen::VectorXd* step);

struct ChainSolveSummary {
  double initial_cost = 0, final_cost = 0;
  int iterations = 0;  // steps tried, accepted or not, as Ceres counts them
  Termination termination = Termination::kNoConvergence;
  std::string message;
};

// Minimises from `p` (3T + M entries) in place; `p` stays at the last accepted point.
ChainSolveSummary MinimizeChain(ChainLeastSquares& problem, int max_iterations, Eigen::VectorXd* p);

}  // namespace jgpm
