// The model's batched interface (prior/model/gait_model.h) is what the tracker and a sparse GP
// call per frame: it must give what the one-point calls give, allocate nothing once its
// workspace has grown, and give the same results from several threads at once.
#include <atomic>
#include <cstdlib>
#include <limits>
#include <thread>

#include <gtest/gtest.h>

#include "prior/model/gait_model.h"
#include "prior/prior_test_support.h"

#if defined(__SANITIZE_ADDRESS__)
#define JGPM_COUNTS_MALLOC 0  // the sanitizer owns malloc
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define JGPM_COUNTS_MALLOC 0
#endif
#endif
#ifndef JGPM_COUNTS_MALLOC
#define JGPM_COUNTS_MALLOC 1
#endif

#if JGPM_COUNTS_MALLOC
// Every allocation of the program (Eigen, the standard library) goes through malloc.
std::atomic<long> g_mallocs{0};
extern "C" void* __libc_malloc(size_t size);
extern "C" void* malloc(size_t size) {
  g_mallocs.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}
#endif

namespace jgpm {
namespace {

// Latent points near and between the training points, and a few far away.
Eigen::MatrixXd Queries(const GaitModel& model, int n) {
  Eigen::MatrixXd xs(n, 3);
  const Eigen::MatrixXd& x = model.latent();
  for (int t = 0; t < n; ++t) {
    const int i = (7 * t) % x.rows(), j = (11 * t + 3) % x.rows();
    const double w = (t % 5) / 4.0;
    xs.row(t) = (1 - w) * x.row(i) + w * x.row(j);
    if (t % 9 == 0) xs.row(t) *= 3;  // off the manifold
  }
  return xs;
}

class GaitModelBatch : public testing::TestWithParam<ModelKind> {
 protected:
  static const GaitModel& Model(ModelKind kind) {
    static std::map<ModelKind, std::unique_ptr<GaitModel>>* models = new std::map<ModelKind, std::unique_ptr<GaitModel>>;
    auto& m = (*models)[kind];
    if (!m) {  // a few iterations: the calls need a model, not a good one
      TrainingOptions options;
      options.kind = kind;
      options.full.max_iterations = 15;
      m = TrainGaitModel(test::SyntheticWalks(5, 10), test::Skeleton35(), options);
    }
    return *m;
  }
};

TEST_P(GaitModelBatch, AgreesWithTheOnePointCalls) {
  const GaitModel& model = Model(GetParam());
  const Eigen::MatrixXd xs = Queries(model, 37);
  ModelWorkspace workspace;
  Eigen::MatrixXd poses(37, model.NumChannels()), next(37, 3);
  Eigen::VectorXd density(37), prior(37);
  model.MeanPoses(xs, poses, &workspace);
  model.LogDensities(xs, density, &workspace);
  model.LogPriors(xs, prior, &workspace);
  model.NextLatents(xs, next, &workspace);
  EXPECT_EQ(poses, model.MeanPoses(xs));
  for (int t = 0; t < 37; ++t) {
    const Eigen::Vector3d x = xs.row(t).transpose();
    Eigen::VectorXd pose;
    model.Predict(x, &pose, nullptr);
    EXPECT_LT((poses.row(t).transpose() - pose).cwiseAbs().maxCoeff(), 1e-9) << t;
    EXPECT_NEAR(density[t], model.LogDensity(x, nullptr), 1e-12 * (1 + std::abs(density[t]))) << t;
    EXPECT_NEAR(prior[t], model.LogPrior(x, nullptr), 1e-9 * (1 + std::abs(prior[t]))) << t;
    EXPECT_LT((next.row(t).transpose() - model.NextLatent(x, nullptr)).norm(), 1e-12 * (1 + x.norm())) << t;
  }
}

TEST_P(GaitModelBatch, AllocatesNothingOnceTheWorkspaceHasGrown) {
#if !JGPM_COUNTS_MALLOC
  GTEST_SKIP() << "malloc belongs to the sanitizer in this build";
#else
  const GaitModel& model = Model(GetParam());
  const Eigen::MatrixXd xs = Queries(model, 64);
  ModelWorkspace workspace;
  Eigen::MatrixXd poses(64, model.NumChannels()), next(64, 3);
  Eigen::VectorXd density(64), prior(64);
  auto all = [&](int rows) {
    model.MeanPoses(xs.topRows(rows), poses.topRows(rows), &workspace);
    model.LogDensities(xs.topRows(rows), density.head(rows), &workspace);
    model.LogPriors(xs.topRows(rows), prior.head(rows), &workspace);
    model.NextLatents(xs.topRows(rows), next.topRows(rows), &workspace);
  };
  {  // the count sees allocations
    const long start = g_mallocs.load();
    const Eigen::VectorXd probe = Eigen::VectorXd::LinSpaced(1000, 0, 1);
    EXPECT_GT(g_mallocs.load() - start, 0) << probe.sum();
  }
  all(64);  // grows the workspace
  const long before = g_mallocs.load();
  all(64);
  all(17);  // smaller batches reuse it
  EXPECT_EQ(g_mallocs.load() - before, 0);
#endif
}

TEST_P(GaitModelBatch, SameResultsFromManyThreads) {
  const GaitModel& model = Model(GetParam());
  const Eigen::MatrixXd xs = Queries(model, 50);
  ModelWorkspace workspace;
  Eigen::MatrixXd expected(50, model.NumChannels());
  Eigen::VectorXd expected_prior(50);
  model.MeanPoses(xs, expected, &workspace);
  model.LogPriors(xs, expected_prior, &workspace);
  std::atomic<int> mismatches{0};
  auto work = [&] {
    ModelWorkspace own;
    Eigen::MatrixXd poses(50, model.NumChannels());
    Eigen::VectorXd prior(50);
    for (int repeat = 0; repeat < 20; ++repeat) {
      model.MeanPoses(xs, poses, &own);
      model.LogPriors(xs, prior, &own);
      mismatches += poses != expected || prior != expected_prior;
    }
  };
  std::thread a(work), b(work), c(work);
  a.join();
  b.join();
  c.join();
  EXPECT_EQ(mismatches.load(), 0);
}

// The oracle is the exact variance: the bound from the nearest points is never below it,
// equals it given every point, and tightens as more points are used (nested subsets: a GP
// conditioned on more observations never has a higher variance). The subset has the full
// factor's jitter, so it also holds for a model whose kernel needed jitter.
TEST_P(GaitModelBatch, VarianceBoundIsAboveTheExactVarianceAndTightens) {
  const GaitModel& model = Model(GetParam());
  const Eigen::MatrixXd xs = Queries(model, 45);
  const Eigen::VectorXd exact = model.Variances(xs);
  double loose = 0;
  for (int t = 0; t < xs.rows(); ++t) {
    const Eigen::Vector3d x = xs.row(t).transpose();
    double previous = std::numeric_limits<double>::infinity();
    for (int m : {4, 16, 64}) {
      const double bound = model.VarianceBound(x, m);
      EXPECT_GE(bound, exact[t] - 1e-10) << "point " << t << ", " << m << " neighbours";
      EXPECT_LE(bound, previous + 1e-10) << "point " << t << ", " << m << " neighbours";
      previous = bound;
      if (m == 4) loose = std::max(loose, bound - exact[t]);
    }
    EXPECT_NEAR(model.VarianceBound(x, model.NumPoints()), exact[t], 1e-12) << t;
  }
  // A bound that can fail: with few neighbours it is not the exact variance everywhere
  // (except for models whose variance does not depend on the data near x).
  if (GetParam() != ModelKind::kPca) {
    EXPECT_GT(loose, 1e-6);
  }
}

INSTANTIATE_TEST_SUITE_P(Kinds, GaitModelBatch,
                         testing::Values(ModelKind::kPca, ModelKind::kGplvm, ModelKind::kGpdm, ModelKind::kMljgpmTorus),
                         [](const testing::TestParamInfo<ModelKind>& info) {
                           std::string name(ModelKindName(info.param));
                           name.erase(std::remove(name.begin(), name.end(), '-'), name.end());
                           return name;
                         });

}  // namespace
}  // namespace jgpm
