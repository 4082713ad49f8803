// The pose table against the model it tabulates: at grid nodes its joints and ln density
// are the model's (float storage aside); between nodes, trilinear interpolation must stay
// within a few millimetres of forward kinematics of the model's exact mean pose (a third
// of a pixel at the clips' 15 mm per pixel), along each grid direction and at random
// points, for an ML-JGPM model (manifold coordinates) and a latent model (PCA). Phase
// wraps; the stride it derives is each training walker's real stride and grows with the
// stride scale.
#include "tracker/state/pose_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "io/base/error.h"
#include "io/base/text_reader.h"
#include "io/gait/gait_dataset.h"
#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/kinematics.h"
#include "prior/model/latent_density.h"
#include "prior/model/train.h"
#include "test_support.h"
#include "tracker/state/random.h"
#include "tracker/state/state_model.h"

namespace jgpm {
namespace {

// Four training trials (subjects 02, 05 and 35): enough gaits for a torus, small enough
// to train in a second.
const GaitDataset& Walks() {
  static const GaitDataset dataset = [] {
    std::vector<TrialId> trials = test::SplitTrials("train");
    trials.resize(4);
    return PrepareGaitDataset(test::CmuRoot(), "four", trials, GaitCycleOptions{});
  }();
  return dataset;
}

// 60 full iterations (under a second): trained enough that the pose changes between
// gaits as a learned model's does, not as the topology prior's near-circles do (after 5
// iterations the table looks 2-3 times more accurate along the gait than it is for a
// model trained further; after 300, 2 times less).
std::unique_ptr<GaitModel> Train(ModelKind kind) {
  TrainingOptions options;
  options.kind = kind;
  options.full.max_iterations = 60;
  const GaitTrial& first = Walks().trials[0];
  return TrainGaitModel(Walks(), {first.id.name, ReadTextFile(test::CmuRoot() / first.asf, "asf")}, options);
}

const GaitModel& Mljgpm() {
  static const std::unique_ptr<GaitModel> model = Train(ModelKind::kMljgpmTorus);
  return *model;
}
const GaitModel& Pca() {
  static const std::unique_ptr<GaitModel> model = Train(ModelKind::kPca);
  return *model;
}

// The oracle: the model's exact mean pose at a table coordinate, by forward kinematics,
// and the density the table says it holds: a kernel density over the model's latent
// points with the width of the median distance to the k-th nearest (k =
// PoseTableOptions::density_neighbours; k = 1 would be the model's own LogDensity).
struct Exact {
  Eigen::Matrix3Xd joints;  // root-relative, size 1, facing +z
  double foot_height_mm = 0;
  double log_density = 0;
};
Exact ExactAt(const GaitModel& model, const LatentDensity& density, const Eigen::Vector3d& at) {
  const Eigen::Vector3d x = model.HasManifold() ? model.ManifoldToLatent({at[0], at[1], at[2]}) : at;
  const Eigen::MatrixXd pose = model.MeanPoses(Eigen::MatrixXd(x.transpose()));
  Exact e;
  PosePlacer(model.skeleton()).Relative(pose.row(0).data(), &e.joints, &e.foot_height_mm);
  e.log_density = density.LogDensity(x, nullptr);
  return e;
}
LatentDensity TableDensity(const GaitModel& model, const PoseTableOptions& options) {
  return LatentDensity(model.latent(), options.density_neighbours);
}

double MeanJointError(const Eigen::Matrix3Xd& a, const Eigen::Matrix3Xd& b) {
  return (a - b).colwise().norm().mean();
}

struct Errors {
  double mean_joint_mm = 0, worst_joint_mm = 0, worst_foot_mm = 0, mean_density = 0;
  double density_spread = 0;  // standard deviation of the density over the points
};

// The table against the oracle at `points` random coordinates, off the grid in the
// dimensions `off` says and on a random node in the others.
Errors Compare(const GaitModel& model, const LatentDensity& oracle, const PoseTable& table,
               const std::array<int, 3>& nodes, const std::array<bool, 3>& off, int points, uint64_t seed) {
  Errors e;
  std::vector<double> densities;
  for (int i = 0; i < points; ++i) {
    Random random(seed, i);
    Eigen::Vector3d at;
    for (int d = 0; d < 3; ++d) {
      const double step = (table.hi()[d] - table.lo()[d]) / (table.periodic(d) ? nodes[d] : nodes[d] - 1);
      const int node = std::min(static_cast<int>(random.Uniform() * (nodes[d] - 1)), nodes[d] - 2);
      at[d] = table.lo()[d] + (node + (off[d] ? random.Uniform() : 0.0)) * step;
    }
    const Exact exact = ExactAt(model, oracle, at);
    Eigen::Matrix3Xd joints;
    double foot = 0, density = 0;
    table.Lookup(at, &joints, &foot, &density);
    EXPECT_EQ(joints.cols(), exact.joints.cols());
    const double error = MeanJointError(joints, exact.joints);
    e.mean_joint_mm += error / points;
    e.worst_joint_mm = std::max(e.worst_joint_mm, error);
    e.worst_foot_mm = std::max(e.worst_foot_mm, std::abs(foot - exact.foot_height_mm));
    e.mean_density += std::abs(density - exact.log_density) / points;
    densities.push_back(exact.log_density);
  }
  double mean = 0, squares = 0;
  for (double d : densities) mean += d / points;
  for (double d : densities) squares += (d - mean) * (d - mean) / points;
  e.density_spread = std::sqrt(squares);
  return e;
}

void Print(const char* what, const Errors& e) {
  std::printf("%-26s mean joint error %6.2f mm, worst point %6.2f mm, worst foot height %6.2f mm, "
              "ln density %.3f (spread %.3f)\n",
              what, e.mean_joint_mm, e.worst_joint_mm, e.worst_foot_mm, e.mean_density, e.density_spread);
}

// Grid nodes: the table holds the model's values (stored as floats).
void ExpectNodesExact(const GaitModel& model, const LatentDensity& oracle, const PoseTable& table,
                      const std::array<int, 3>& nodes) {
  for (int k = 0; k < 6; ++k) {
    Eigen::Vector3d at;
    for (int d = 0; d < 3; ++d) {
      const int n = nodes[d], i = (k * 7 + d * 3) % n;  // a spread of nodes
      const double step = (table.hi()[d] - table.lo()[d]) / (table.periodic(d) ? n : n - 1);
      at[d] = table.lo()[d] + i * step;
    }
    const Exact exact = ExactAt(model, oracle, at);
    Eigen::Matrix3Xd joints;
    double foot = 0, density = 0;
    table.Lookup(at, &joints, &foot, &density);
    EXPECT_LT((joints - exact.joints).cwiseAbs().maxCoeff(), 1e-3) << at.transpose();  // float: 1e-4 of 2 m
    EXPECT_NEAR(foot, exact.foot_height_mm, 1e-3) << at.transpose();
    EXPECT_NEAR(density, exact.log_density, 1e-4 * std::max(1.0, std::abs(exact.log_density))) << at.transpose();
  }
}

TEST(PoseTable, MljgpmLookupFollowsTheModel) {
  const GaitModel& model = Mljgpm();
  ASSERT_TRUE(model.HasManifold());
  PoseTableOptions options;
  options.threads = 2;
  const PoseTable table(model, options);
  ASSERT_TRUE(table.manifold());
  const int gaits = model.data().set.NumGaits();
  EXPECT_TRUE(table.periodic(0));
  EXPECT_TRUE(table.periodic(1));  // a torus
  EXPECT_FALSE(table.periodic(2));
  EXPECT_EQ(table.hi()[1], gaits);
  EXPECT_EQ(table.NumBones(), static_cast<int>(model.skeleton().bones.size()));
  const LatentDensity oracle = TableDensity(model, options);
  const std::array<int, 3> nodes = {options.phase_nodes, gaits * options.nodes_per_gait, options.scale_nodes};
  ExpectNodesExact(model, oracle, table, nodes);

  // Bounds: a third of a pixel (5 mm) on average, 20 mm at the worst point, along each
  // direction and anywhere. Measured (this model, default options): phase 0.30 mm mean,
  // 2.7 worst point; scale 0.05, 0.27; gait 10.1, 48 (worst single joint 172 mm);
  // anywhere 10.5, 45. Along the gait the pose bends between the training gaits far more
  // than along the cycle, and 4 nodes per gait miss it: the error falls as 1/n^2 (16 nodes
  // per gait: gait 0.70, 4.3; anywhere 0.90, 4.4). The tracker scores the table's pose but
  // reports the model's (Tracker::Exact), so the two must agree.
  const Errors phase = Compare(model, oracle, table, nodes, {true, false, false}, 200, 21);
  const Errors gait = Compare(model, oracle, table, nodes, {false, true, false}, 200, 22);
  const Errors scale = Compare(model, oracle, table, nodes, {false, false, true}, 200, 23);
  const Errors anywhere = Compare(model, oracle, table, nodes, {true, true, true}, 300, 24);
  Print("ML-JGPM, off-grid in phase", phase);
  Print("ML-JGPM, off-grid in gait", gait);
  Print("ML-JGPM, off-grid in scale", scale);
  Print("ML-JGPM, anywhere", anywhere);
  for (const auto& [name, e] : {std::pair<const char*, const Errors&>{"phase", phase}, {"gait", gait},
                                {"scale", scale}, {"anywhere", anywhere}}) {
    EXPECT_LT(e.mean_joint_mm, 5.0) << name;
    EXPECT_LT(e.worst_joint_mm, 20.0) << name;
  }
  // ln density: measured 0.17 nats mean against a spread of 1.5 over the manifold (16
  // nodes per gait: 0.02).
  EXPECT_LT(anywhere.mean_density, 0.2 * anywhere.density_spread);

  // The phase's last cell interpolates between the last node and node 0 (the wrap).
  const Errors seam = [&] {
    Errors e;
    for (int i = 0; i < 50; ++i) {
      Random random(25, i);
      const Eigen::Vector3d at(1 - random.Uniform() / options.phase_nodes, std::floor(gaits * random.Uniform()),
                               1.0);
      Eigen::Matrix3Xd joints;
      table.Lookup(at, &joints, nullptr, nullptr);
      const double error = MeanJointError(joints, ExactAt(model, oracle, at).joints);
      e.mean_joint_mm += error / 50;
      e.worst_joint_mm = std::max(e.worst_joint_mm, error);
    }
    return e;
  }();
  std::printf("ML-JGPM, last phase cell   mean joint error %6.2f mm, worst point %6.2f mm\n", seam.mean_joint_mm,
              seam.worst_joint_mm);
  EXPECT_LT(seam.mean_joint_mm, 5.0);
  EXPECT_LT(seam.worst_joint_mm, 20.0);
}

TEST(PoseTable, PcaLookupFollowsTheModel) {
  const GaitModel& model = Pca();
  ASSERT_FALSE(model.HasManifold());
  PoseTableOptions options;
  const PoseTable table(model, options);
  ASSERT_FALSE(table.manifold());
  for (int d = 0; d < 3; ++d) {
    EXPECT_FALSE(table.periodic(d));
    // The box holds every training latent point, padded.
    EXPECT_LT(table.lo()[d], model.latent().col(d).minCoeff());
    EXPECT_GT(table.hi()[d], model.latent().col(d).maxCoeff());
  }
  const LatentDensity oracle = TableDensity(model, options);
  const std::array<int, 3> nodes = {options.latent_nodes, options.latent_nodes, options.latent_nodes};
  ExpectNodesExact(model, oracle, table, nodes);
  const Errors e = Compare(model, oracle, table, nodes, {true, true, true}, 300, 31);
  Print("PCA, anywhere", e);
  // PCA's mean pose is linear in the point; only forward kinematics bends: measured
  // 0.07 mm mean, 0.10 worst; ln density 0.018 nats against a spread of 3.8.
  EXPECT_LT(e.mean_joint_mm, 1.0);
  EXPECT_LT(e.worst_joint_mm, 3.0);
  EXPECT_LT(e.mean_density, 0.05 * e.density_spread);
}

TEST(PoseTable, PhaseWrapsAndGaitWrapsOnATorus) {
  const GaitModel& model = Mljgpm();
  const PoseTable table(model);
  const double gaits = model.data().set.NumGaits();
  for (int i = 0; i < 50; ++i) {
    Random random(41, i);
    const Eigen::Vector3d at(random.Uniform(), gaits * random.Uniform(), 0.4 + 0.85 * random.Uniform());
    Eigen::Matrix3Xd a, b, c;
    double foot_a = 0, foot_b = 0, density_a = 0, density_b = 0;
    table.Lookup(at, &a, &foot_a, &density_a);
    table.Lookup(at + Eigen::Vector3d(1, 0, 0), &b, &foot_b, &density_b);
    table.Lookup(at + Eigen::Vector3d(-3, gaits, 0), &c, nullptr, nullptr);
    // Equal but for the rounding of the wrapped coordinate.
    EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-6) << at.transpose();
    EXPECT_LT((a - c).cwiseAbs().maxCoeff(), 1e-6) << at.transpose();
    EXPECT_NEAR(foot_a, foot_b, 1e-6);
    EXPECT_NEAR(density_a, density_b, 1e-9);
    EXPECT_LT((table.Pose(at) - table.Pose(at + Eigen::Vector3d(1, 0, 0))).cwiseAbs().maxCoeff(), 1e-6);
  }
  // Outside the scale range, clamped.
  Eigen::Matrix3Xd low, below;
  table.Lookup({0.3, 1.2, table.lo()[2]}, &low, nullptr, nullptr);
  table.Lookup({0.3, 1.2, table.lo()[2] - 5}, &below, nullptr, nullptr);
  EXPECT_LT((low - below).cwiseAbs().maxCoeff(), 1e-9);
}

// Thigh plus shin of a skeleton (its length units are the same for every CMU subject).
double LegLength(const Skeleton& skeleton) {
  return skeleton.bones[skeleton.FindBone("lfemur")].length + skeleton.bones[skeleton.FindBone("ltibia")].length;
}

TEST(PoseTable, StrideIsAWalkersAndGrowsWithTheScale) {
  const GaitModel& model = Mljgpm();
  const PoseTable table(model);
  const TrainingSet& set = model.data().set;
  const int gaits = set.NumGaits();
  const double lowest = table.lo()[2], highest = table.hi()[2];
  ASSERT_LT(lowest, 1.0);
  ASSERT_GT(highest, 1.0);
  // Each training walker's own stride: the root's travel over the cycle the model learned,
  // in the data, scaled to the reference skeleton's legs (the table walks on those), against
  // the table's at that gait's position on the manifold, scale 1.
  const std::vector<int>& order = model.data().gait_order;
  const double reference_leg = LegLength(model.skeleton());
  for (int g = 0; g < gaits; ++g) {
    const GaitTrial& trial = Walks().trials[g];
    ASSERT_EQ(set.gait_ids[g], trial.id.name);
    const int position = static_cast<int>(std::find(order.begin(), order.end(), g) - order.begin());
    ASSERT_LT(position, gaits);
    const Skeleton skeleton = ReadAsf(test::CmuRoot() / trial.asf);
    const Motion motion = ReadAmc(test::CmuRoot() / trial.amc, skeleton);
    const Kinematics kinematics(skeleton);
    const Eigen::Vector3d travel = kinematics.Compute(motion.Frame(trial.cycle.end_frame)).col(0) -
                                   kinematics.Compute(motion.Frame(trial.cycle.start_frame)).col(0);
    const double real = std::hypot(travel.x(), travel.z()) * reference_leg / LegLength(skeleton);
    const double tabulated = table.StrideMm(position, 1.0);
    std::printf("%s: stride %.0f mm in the data (on the reference legs), %.0f mm in the table; "
                "scale %.2f: %.0f, %.2f: %.0f\n",
                trial.id.name.c_str(), real, tabulated, lowest, table.StrideMm(position, lowest), highest,
                table.StrideMm(position, highest));
    // One walking cycle (two steps) of an adult at a normal walk: 1.0-1.7 m.
    EXPECT_GT(tabulated, 1000) << trial.id.name;
    EXPECT_LT(tabulated, 1700) << trial.id.name;
    // Measured: 5-13% short (the model's mean poses swing a little less than the data).
    EXPECT_NEAR(tabulated, real, 0.15 * real) << trial.id.name;
    // The layers' scales (0.4, 1, 1.25) scale the swing about the mean pose: measured
    // 0.24-0.35 and 1.23-1.28 of the stride at scale 1.
    EXPECT_GT(table.StrideMm(position, highest), 1.15 * tabulated) << trial.id.name;
    EXPECT_LT(table.StrideMm(position, lowest), 0.5 * tabulated) << trial.id.name;
  }
  // Longer with the stride scale, everywhere on the manifold (between the training gaits
  // too, where it grows less: measured 1.07 times from scale 1 to 1.25 at gait 0.35).
  for (int k = 0; k < 4 * gaits; ++k) {
    const double gait = 0.25 * k + 0.1;
    double previous = 0;
    for (int s = 0; s <= 8; ++s) {
      const double scale = lowest + s * (highest - lowest) / 8;
      const double stride = table.StrideMm(gait, scale);
      EXPECT_GT(stride, previous) << "gait " << gait << " scale " << scale;
      previous = stride;
    }
  }
}

// Serialize and Parse: the table read back is the table, bit for bit (the same lookups,
// poses and strides at random points); another key reads as "not this table"; bytes cut
// short or altered at the start are refused naming the source.
TEST(PoseTable, ReadsBackBitForBitAndRefusesWhatIsNotATable) {
  PoseTableOptions options;
  options.phase_nodes = 16;
  options.nodes_per_gait = 3;
  options.scale_nodes = 3;
  const PoseTable table(Mljgpm(), options);
  const std::string bytes = table.Serialize("key A");
  const std::unique_ptr<PoseTable> back = PoseTable::Parse(bytes, "key A", "a.table");
  ASSERT_TRUE(back);
  Random random(5, 0);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Vector3d at(3 * random.Uniform() - 1, 6 * random.Uniform() - 1, random.Uniform() + 0.5);
    Eigen::Matrix3Xd a, b;
    double foot_a, foot_b, density_a, density_b;
    table.Lookup(at, &a, &foot_a, &density_a);
    back->Lookup(at, &b, &foot_b, &density_b);
    ASSERT_EQ(a, b);
    ASSERT_EQ(foot_a, foot_b);
    ASSERT_EQ(density_a, density_b);
    ASSERT_EQ(table.Pose(at), back->Pose(at));
    ASSERT_EQ(table.StrideMm(at[1], at[2]), back->StrideMm(at[1], at[2]));
  }
  EXPECT_EQ(back->Serialize("key A"), bytes);
  EXPECT_FALSE(PoseTable::Parse(bytes, "key B", "a.table"));
  for (const size_t cut : {size_t{0}, size_t{5}, size_t{30}, bytes.size() / 2, bytes.size() - 1}) {
    try {
      PoseTable::Parse(bytes.substr(0, cut), "key A", "cut.table");
      ADD_FAILURE() << "cut at " << cut << " was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("cut.table"), std::string::npos) << e.what();
    }
  }
  std::string altered = bytes;
  altered[0] = 'X';
  EXPECT_THROW(PoseTable::Parse(altered, "key A", "x.table"), InputError);
  EXPECT_THROW(PoseTable::Parse(bytes + "more", "key A", "x.table"), InputError);

  // A latent model's table has no strides: an empty array written and read (it passed a
  // null pointer to memcpy, which the sanitizer build aborts on).
  const PoseTable pca(Pca(), options);
  const std::unique_ptr<PoseTable> pca_back = PoseTable::Parse(pca.Serialize("pca"), "pca", "pca.table");
  ASSERT_TRUE(pca_back);
  EXPECT_EQ(pca_back->Pose(Eigen::Vector3d(0.1, 0.2, 0.3)), pca.Pose(Eigen::Vector3d(0.1, 0.2, 0.3)));
}

}  // namespace
}  // namespace jgpm
