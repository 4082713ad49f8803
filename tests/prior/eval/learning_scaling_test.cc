// The scaling benchmark's pieces (prior/eval/learning_scaling.h): its synthetic problem is a
// valid GP problem whose sparse bound with M = N inducing inputs at the latent points equals
// the exact objective (the bound's oracle), the timing reports the objective it evaluated,
// learning to convergence starts from the problem's objective and ends by the trainer's rule
// or its budget, and the chart draws the exact series in red, the first sparse one in blue.
#include "prior/eval/learning_scaling.h"

#include <gtest/gtest.h>

namespace jgpm {
namespace {

ObjectiveValue Evaluate(const SyntheticGpProblem& problem, const GpParameters& params) {
  ObjectiveTerms terms;
  terms.channel_scales = terms.dynamics = true;
  terms.inducing_jitter = 0;  // so that U = X gives the exact objective to round-off
  const GpObjective objective(problem.y, problem.sequences, nullptr, terms);
  return objective.Evaluate(params, nullptr);
}

TEST(LearningScaling, SyntheticProblemsBoundEqualsExactWithEveryPointInducing) {
  const SyntheticGpProblem sparse = MakeSyntheticGpProblem(90, 90);
  ASSERT_EQ(sparse.params.u.rows(), 90);
  EXPECT_EQ(sparse.params.u, sparse.params.x);
  ASSERT_EQ(sparse.sequences.size(), 3u);
  EXPECT_EQ(sparse.sequences[2].first, 60);
  GpParameters exact = sparse.params;
  exact.u.resize(0, 3);
  exact.u_dynamics.resize(0, 3);
  const ObjectiveValue a = Evaluate(sparse, sparse.params), b = Evaluate(sparse, exact);
  ASSERT_TRUE(a.ok && b.ok) << a.why << b.why;
  EXPECT_NEAR(a.total, b.total, 1e-8 * std::abs(b.total));
  // With fewer inducing inputs the bound lies above the exact objective.
  const SyntheticGpProblem fewer = MakeSyntheticGpProblem(90, 20);
  EXPECT_GT(Evaluate(fewer, fewer.params).total, b.total);
}

TEST(LearningScaling, TimingReportsTheObjectiveItEvaluated) {
  const ScalingPoint p = TimeObjectiveEvaluation(60, 0, 2);
  EXPECT_EQ(p.n, 60);
  EXPECT_EQ(p.m, 0);
  EXPECT_GT(p.seconds, 0);
  const SyntheticGpProblem problem = MakeSyntheticGpProblem(60, 0);
  EXPECT_DOUBLE_EQ(p.objective, Evaluate(problem, problem.params).total);
}

TEST(LearningScaling, LearningToConvergenceStartsAtTheProblemAndStopsByItsRule) {
  for (const int m : {0, 10}) {
    const ConvergencePoint c = TimeToConverge(60, m, 120);
    EXPECT_EQ(c.n, 60);
    EXPECT_EQ(c.m, m);
    EXPECT_EQ(c.termination, Termination::kConverged) << "M " << m;
    EXPECT_GT(c.iterations, 50) << "M " << m;  // the plateau rule looks back 50 iterations
    const SyntheticGpProblem problem = MakeSyntheticGpProblem(60, m);
    ObjectiveTerms terms;
    terms.channel_scales = terms.dynamics = true;
    const double start = GpObjective(problem.y, problem.sequences, nullptr, terms).Evaluate(problem.params, nullptr).total;
    EXPECT_DOUBLE_EQ(c.initial_objective, start);
    EXPECT_LT(c.final_objective, c.initial_objective);
  }
  // A budget already spent stops it at the first iteration.
  const ConvergencePoint stopped = TimeToConverge(60, 10, 1e-9);
  EXPECT_EQ(stopped.termination, Termination::kStopped);
  EXPECT_LE(stopped.iterations, 1);
}

TEST(LearningScaling, ChartDrawsTheExactSeriesInRedAndSparseInBlue) {
  const cv::Mat image = ScalingPlot({{100, 0, 0.01, 0}, {200, 0, 0.08, 0}, {100, 20, 0.001, 0}, {200, 20, 0.002, 0}});
  ASSERT_EQ(image.type(), CV_8UC3);
  int red = 0, blue = 0;
  for (int r = 0; r < image.rows; ++r) {
    for (int c = 0; c < image.cols; ++c) {
      const cv::Vec3b& p = image.at<cv::Vec3b>(r, c);
      red += p == cv::Vec3b(60, 60, 200);
      blue += p == cv::Vec3b(180, 110, 30);
    }
  }
  EXPECT_GT(red, 50);  // each line is a few hundred pixels long
  EXPECT_GT(blue, 50);
}

}  // namespace
}  // namespace jgpm
