#include "prior/eval/inducing_gap.h"

#include <cmath>
#include <random>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include "io/base/error.h"
#include "prior/numerics/kernel.h"
#include "prior/prior_test_support.h"

namespace jgpm {
namespace {

TEST(InducingGap, BoundTightensToTheExactObjectiveAsMGrows) {
  const auto model = test::TrainOnSyntheticWalks(ModelKind::kMljgpmTorus);
  const int n = model->data().set.NumPoints();  // 150
  const InducingGapReport r = MeasureInducingGap(*model, {3, 10, 30, 60, 100, n});
  // The exact objective is the one training minimised (same terms, topology, sequences).
  EXPECT_NEAR(r.exact, model->data().summary.final_objective, 1e-8 * std::abs(r.exact));
  EXPECT_GT(r.exact_seconds, 0);
  ASSERT_EQ(r.points.size(), 6u);
  const double tolerance = 1e-6 * std::abs(r.exact);
  for (size_t k = 0; k < r.points.size(); ++k) {
    const InducingGapPoint& p = r.points[k];
    EXPECT_GE(p.gap(), -tolerance) << "M " << p.m;  // a bound
    EXPECT_NEAR(p.bound - r.exact, p.gap(), tolerance);
    // Nested inducing sets never loosen the collapsed bound.
    if (k > 0) {
      EXPECT_LE(p.gap(), r.points[k - 1].gap() + tolerance) << "M " << p.m;
    }
  }
  EXPECT_GT(r.points[0].gap(), 1e3 * r.points.back().gap());
  // Every point inducing: the exact objective but for the jitter e on K_uu, which makes
  // Q = K (K + e I)^-1 K at most e below K on each eigenvalue, so the trace term adds at
  // most c N e / (2 sigma^2) per GP (c outputs, sigma^2 its noise) and the rest shrinks.
  const GaitModelData& data = model->data();
  const double e = data.terms.inducing_jitter;
  const int channels = data.set.NumChannels(), pairs = n - data.set.NumLayers() * data.set.NumGaits();
  const double mapping_most = channels * n * e / (2 * r.noise_std * r.noise_std);
  const double dynamics_most = 3 * pairs * e / (2 * std::exp(-data.params.log_alpha[3]));
  const InducingGapPoint& all = r.points.back();
  EXPECT_LE(all.mapping_gap, 1.01 * mapping_most);
  EXPECT_GE(all.mapping_gap, 0.5 * mapping_most);  // here the noise is small enough to show it
  EXPECT_LE(all.dynamics_gap, 1.01 * dynamics_most);
  EXPECT_GE(all.dynamics_gap, -tolerance);

  // Predictions: the exact mean is the model's own (MeanPoses at the training latents); the
  // inducing-point mean approaches it as M grows and costs less per pose at small M.
  const Eigen::MatrixXd poses = model->MeanPoses(data.params.x);
  const double model_error = (poses - data.set.y_deg).cwiseAbs().mean();
  EXPECT_NEAR(r.exact_mean_error_deg, model_error, 1e-6 * model_error + 1e-9);
  EXPECT_GT(r.points[0].mean_error_deg, 10 * r.exact_mean_error_deg);  // 3 inputs cannot fit 150 poses
  // (Not equal: the inducing jitter, 1e-6, is half this model's noise variance.)
  EXPECT_NEAR(all.mean_error_deg, r.exact_mean_error_deg, 0.2 * r.exact_mean_error_deg);
  EXPECT_GT(r.exact_mean_seconds, 0);
  EXPECT_GT(r.points[0].mean_seconds, 0);
}

TEST(InducingGap, OptimisingTheInducingInputsTightensTheBoundAndKeepsItABound) {
  const auto model = test::TrainOnSyntheticWalks(ModelKind::kMljgpmTorus);
  const InducingGapReport greedy = MeasureInducingGap(*model, {10, 30});
  const InducingGapReport r = MeasureInducingGap(*model, {10, 30}, 25);
  for (size_t k = 0; k < r.points.size(); ++k) {
    const InducingGapPoint& p = r.points[k];
    EXPECT_EQ(p.bound, greedy.points[k].bound);  // it starts from the greedy inputs
    EXPECT_EQ(greedy.points[k].optimised_bound, greedy.points[k].bound);
    EXPECT_GT(p.optimiser_iterations, 0);
    EXPECT_LE(p.optimiser_iterations, 25);
    EXPECT_LT(p.optimised_gap(r.exact), 0.9 * p.gap()) << "M " << p.m;
    EXPECT_GT(p.optimised_gap(r.exact), 0) << "M " << p.m;  // still above the exact objective
  }
}

TEST(InducingGap, RefusesPcaAndBadCounts) {
  const auto pca = test::TrainOnSyntheticWalks(ModelKind::kPca);
  EXPECT_THROW(MeasureInducingGap(*pca, {10}), InputError);
  const auto gpdm = test::TrainOnSyntheticWalks(ModelKind::kGpdm);
  EXPECT_THROW(MeasureInducingGap(*gpdm, {2}), InputError);
  EXPECT_THROW(MeasureInducingGap(*gpdm, {51}), InputError);  // N = 50
  EXPECT_EQ(MeasureInducingGap(*gpdm, {50}).points.size(), 1u);
}

}  // namespace
}  // namespace jgpm
