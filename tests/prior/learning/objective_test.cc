#include "prior/learning/objective.h"

#include <limits>
#include <memory>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "prior/learning/training_set.h"
#include "prior/model/model_kind.h"
#include "prior/prior_test_support.h"

namespace jgpm {
namespace {

// Every GP model kind's full objective, and its restriction to a subset, against central
// finite differences of the value, for every latent coordinate and hyper-parameter.
class ObjectiveGradient : public testing::TestWithParam<ModelKind> {};

std::vector<Sequence> SequencesOf(const TrainingSet& set) {
  std::vector<Sequence> sequences;
  for (int s = 0; s < set.NumLayers() * set.NumGaits(); ++s) {
    sequences.push_back({s * set.poses_per_gait, set.poses_per_gait});
  }
  return sequences;
}

GpParameters RandomParameters(const ModelSpec& spec, const TrainingSet& set, const Topology* topology) {
  std::mt19937 random(5);
  std::normal_distribution<double> noise(0, 0.05);
  GpParameters p;
  p.x = topology ? topology->coordinates : Eigen::MatrixXd::Random(set.NumPoints(), 3);
  for (int i = 0; i < p.x.size(); ++i) p.x.data()[i] += noise(random);
  p.log_beta = Eigen::Vector3d(0.1, 0.3, 2.0);
  if (spec.terms.dynamics) p.log_alpha = Eigen::Vector4d(-0.1, 0.2, -1.5, 2.5);
  if (spec.terms.channel_scales) {
    p.log_w = Eigen::VectorXd::Zero(set.NumChannels());
    for (int k = 0; k < p.log_w.size(); ++k) p.log_w[k] = noise(random);
  }
  return p;
}

void CheckAgainstFiniteDifferences(const GpObjective& objective, const GpParameters& p,
                                   const std::vector<int>& subset) {
  GpParameters gradient;
  const ObjectiveValue value = objective.EvaluateSubset(p, subset, &gradient);
  ASSERT_TRUE(value.ok) << value.why;
  std::vector<double> packed(p.Size()), analytic(p.Size());
  p.Pack(packed.data());
  gradient.Pack(analytic.data());
  GpParameters q = p;
  const double h = 1e-5;
  double worst = 0;
  std::vector<bool> free_row(p.x.rows(), false);
  for (int i : subset) free_row[i] = true;
  for (int k = 0; k < p.Size(); ++k) {
    // Latent points outside the subset are held fixed: their gradient is zero by design.
    if (k < p.x.size() && !free_row[k / 3]) {
      EXPECT_EQ(analytic[k], 0.0);
      continue;
    }
    std::vector<double> plus = packed, minus = packed;
    plus[k] += h;
    minus[k] -= h;
    q.Unpack(plus.data());
    const double f_plus = objective.EvaluateSubset(q, subset, nullptr).total;
    q.Unpack(minus.data());
    const double f_minus = objective.EvaluateSubset(q, subset, nullptr).total;
    const double fd = (f_plus - f_minus) / (2 * h);
    const double error = std::abs(fd - analytic[k]) / std::max(1.0, std::abs(fd));
    worst = std::max(worst, error);
    EXPECT_LT(error, 1e-5) << "parameter " << k << ": analytic " << analytic[k] << ", fd " << fd;
  }
  std::cout << "worst relative gradient error " << worst << " over " << p.Size() << " parameters\n";
}

TEST_P(ObjectiveGradient, FullAndSubsetMatchFiniteDifferences) {
  ModelSpec spec = SpecFor(GetParam(), 4);
  spec.terms.fixed_inverse_width = false;  // check those gradients too
  spec.terms.fixed_dynamics_noise = false;
  const GaitDataset dataset = test::SyntheticGaitDataset(4, 6, 4);
  const TrainingSet set = MakeTrainingSet(dataset, spec.layer_scales);
  Topology topology;
  if (spec.topology) {
    TopologyOptions options;
    options.shape = spec.shape;
    topology = MakeTopology(set, options);
  }
  const GpObjective objective(set.y, SequencesOf(set), spec.topology ? &topology : nullptr, spec.terms);
  const GpParameters p = RandomParameters(spec, set, spec.topology ? &topology : nullptr);
  std::vector<int> all(set.NumPoints());
  for (int i = 0; i < set.NumPoints(); ++i) all[i] = i;
  CheckAgainstFiniteDifferences(objective, p, all);
  // A subset: every third point and a run of consecutive ones (so dynamics pairs exist).
  std::vector<int> subset;
  for (int i = 0; i < set.NumPoints(); ++i) {
    if (i % 3 == 0 || (i >= 6 && i < 12)) subset.push_back(i);
  }
  CheckAgainstFiniteDifferences(objective, p, subset);
}

INSTANTIATE_TEST_SUITE_P(AllGpKinds, ObjectiveGradient,
                         testing::Values(ModelKind::kGplvm, ModelKind::kGpdm, ModelKind::kBgpdm,
                                         ModelKind::kLlgpdm, ModelKind::kJgpm,
                                         ModelKind::kMljgpmTorus, ModelKind::kMljgpmCyl),
                         [](const testing::TestParamInfo<ModelKind>& info) {
                           std::string name(ModelKindName(info.param));
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

// The linear mapping kernel (a test oracle for the trainers): its objective against finite
// differences; held, b1 and b2 have a zero gradient.
TEST(Objective, LinearMappingMatchesFiniteDifferences) {
  ObjectiveTerms terms;
  terms.linear_mapping = true;
  terms.fixed_inverse_width = false;
  const TrainingSet set = MakeTrainingSet(test::SyntheticGaitDataset(4, 6, 4), {1.0});
  GpParameters p = RandomParameters(SpecFor(ModelKind::kGplvm, 4), set, nullptr);
  p.log_beta = Eigen::Vector3d(-0.4, 0.3, 1.2);
  std::vector<int> all(set.NumPoints());
  for (int i = 0; i < set.NumPoints(); ++i) all[i] = i;
  CheckAgainstFiniteDifferences(GpObjective(set.y, {}, nullptr, terms), p, all);
  CheckAgainstFiniteDifferences(GpObjective(set.y, {}, nullptr, terms), p, {1, 2, 5, 8, 13, 21});
  terms.fixed_inverse_width = true;
  GpParameters gradient;
  ASSERT_TRUE(GpObjective(set.y, {}, nullptr, terms).Evaluate(p, &gradient).ok);
  EXPECT_EQ(gradient.log_beta[0], 0.0);
  EXPECT_EQ(gradient.log_beta[1], 0.0);
  EXPECT_NE(gradient.log_beta[2], 0.0);
}

// The mapping term of a two-point GPLVM by hand: K = [[b1 + 1/b3, c], [c, b1 + 1/b3]].
TEST(Objective, MappingTermByHand) {
  Eigen::MatrixXd y(2, 1);
  y << 1.0, -0.5;
  const GpObjective objective(y, {}, nullptr, ObjectiveTerms{});
  GpParameters p;
  p.x = Eigen::MatrixXd::Zero(2, 3);
  p.x(1, 0) = 1.0;
  p.log_beta = Eigen::Vector3d(0, 0, std::log(10.0));
  const double c = std::exp(-0.5), a = 1.1;
  const double det = a * a - c * c;
  const double quad = (a * 1.0 * 1.0 - 2 * c * 1.0 * -0.5 + a * 0.25) / det;
  const double expected = 0.5 * std::log(det) + 0.5 * quad + std::log(2 * std::numbers::pi) + std::log(10.0);
  const ObjectiveValue value = objective.Evaluate(p, nullptr);
  ASSERT_TRUE(value.ok);
  EXPECT_NEAR(value.total, expected, 1e-12);
}

TEST(Objective, FixedInverseWidthHasZeroGradient) {
  Eigen::MatrixXd y = Eigen::MatrixXd::Random(5, 2);
  const GpObjective objective(y, {}, nullptr, ObjectiveTerms{});
  GpParameters p;
  p.x = Eigen::MatrixXd::Random(5, 3);
  p.log_beta = Eigen::Vector3d(0.2, 0.0, 1.0);
  GpParameters gradient;
  ASSERT_TRUE(objective.Evaluate(p, &gradient).ok);
  EXPECT_EQ(gradient.log_beta[1], 0.0);
  EXPECT_NE(gradient.log_beta[0], 0.0);
}

TEST(Objective, DuplicateLatentPointsGiveFiniteValuesAndGradients) {
  const GaitDataset dataset = test::SyntheticGaitDataset(3, 6, 4);
  const TrainingSet set = MakeTrainingSet(dataset, {1.0});
  const ModelSpec spec = SpecFor(ModelKind::kGpdm, set.NumChannels());
  const GpObjective objective(set.y, SequencesOf(set), nullptr, spec.terms);
  GpParameters p;
  p.x = Eigen::MatrixXd::Zero(set.NumPoints(), 3);  // every point on top of every other
  p.log_beta = Eigen::Vector3d(0, 0, 45.0);        // and noise far below rounding (1e-20)
  p.log_alpha = Eigen::Vector4d(0, 0, 0, 45.0);
  p.log_w = Eigen::VectorXd::Zero(set.NumChannels());
  GpParameters gradient;
  const ObjectiveValue value = objective.Evaluate(p, &gradient);
  ASSERT_TRUE(value.ok) << value.why;
  EXPECT_GT(value.jitter, 0.0);
  EXPECT_TRUE(std::isfinite(value.total));
  EXPECT_TRUE(gradient.x.allFinite() && gradient.log_beta.allFinite() && gradient.log_alpha.allFinite());
  // NaN in the parameters is reported, not passed on.
  p.x(0, 0) = std::nan("");
  const ObjectiveValue bad = objective.Evaluate(p, &gradient);
  EXPECT_FALSE(bad.ok);
  EXPECT_FALSE(bad.why.empty());
}


// --- Sparse learning (prior/learning/sparse_gp.h).

// The rows that are dynamics inputs (a next point in the same sequence), in order.
std::vector<int> DynamicsInputs(const TrainingSet& set) {
  std::vector<int> in;
  for (int i = 0; i < set.NumPoints(); ++i)
    if ((i + 1) % set.poses_per_gait != 0) in.push_back(i);
  return in;
}

struct SparseProblem {
  ModelSpec spec;
  TrainingSet set;
  Topology topology;
  std::unique_ptr<GpObjective> objective;
  GpParameters p;
};

SparseProblem MakeSparseProblem(ModelKind kind) {
  SparseProblem s;
  s.spec = SpecFor(kind, 4);
  s.spec.terms.fixed_inverse_width = false;  // check those gradients too
  s.spec.terms.fixed_dynamics_noise = false;
  s.spec.terms.inducing_jitter = 0;  // so that U = X is the exact objective to round-off
  s.set = MakeTrainingSet(test::SyntheticGaitDataset(4, 6, 4), s.spec.layer_scales);
  if (s.spec.topology) {
    TopologyOptions options;
    options.shape = s.spec.shape;
    s.topology = MakeTopology(s.set, options);
  }
  s.objective = std::make_unique<GpObjective>(s.set.y, SequencesOf(s.set), s.spec.topology ? &s.topology : nullptr,
                                              s.spec.terms);
  s.p = RandomParameters(s.spec, s.set, s.spec.topology ? &s.topology : nullptr);
  return s;
}

// Inducing inputs: every k-th latent point (of the dynamics inputs for the dynamics GP),
// moved a little off them unless `exact`.
void SetInducing(SparseProblem* s, int every, bool exact) {
  std::mt19937 random(11);
  std::normal_distribution<double> noise(0, exact ? 0.0 : 0.1);
  auto pick = [&](const std::vector<int>& rows) {
    std::vector<int> chosen;
    for (size_t k = 0; k < rows.size(); k += every) chosen.push_back(rows[k]);
    Eigen::MatrixXd u(chosen.size(), 3);
    for (size_t k = 0; k < chosen.size(); ++k)
      for (int d = 0; d < 3; ++d) u(k, d) = s->p.x(chosen[k], d) + noise(random);
    return u;
  };
  std::vector<int> all(s->set.NumPoints());
  for (int i = 0; i < s->set.NumPoints(); ++i) all[i] = i;
  s->p.u = pick(all);
  if (s->spec.terms.dynamics) s->p.u_dynamics = pick(DynamicsInputs(s->set));
}

class SparseObjective : public testing::TestWithParam<ModelKind> {};

TEST_P(SparseObjective, GradientMatchesFiniteDifferencesInducingInputsIncluded) {
  SparseProblem s = MakeSparseProblem(GetParam());
  SetInducing(&s, 4, false);
  std::vector<int> all(s.set.NumPoints());
  for (int i = 0; i < s.set.NumPoints(); ++i) all[i] = i;
  CheckAgainstFiniteDifferences(*s.objective, s.p, all);
}

// The oracle: inducing inputs at the latent points give the exact objective, and the
// sparse gradients with respect to x and to its copies u add up to the exact gradient.
TEST_P(SparseObjective, InducingInputsAtTheLatentPointsGiveTheExactObjective) {
  SparseProblem s = MakeSparseProblem(GetParam());
  GpParameters exact_gradient;
  const ObjectiveValue exact = s.objective->Evaluate(s.p, &exact_gradient);
  ASSERT_TRUE(exact.ok) << exact.why;
  SetInducing(&s, 1, true);
  GpParameters gradient;
  const ObjectiveValue sparse = s.objective->Evaluate(s.p, &gradient);
  ASSERT_TRUE(sparse.ok) << sparse.why;
  EXPECT_NEAR(sparse.total, exact.total, 1e-9 * std::abs(exact.total));
  Eigen::MatrixXd dx = gradient.x + gradient.u;
  if (s.spec.terms.dynamics) {
    const std::vector<int> in = DynamicsInputs(s.set);
    for (size_t k = 0; k < in.size(); ++k) dx.row(in[k]) += gradient.u_dynamics.row(k);
  }
  const auto largest = [](const Eigen::MatrixXd& m) { return m.size() ? m.cwiseAbs().maxCoeff() : 0.0; };
  const double scale = largest(exact_gradient.x);
  EXPECT_LT(largest(dx - exact_gradient.x), 1e-7 * scale);
  EXPECT_LT(largest(gradient.log_beta - exact_gradient.log_beta), 1e-7 * scale);
  EXPECT_LT(largest(gradient.log_alpha - exact_gradient.log_alpha), 1e-7 * scale);
  EXPECT_LT(largest(gradient.log_w - exact_gradient.log_w), 1e-7 * scale);
  std::cout << "objective exact " << exact.total << ", sparse " << sparse.total << ", jitter " << sparse.jitter
            << "; largest gradient difference " << largest(dx - exact_gradient.x) << " of " << scale << "\n";
}

// A bound: above the exact objective with fewer inducing inputs, coming down to it as they
// grow (nested sets of latent points).
TEST_P(SparseObjective, BoundIsAboveTheExactObjectiveAndTightens) {
  SparseProblem s = MakeSparseProblem(GetParam());
  const double exact = s.objective->Evaluate(s.p, nullptr).total;
  double previous = std::numeric_limits<double>::infinity();
  for (int every : {8, 4, 2, 1}) {
    SetInducing(&s, every, true);
    const ObjectiveValue v = s.objective->Evaluate(s.p, nullptr);
    ASSERT_TRUE(v.ok) << v.why;
    EXPECT_GE(v.total, exact - 1e-6 * std::abs(exact)) << "every " << every;
    EXPECT_LE(v.total, previous + 1e-9 * std::abs(exact)) << "every " << every;
    if (every == 8) {
      EXPECT_GT(v.total, exact + 1.0);  // a bound that is not the objective
    }
    previous = v.total;
  }
}

INSTANTIATE_TEST_SUITE_P(Kinds, SparseObjective,
                         testing::Values(ModelKind::kGplvm, ModelKind::kGpdm, ModelKind::kMljgpmTorus),
                         [](const testing::TestParamInfo<ModelKind>& info) {
                           std::string name(ModelKindName(info.param));
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
}  // namespace jgpm
