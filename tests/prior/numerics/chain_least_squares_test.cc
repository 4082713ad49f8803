// The chain solver against oracles: its structured solve against a dense Cholesky of the
// same matrix, and its Levenberg-Marquardt against Ceres's on the same residuals (same
// iterates, not only the same minimum).
#include "prior/numerics/chain_least_squares.h"

#include <cmath>
#include <random>

#include <ceres/ceres.h>
#include <Eigen/Cholesky>
#include <gtest/gtest.h>

namespace jgpm {
namespace {

// A random symmetric positive definite system of chain shape.
ChainNormalEquations RandomEquations(int frames, int border, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  const int n = 3 * frames + border;
  // J with the chain's pattern: rows that see x_{t-1}, x_t and the border.
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(6 * frames + 2 * border, n);
  for (int f = 0; f < frames; ++f) {
    for (int row = 6 * f; row < 6 * f + 6; ++row) {
      for (int c = std::max(f - 1, 0) * 3; c < 3 * f + 3; ++c) j(row, c) = normal(rng);
      for (int c = 3 * frames; c < n; ++c) j(row, c) = normal(rng);
    }
  }
  for (int row = 6 * frames; row < j.rows(); ++row) {
    for (int c = 3 * frames; c < n; ++c) j(row, c) = normal(rng);
  }
  const Eigen::MatrixXd h = j.transpose() * j;
  ChainNormalEquations e;
  e.Reset(frames, border);
  for (int f = 0; f < frames; ++f) {
    e.diagonal[f] = h.block<3, 3>(3 * f, 3 * f);
    if (f > 0) e.lower[f - 1] = h.block<3, 3>(3 * f, 3 * (f - 1));
  }
  e.border = h.topRightCorner(3 * frames, border);
  e.corner = h.bottomRightCorner(border, border);
  for (int i = 0; i < n; ++i) e.gradient[i] = normal(rng);
  return e;
}

TEST(ChainLeastSquares, SolveMatchesADenseCholesky) {
  std::mt19937 rng(3);
  for (const auto& [frames, border] : std::vector<std::pair<int, int>>{{1, 0}, {7, 0}, {7, 5}, {30, 86}, {2, 1}}) {
    const ChainNormalEquations e = RandomEquations(frames, border, rng);
    const int n = 3 * frames + border;
    Eigen::VectorXd damping = Eigen::VectorXd::LinSpaced(n, 1e-3, 1.0);
    Eigen::MatrixXd dense = e.Dense();
    EXPECT_LT((dense - dense.transpose()).norm(), 1e-12);
    dense.diagonal() += damping;
    const Eigen::VectorXd expected = dense.llt().solve(-e.gradient);
    Eigen::VectorXd step;
    ASSERT_TRUE(SolveChainNormalEquations(e, damping, &step));
    EXPECT_LT((step - expected).norm(), 1e-9 * expected.norm()) << frames << " frames, border " << border;
  }
}

TEST(ChainLeastSquares, SolveRefusesAnIndefiniteMatrix) {
  std::mt19937 rng(4);
  ChainNormalEquations e = RandomEquations(4, 3, rng);
  Eigen::VectorXd step;
  e.corner(1, 1) = -1e6;  // the Schur complement is indefinite
  EXPECT_FALSE(SolveChainNormalEquations(e, Eigen::VectorXd::Zero(15), &step));
  e = RandomEquations(4, 3, rng);
  e.diagonal[2](0, 0) = -1e6;  // the chain is
  EXPECT_FALSE(SolveChainNormalEquations(e, Eigen::VectorXd::Zero(15), &step));
}

// A nonlinear chain: per frame, 4 residuals a_i sin(x_t . b_i) + s . c_i - y_i; between
// frames, x_t - 0.9 x_{t-1}; on the border, s / 2. One Ceres cost function for all of it
// (numeric derivatives are fine for an oracle of the iteration).
struct ChainResiduals {
  int frames, border;
  Eigen::MatrixXd a, b, c, y;  // a, y: 4T; b: 4T x 3; c: 4T x M
  int NumResiduals() const { return 4 * frames + 3 * (frames - 1) + border; }
  template <typename T>
  bool operator()(const T* const* parameters, T* residuals) const {
    const T* p = parameters[0];
    int r = 0;
    for (int f = 0; f < frames; ++f) {
      for (int i = 4 * f; i < 4 * f + 4; ++i) {
        T dot = T(0), shared = T(0);
        for (int d = 0; d < 3; ++d) dot += p[3 * f + d] * b(i, d);
        for (int k = 0; k < border; ++k) shared += p[3 * frames + k] * c(i, k);
        residuals[r++] = a(i, 0) * sin(dot) + shared - y(i, 0);
      }
    }
    for (int f = 1; f < frames; ++f) {
      for (int d = 0; d < 3; ++d) residuals[r++] = p[3 * f + d] - 0.9 * p[3 * (f - 1) + d];
    }
    for (int k = 0; k < border; ++k) residuals[r++] = 0.5 * p[3 * frames + k];
    return true;
  }
};

ChainResiduals RandomChain(int frames, int border, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  ChainResiduals chain{frames, border, {}, {}, {}, {}};
  auto random = [&](int rows, int cols, double scale) {
    Eigen::MatrixXd m(rows, cols);
    for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = scale * normal(rng);
    return m;
  };
  chain.a = random(4 * frames, 1, 2.0);
  chain.b = random(4 * frames, 3, 1.0);
  chain.c = random(4 * frames, border, 1.0);
  chain.y = random(4 * frames, 1, 1.0);
  return chain;
}

// The chain's residuals as one Ceres block on the parameters at `p`.
void AddChain(const ChainResiduals& chain, double* p, ceres::Problem* problem) {
  auto* cost = new ceres::DynamicAutoDiffCostFunction<ChainResiduals>(new ChainResiduals(chain));
  cost->AddParameterBlock(3 * chain.frames + chain.border);
  cost->SetNumResiduals(chain.NumResiduals());
  problem->AddResidualBlock(cost, nullptr, p);
}

// The chain problem through Ceres's Jacobian (evaluated by the Ceres problem itself).
class ViaCeres : public ChainLeastSquares {
 public:
  ViaCeres(const ChainResiduals& chain) : chain_(chain), p_(3 * chain.frames + chain.border) {
    AddChain(chain, p_.data(), &problem_);
  }
  int NumFrames() const override { return chain_.frames; }
  int BorderSize() const override { return chain_.border; }
  bool Cost(const Eigen::VectorXd& p, double* cost) override {
    p_ = p;
    return problem_.Evaluate({}, cost, nullptr, nullptr, nullptr);
  }
  bool Linearize(const Eigen::VectorXd& p, ChainNormalEquations* e) override {
    p_ = p;
    std::vector<double> r;
    ceres::CRSMatrix crs;
    double cost = 0;
    if (!problem_.Evaluate({}, &cost, &r, nullptr, &crs)) return false;
    Eigen::MatrixXd j = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
    for (int row = 0; row < crs.num_rows; ++row) {
      for (int i = crs.rows[row]; i < crs.rows[row + 1]; ++i) j(row, crs.cols[i]) = crs.values[i];
    }
    const Eigen::MatrixXd h = j.transpose() * j;
    const int t = chain_.frames, m = chain_.border;
    e->Reset(t, m);
    for (int f = 0; f < t; ++f) {
      e->diagonal[f] = h.block<3, 3>(3 * f, 3 * f);
      if (f > 0) e->lower[f - 1] = h.block<3, 3>(3 * f, 3 * (f - 1));
    }
    e->border = h.topRightCorner(3 * t, m);
    e->corner = h.bottomRightCorner(m, m);
    e->gradient = j.transpose() * Eigen::Map<const Eigen::VectorXd>(r.data(), static_cast<Eigen::Index>(r.size()));
    e->cost = cost;
    return true;
  }

 private:
  const ChainResiduals chain_;
  Eigen::VectorXd p_;  // the Ceres problem's parameter block
  ceres::Problem problem_;
};

TEST(ChainLeastSquares, TakesCeressStepsToCeressMinimum) {
  std::mt19937 rng(11);
  for (const auto& [frames, border] : std::vector<std::pair<int, int>>{{6, 4}, {10, 0}, {3, 8}}) {
    const ChainResiduals chain = RandomChain(frames, border, rng);
    const int n = 3 * frames + border;
    std::normal_distribution<double> normal;
    Eigen::VectorXd start(n);
    for (int i = 0; i < n; ++i) start[i] = normal(rng);
    for (const int iterations : {1, 3, 100}) {
      Eigen::VectorXd ours = start, theirs = start;
      ViaCeres problem(chain);
      const ChainSolveSummary summary = MinimizeChain(problem, iterations, &ours);

      ceres::Problem reference;
      AddChain(chain, theirs.data(), &reference);
      ceres::Solver::Options options;
      options.max_num_iterations = iterations;
      options.linear_solver_type = ceres::DENSE_QR;
      options.logging_type = ceres::SILENT;
      ceres::Solver::Summary ceres_summary;
      ceres::Solve(options, &reference, &ceres_summary);

      const std::string where = std::to_string(frames) + " frames, border " + std::to_string(border) + ", " +
                                std::to_string(iterations) + " iterations";
      EXPECT_LT((ours - theirs).norm(), 1e-7 * (1 + theirs.norm())) << where;
      EXPECT_NEAR(summary.final_cost, ceres_summary.final_cost, 1e-9 * ceres_summary.initial_cost) << where;
      EXPECT_NEAR(summary.initial_cost, ceres_summary.initial_cost, 1e-12 * ceres_summary.initial_cost) << where;
      EXPECT_EQ(summary.iterations, static_cast<int>(ceres_summary.iterations.size()) - 1) << where;
      EXPECT_EQ(summary.termination == Termination::kConverged, ceres_summary.termination_type == ceres::CONVERGENCE)
          << where << ": " << summary.message << " / " << ceres_summary.message;
      if (iterations == 100) {
        EXPECT_EQ(summary.termination, Termination::kConverged) << where;
      }
    }
  }
}

TEST(ChainLeastSquares, ANonFiniteStartIsANumericalFailure) {
  struct NotFinite : ChainLeastSquares {
    int NumFrames() const override { return 3; }
    int BorderSize() const override { return 2; }
    bool Cost(const Eigen::VectorXd&, double* cost) override { return *cost = std::nan(""), true; }
    bool Linearize(const Eigen::VectorXd&, ChainNormalEquations* e) override {
      e->Reset(3, 2);
      e->cost = std::nan("");
      return true;  // the solver must check, not trust this
    }
  } problem;
  Eigen::VectorXd p = Eigen::VectorXd::Zero(11);
  const ChainSolveSummary summary = MinimizeChain(problem, 10, &p);
  EXPECT_EQ(summary.termination, Termination::kNumericalFailure);
  EXPECT_FALSE(summary.message.empty());
}

}  // namespace
}  // namespace jgpm
