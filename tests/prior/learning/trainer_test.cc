// Both trainers on small synthetic problems: they reach the optimum of a GP-LVM whose
// MAP is known in closed form (PCA), improve the models' objectives, report how they
// ended, call progress, and refuse non-finite problems.
#include <atomic>
#include <numbers>
#include <random>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <Eigen/SVD>

#include <gtest/gtest.h>

#include "io/base/error.h"
#include "prior/learning/full_trainer.h"
#include "prior/learning/local_trainer.h"
#include "prior/learning/topology.h"
#include "prior/learning/training_set.h"
#include "prior/model/model_kind.h"
#include "prior/numerics/blas_threads.h"
#include "prior/prior_test_support.h"

namespace jgpm {
namespace {

struct Problem {
  TrainingSet set;
  Topology topology;
  std::unique_ptr<GpObjective> objective;
  GpParameters start;
};

Problem MakeProblem(ModelKind kind, bool nan_in_data = false) {
  Problem p;
  const ModelSpec spec = SpecFor(kind, 5);
  p.set = MakeTrainingSet(test::SyntheticGaitDataset(4, 8, 5), spec.layer_scales);
  p.topology = MakeTopology(p.set, TopologyOptions{});
  std::vector<Sequence> sequences;
  for (int s = 0; s < p.set.NumLayers() * p.set.NumGaits(); ++s) sequences.push_back({8 * s, 8});
  Eigen::MatrixXd y = p.set.y;
  if (nan_in_data) y(3, 2) = std::nan("");
  p.objective = std::make_unique<GpObjective>(y, sequences, &p.topology, spec.terms);
  p.start.x = p.topology.coordinates;
  p.start.log_beta = Eigen::Vector3d(0, 0, std::log(100.0));
  p.start.log_alpha = Eigen::Vector4d(0, 0, std::log(0.1), std::log(1e4));
  p.start.log_w = Eigen::VectorXd::Zero(5);
  return p;
}

// The oracle for both trainers: a GP-LVM with the linear mapping kernel and no other
// terms (ObjectiveTerms::linear_mapping) has PCA as its MAP, in closed form (Tipping &
// Bishop 1999, Lawrence 2005). With S = Y Y^T / D, eigenvalues l_1 >= ... >= l_N and
// eigenvectors U, and q = 3: the latent points span U_q, X^T X has the eigenvalues
// l_j - s2 (j <= q), and the noise variance s2 = 1/b3 is that of the discarded
// directions, D sum_{j>q} l_j / (D (N - q) - 2) (the 2: the prior p(b3) ~ 1/b3). There
//   f* = D/2 (sum_{j<=q} ln l_j + (N-q) ln s2) + D/2 (q + sum_{j>q} l_j / s2) + ND/2 ln 2pi - ln s2.
struct PcaOptimum {
  double objective = 0;
  double noise_variance = 0;
  Eigen::MatrixXd basis;             // N x 3, U_q
  Eigen::Vector3d latent_variances;  // eigenvalues of X^T X, descending
};

PcaOptimum LinearGplvmOptimum(const Eigen::MatrixXd& y) {
  const double n = y.rows(), d = y.cols(), q = 3;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(y * y.transpose() / d);
  const Eigen::VectorXd l = eigen.eigenvalues().reverse();  // descending
  PcaOptimum o;
  const double rest = l.tail(y.rows() - 3).sum();
  o.noise_variance = d * rest / (d * (n - q) - 2);
  o.basis = eigen.eigenvectors().rightCols(3).rowwise().reverse();
  o.latent_variances = l.head(3).array() - o.noise_variance;
  o.objective = d / 2 * (l.head(3).array().log().sum() + (n - q) * std::log(o.noise_variance)) +
                d / 2 * (q + rest / o.noise_variance) + n * d / 2 * std::log(2 * std::numbers::pi) - std::log(o.noise_variance);
  return o;
}

// Largest principal angle (radians) between the column spans of a and b.
double SubspaceAngle(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  const Eigen::MatrixXd qa = Eigen::HouseholderQR<Eigen::MatrixXd>(a).householderQ() * Eigen::MatrixXd::Identity(a.rows(), a.cols());
  const Eigen::MatrixXd qb = Eigen::HouseholderQR<Eigen::MatrixXd>(b).householderQ() * Eigen::MatrixXd::Identity(b.rows(), b.cols());
  const double cos_min = Eigen::JacobiSVD<Eigen::MatrixXd>(qa.transpose() * qb).singularValues().minCoeff();
  return std::acos(std::min(1.0, cos_min));
}

// The synthetic walks with white noise of 1 degree: their centred poses span 3 dimensions,
// and without the noise the discarded directions would have no variance (s2 = 0, the
// optimum at infinity).
struct LinearProblem {
  TrainingSet set;
  std::unique_ptr<GpObjective> objective;
  GpParameters start;
};
LinearProblem MakeLinearProblem() {
  LinearProblem p;
  GaitDataset walks = test::SyntheticGaitDataset(5, 8, 6);
  std::mt19937 random(3);
  std::normal_distribution<double> noise(0, 1);
  for (GaitTrial& trial : walks.trials) {
    for (int i = 0; i < trial.cycle.poses.size(); ++i) trial.cycle.poses.data()[i] += noise(random);
  }
  p.set = MakeTrainingSet(walks, {1.0});
  ObjectiveTerms terms;
  terms.linear_mapping = true;
  p.objective = std::make_unique<GpObjective>(p.set.y, std::vector<Sequence>{}, nullptr, terms);
  p.start.x.resize(p.set.NumPoints(), 3);
  for (int i = 0; i < p.start.x.size(); ++i) p.start.x.data()[i] = 0.3 * noise(random);
  p.start.log_beta = Eigen::Vector3d(0, 0, std::log(10.0));
  return p;
}

// The largest principal angle between span(X) and the closed form's; X^T X's eigenvalues.
struct LatentShape {
  double angle = 0;
  Eigen::Vector3d variances;
};
LatentShape ShapeOf(const Eigen::MatrixXd& x, const PcaOptimum& optimum) {
  return {SubspaceAngle(x, optimum.basis),
          Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(x.transpose() * x).eigenvalues().reverse()};
}

// The closed form is the objective's optimum: the objective there is f* and its gradient
// zero (a check of the oracle against the objective, before the trainers are held to it).
TEST(LinearGplvm, ClosedFormIsTheObjectivesOptimum) {
  const LinearProblem p = MakeLinearProblem();
  const PcaOptimum optimum = LinearGplvmOptimum(p.set.y);
  GpParameters at = p.start;
  at.x = optimum.basis * optimum.latent_variances.cwiseSqrt().asDiagonal();
  at.log_beta[2] = -std::log(optimum.noise_variance);
  GpParameters gradient;
  const ObjectiveValue value = p.objective->Evaluate(at, &gradient);
  ASSERT_TRUE(value.ok) << value.why;
  EXPECT_NEAR(value.total, optimum.objective, 1e-9 * std::abs(optimum.objective));
  EXPECT_LT(gradient.x.cwiseAbs().maxCoeff(), 1e-8);
  EXPECT_LT(std::abs(gradient.log_beta[2]), 1e-8);
}

// Full learning from random latent points reaches the closed-form optimum: the objective
// to 1e-6 of |f*| (it ends 3e-7 above f*, from 970 at the start), the latent subspace to
// 1e-3 rad of PCA's, the noise variance and the latent variances to 1e-3.
TEST(FullTrainer, ReachesTheLinearGplvmOptimum) {
  const LinearProblem p = MakeLinearProblem();
  const PcaOptimum optimum = LinearGplvmOptimum(p.set.y);
  FullTrainingOptions options;
  options.plateau_tolerance = 1e-8;
  GpParameters x = p.start;
  const TrainingSummary s = TrainFull(*p.objective, &x, options);
  const LatentShape shape = ShapeOf(x.x, optimum);
  std::cout << s.BriefReport() << "; f* " << optimum.objective << ", subspace angle " << shape.angle << " rad\n";
  EXPECT_EQ(s.termination, Termination::kConverged) << s.BriefReport();
  EXPECT_NEAR(s.final_objective, optimum.objective, 1e-6 * std::abs(optimum.objective));
  EXPECT_NEAR(p.objective->Evaluate(x, nullptr).total, optimum.objective, 1e-6 * std::abs(optimum.objective));
  EXPECT_LT(shape.angle, 1e-3);
  EXPECT_NEAR(std::exp(-x.log_beta[2]), optimum.noise_variance, 1e-3 * optimum.noise_variance);
  for (int j = 0; j < 3; ++j) {
    EXPECT_NEAR(shape.variances[j], optimum.latent_variances[j], 1e-3 * optimum.latent_variances[j]) << j;
  }
  EXPECT_EQ(x.log_beta[0], 0.0);  // held
}

// Local learning on the same problem. With every point in every neighbourhood its steps
// follow the full gradient and it reaches the optimum (to 2e-5 of |f*|; it ends 0.002
// above); with neighbourhoods of 12 of the 40 points its gradients are biased (see
// local_trainer.h) and it stops short, but closes all but 1% of the gap from the start
// (it ends 3 above f*, from 1270 above) with the subspace within 0.15 rad (0.065).
TEST(LocalTrainer, ApproachesTheLinearGplvmOptimum) {
  const LinearProblem p = MakeLinearProblem();
  const PcaOptimum optimum = LinearGplvmOptimum(p.set.y);
  for (const double fraction : {1.0, 0.3}) {
    SCOPED_TRACE("neighbourhoods of " + std::to_string(fraction) + " of the points");
    LocalTrainingOptions options;
    options.max_neighbourhood_fraction = fraction;
    const auto neighbourhoods =
        LocalNeighbourhoods(p.set, p.start.x, LocalNeighbourhoodSize(p.set.NumPoints(), options));
    GpParameters x = p.start;
    const TrainingSummary s = TrainLocal(*p.objective, neighbourhoods, &x, options);
    const LatentShape shape = ShapeOf(x.x, optimum);
    std::cout << s.BriefReport() << "; f* " << optimum.objective << ", subspace angle " << shape.angle << " rad\n";
    EXPECT_EQ(s.termination, Termination::kConverged) << s.BriefReport();
    EXPECT_NEAR(s.final_objective, p.objective->Evaluate(x, nullptr).total, 1e-9 * std::abs(s.final_objective));
    EXPECT_GE(s.final_objective, optimum.objective - 1e-9 * std::abs(optimum.objective));
    if (fraction == 1.0) {
      EXPECT_LT(s.final_objective - optimum.objective, 2e-5 * std::abs(optimum.objective));
      EXPECT_LT(shape.angle, 1e-3);
    } else {
      EXPECT_LT(s.final_objective - optimum.objective, 0.01 * (s.initial_objective - optimum.objective));
      EXPECT_LT(shape.angle, 0.15);
    }
  }
}

TEST(FullTrainer, ConvergesAndReports) {
  Problem p = MakeProblem(ModelKind::kJgpm);
  FullTrainingOptions options;
  options.progress_interval_s = 0;
  // This smooth synthetic data keeps paying a little for ever larger b1; a looser plateau.
  options.plateau_tolerance = 1e-2;
  int calls = 0, last_iteration = -1;
  std::vector<double> gains;  // the plateau window's gain at each report
  options.progress = [&](const TrainingProgress& progress) {
    ++calls;
    EXPECT_GT(progress.iteration, last_iteration);
    last_iteration = progress.iteration;
    EXPECT_EQ(progress.stage, "full");
    EXPECT_EQ(progress.plateau_tolerance, 1e-2);
    EXPECT_GE(progress.seconds_since_improvement, 0);
    gains.push_back(progress.window_improvement);
  };
  GpParameters x = p.start;
  const TrainingSummary s = TrainFull(*p.objective, &x, options);
  EXPECT_EQ(s.termination, Termination::kConverged) << s.BriefReport();
  // The progress line's convergence state is the test's: NaN until the window fills, then
  // at or above the tolerance until the report of the iteration that converged.
  ASSERT_GT(gains.size(), static_cast<size_t>(options.plateau_window));
  for (int k = 0; k < options.plateau_window; ++k) EXPECT_TRUE(std::isnan(gains[k])) << k;
  for (size_t k = options.plateau_window; k + 1 < gains.size(); ++k) EXPECT_GE(gains[k], 1e-2) << k;
  EXPECT_LT(gains.back(), 1e-2);
  EXPECT_LT(s.final_objective, s.initial_objective);
  EXPECT_NEAR(s.final_objective, p.objective->Evaluate(x, nullptr).total, 1e-9 * std::abs(s.final_objective));
  EXPECT_GT(calls, 1);
  EXPECT_NE(s.BriefReport().find("full learning: converged after"), std::string::npos);
  // The held hyper-parameters did not move.
  EXPECT_EQ(x.log_beta[1], p.start.log_beta[1]);
  EXPECT_EQ(x.log_alpha[3], p.start.log_alpha[3]);
}

TEST(WindowImprovement, IsTheRelativeGainOverTheWindow) {
  EXPECT_TRUE(std::isnan(WindowImprovement({-10, -12}, 2)));  // the window has not filled
  EXPECT_DOUBLE_EQ(WindowImprovement({-10, -12, -15}, 2), 5.0 / 15);
  EXPECT_DOUBLE_EQ(WindowImprovement({-10, -12, -15, -15}, 2), 3.0 / 15);
  EXPECT_DOUBLE_EQ(WindowImprovement({8, 4}, 1), 1.0);
}

TEST(FullTrainer, PlateauWindowStopsEarly) {
  Problem p = MakeProblem(ModelKind::kGpdm);
  FullTrainingOptions options;
  options.plateau_window = 5;
  options.plateau_tolerance = 10.0;  // any progress below 10 |f| in 5 iterations counts as a plateau
  GpParameters x = p.start;
  const TrainingSummary s = TrainFull(*p.objective, &x, options);
  EXPECT_EQ(s.termination, Termination::kConverged);
  EXPECT_EQ(s.iterations, 5);
}

TEST(FullTrainer, NonFiniteDataIsANumericalFailure) {
  Problem p = MakeProblem(ModelKind::kGplvm, /*nan_in_data=*/true);
  GpParameters x = p.start;
  x.log_alpha.resize(0);
  x.log_w.resize(0);
  const TrainingSummary s = TrainFull(*p.objective, &x, FullTrainingOptions{});
  EXPECT_EQ(s.termination, Termination::kNumericalFailure);
  EXPECT_FALSE(s.usable());
}

TEST(TrainingOptions, ChecksAcceptANullWhy) {
  LocalTrainingOptions local;
  local.neighbourhood_size = 2;
  EXPECT_FALSE(local.Check(nullptr));
  TrainingOptions options;
  options.threads = -1;
  EXPECT_FALSE(options.Check(nullptr));
  options.threads = 0;
  options.local = local;
  EXPECT_FALSE(options.Check(nullptr));
  std::string why;
  EXPECT_FALSE(options.Check(&why));
  EXPECT_NE(why.find("neighbourhood_size"), std::string::npos) << why;
}

TEST(LocalTrainer, ImprovesDeterministicallyAndReports) {
  Problem p = MakeProblem(ModelKind::kMljgpmTorus);
  LocalTrainingOptions options;
  options.max_neighbourhood_fraction = 0.3;
  options.max_steps = 2000;
  options.progress_interval_s = 0;
  int calls = 0;
  options.progress = [&](const TrainingProgress& progress) {
    ++calls;
    EXPECT_EQ(progress.stage, "local");
  };
  const auto neighbourhoods =
      LocalNeighbourhoods(p.set, p.topology.coordinates, LocalNeighbourhoodSize(p.set.NumPoints(), options));
  EXPECT_EQ(LocalNeighbourhoodSize(96, options), 28);  // min(120, 30% of 96)
  GpParameters a = p.start, b = p.start;
  const TrainingSummary s = TrainLocal(*p.objective, neighbourhoods, &a, options);
  TrainLocal(*p.objective, neighbourhoods, &b, options);
  EXPECT_LT(s.final_objective, s.initial_objective);
  EXPECT_NEAR(s.final_objective, p.objective->Evaluate(a, nullptr).total, 1e-9 * std::abs(s.final_objective));
  EXPECT_EQ(a.x, b.x);
  EXPECT_GT(calls, 0);
}

// Shrinking the steps when a check finds no improvement lets local learning settle below
// the noise floor of a constant step. One seed can go either way on a problem this small,
// so the claim is made over five. Results do not depend on the BLAS thread count, and the
// caller's thread setting is restored.
TEST(LocalTrainer, StepDecaySettlesLower) {
  Problem p = MakeProblem(ModelKind::kMljgpmTorus);
  LocalTrainingOptions options;
  options.max_neighbourhood_fraction = 0.3;
  const auto neighbourhoods =
      LocalNeighbourhoods(p.set, p.topology.coordinates, LocalNeighbourhoodSize(p.set.NumPoints(), options));
  GpParameters decayed = p.start;
  {
    const LinearAlgebraThreadScope two(2);
    const TrainingSummary s = TrainLocal(*p.objective, neighbourhoods, &decayed, options);
    EXPECT_EQ(s.termination, Termination::kConverged) << s.BriefReport();
    EXPECT_EQ(LinearAlgebraThreads(), 2);
  }
  {
    const LinearAlgebraThreadScope one(1);
    GpParameters again = p.start;
    TrainLocal(*p.objective, neighbourhoods, &again, options);
    EXPECT_EQ(again.x, decayed.x);
  }

  double sum_decayed = 0.0, sum_constant = 0.0;
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    LocalTrainingOptions o = options;
    o.seed = seed;
    GpParameters a = p.start;
    sum_decayed += TrainLocal(*p.objective, neighbourhoods, &a, o).final_objective;
    o.step_decay = 1.0;
    GpParameters b = p.start;
    sum_constant += TrainLocal(*p.objective, neighbourhoods, &b, o).final_objective;
  }
  EXPECT_LT(sum_decayed / 5, sum_constant / 5 - 0.03 * std::abs(sum_constant / 5))
      << "mean final objective, decayed " << sum_decayed / 5 << " constant " << sum_constant / 5;
}

// A used-up time budget or an interrupt ends either trainer after its first check, with
// "stopped", the reason, and parameters whose objective is the one reported.
TEST(TrainingBudget, StopsBothTrainersAndKeepsTheParameters) {
  Problem p = MakeProblem(ModelKind::kMljgpmTorus);
  std::atomic<bool> interrupted{true};
  for (const bool by_interrupt : {false, true}) {
    TrainingBudget budget;
    if (by_interrupt) {
      budget.interrupted = &interrupted;
    } else {
      budget.max_seconds = 1e-9;
    }
    const std::string why = by_interrupt ? "interrupted" : "time budget of 1e-09 s used up";
    EXPECT_EQ(budget.Exhausted(0.5), why);

    FullTrainingOptions full;
    full.budget = budget;
    GpParameters x = p.start;
    const TrainingSummary f = TrainFull(*p.objective, &x, full);
    EXPECT_EQ(f.termination, Termination::kStopped) << f.BriefReport();
    EXPECT_EQ(f.message, why);
    EXPECT_LE(f.iterations, 1);
    EXPECT_NEAR(f.final_objective, p.objective->Evaluate(x, nullptr).total, 1e-9 * std::abs(f.final_objective));

    LocalTrainingOptions local;
    local.max_neighbourhood_fraction = 0.3;
    local.budget = budget;
    const auto neighbourhoods =
        LocalNeighbourhoods(p.set, p.topology.coordinates, LocalNeighbourhoodSize(p.set.NumPoints(), local));
    x = p.start;
    const TrainingSummary l = TrainLocal(*p.objective, neighbourhoods, &x, local);
    EXPECT_EQ(l.termination, Termination::kStopped) << l.BriefReport();
    EXPECT_EQ(l.message, why);
    EXPECT_EQ(l.evaluations, 2);  // the starting point and the first check
    EXPECT_NEAR(l.final_objective, p.objective->Evaluate(x, nullptr).total, 1e-9 * std::abs(l.final_objective));
  }
  EXPECT_EQ(TrainingBudget{}.Exhausted(1e9), "");
}

// Neighbourhoods: an equal share per layer, each point's own included, compared with a
// brute-force search over the prior coordinates (ties allowed: the torus is symmetric).
TEST(LocalTrainer, NeighbourhoodsMatchBruteForce) {
  Problem p = MakeProblem(ModelKind::kMljgpmTorus);
  const auto neighbourhoods = LocalNeighbourhoods(p.set, p.topology.coordinates, 12);
  const Eigen::MatrixXd& t = p.topology.coordinates;
  for (int i = 0; i < p.set.NumPoints(); i += 5) {
    const TrainingPoint& point = p.set.points[i];
    ASSERT_EQ(neighbourhoods[i].size(), 12u);
    EXPECT_TRUE(std::binary_search(neighbourhoods[i].begin(), neighbourhoods[i].end(), i));
    for (int layer = 0; layer < 3; ++layer) {
      const Eigen::RowVector3d query = t.row(p.set.Row(layer, point.gait, point.pose));
      std::vector<double> all;
      for (int row = p.set.Row(layer, 0, 0); row < p.set.Row(layer + 1, 0, 0); ++row) {
        all.push_back((t.row(row) - query).squaredNorm());
      }
      std::sort(all.begin(), all.end());
      int chosen = 0;
      for (int row : neighbourhoods[i]) {
        if (p.set.points[row].layer != layer) continue;
        ++chosen;
        EXPECT_LE((t.row(row) - query).squaredNorm(), all[3] + 1e-12) << i;  // among the 4 nearest
      }
      EXPECT_EQ(chosen, 4) << i;
    }
  }
}


// A numerical failure part way through training is how training ended, not a bad input:
// TrainGaitModel returns the best model found before it, its summary saying so. Hyper-
// parameter steps of e^1000 overflow the kernel at the first step, so local learning's first
// check fails and the starting parameters are the best. The caller's BLAS thread count is
// the same afterwards.
TEST(TrainGaitModel, NumericalFailureKeepsTheBestModelAndRestoresThreads) {
  const int threads_before = LinearAlgebraThreads();
  TrainingOptions options;
  options.kind = ModelKind::kJgpm;
  options.learning = Learning::kLocal;
  options.threads = threads_before == 1 ? 2 : 1;
  options.local.hyper_step = 1000;
  options.local.max_neighbourhood_fraction = 0.5;
  options.local.evaluation_interval = 20;
  const GaitDataset walks = test::SyntheticWalks(4, 8);
  std::unique_ptr<GaitModel> model;
  ASSERT_NO_THROW(model = TrainGaitModel(walks, test::Skeleton35(), options));
  const TrainingSummary& s = model->data().summary;
  EXPECT_EQ(s.termination, Termination::kNumericalFailure) << s.BriefReport();
  EXPECT_FALSE(s.usable());
  EXPECT_EQ(s.final_objective, s.initial_objective);
  EXPECT_NE(s.BriefReport().find("numerical failure ("), std::string::npos) << s.BriefReport();
  // The model kept is the starting one: the topology prior's coordinates.
  EXPECT_EQ(model->latent(), model->data().prior_coordinates);
  EXPECT_EQ(LinearAlgebraThreads(), threads_before);
}

// Sparse learning end to end on a small ML-JGPM: the model file's summary says so, the
// learned model's exact objective (evaluated once at the end) is below the bound it
// minimised, as a bound must be, and it improved on the start; the inducing inputs are not
// kept (predictions are exact). Too few or too many inducing inputs are refused.
TEST(TrainGaitModel, SparseLearningReportsTheExactObjectiveBelowItsBound) {
  TrainingOptions options = test::SparseTraining(ModelKind::kMljgpmTorus, 12, 60);
  const GaitDataset walks = test::SyntheticWalks(4, 8);
  const std::unique_ptr<GaitModel> model = TrainGaitModel(walks, test::Skeleton35(), options);
  const TrainingSummary& s = model->data().summary;
  EXPECT_EQ(s.learning, Learning::kSparse);
  EXPECT_EQ(s.inducing, 12);
  EXPECT_TRUE(s.usable()) << s.BriefReport();
  EXPECT_LT(s.final_objective, s.initial_objective);
  EXPECT_LE(s.exact_objective, s.final_objective);
  EXPECT_EQ(model->data().params.u.size(), 0);
  EXPECT_NE(s.BriefReport().find("12 inducing inputs, exact objective"), std::string::npos) << s.BriefReport();
  for (int m : {2, 10000}) {
    options.inducing = m;
    EXPECT_THROW(TrainGaitModel(walks, test::Skeleton35(), options), InputError) << m;
  }
}

}  // namespace
}  // namespace jgpm
