// Synthesised walking must look like walking: bones keep the skeleton's lengths in the
// files written, angles stay inside the ASF limits, the feet alternate along the cycle, and
// the outer spiral strides further than the inner one (paper Fig. 14). The model is an
// ML-JGPM torus learned locally (as the quick start does) from five real training trials.
#include "prior/motion/synthesis.h"

#include <cmath>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "io/base/text_reader.h"
#include "io/gait/split.h"
#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/bvh.h"
#include "io/mocap/kinematics.h"
#include "prior/model/train.h"
#include "test_support.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;
using test::ExpectInputError;

const GaitModel& Model() {
  static const std::unique_ptr<GaitModel> model = [] {
    std::vector<TrialId> trials = test::SplitTrials("train");
    trials.resize(5);
    const GaitDataset dataset = PrepareGaitDataset(test::CmuRoot(), "five", trials, GaitCycleOptions{});
    TrainingOptions options;
    options.kind = ModelKind::kMljgpmTorus;
    options.learning = Learning::kLocal;
    const GaitTrial& first = dataset.trials[0];
    return TrainGaitModel(dataset, {first.id.name, ReadTextFile(test::CmuRoot() / first.asf, "asf")}, options);
  }();
  return *model;
}

// Forward distance (mm) of the left foot ahead of the right one, per frame.
std::vector<double> FootLead(const Skeleton& skeleton, const Motion& motion) {
  const Kinematics kinematics(skeleton);
  const int left = skeleton.FindBone("lfoot"), right = skeleton.FindBone("rfoot");
  std::vector<double> lead;
  for (int t = 0; t < motion.NumFrames(); ++t) {
    const Eigen::Matrix3Xd p = kinematics.Compute(motion.Frame(t));
    lead.push_back(p(2, left) - p(2, right));
  }
  return lead;
}

int SignChanges(const std::vector<double>& v) {
  int changes = 0;
  for (size_t t = 1; t < v.size(); ++t) changes += (v[t] > 0) != (v[t - 1] > 0);
  return changes;
}

double MaxAbs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

TEST(Synthesis, WrittenMotionKeepsBoneLengthsAndAsfLimits) {
  test::TempDir dir;
  for (SynthesisPath path : {SynthesisPath::kLine, SynthesisPath::kOuterSpiral, SynthesisPath::kInnerSpiral}) {
    SCOPED_TRACE(std::string(SynthesisPathName(path)));
    const SynthesisResult result = Synthesise(Model(), path);
    const Motion motion = PosesToMotion(Model(), result.poses_deg, 30);
    const fs::path amc = dir.path() / (std::string(SynthesisPathName(path)) + ".amc");
    ASSERT_EQ(WriteSynthesis(Model().skeleton(), Model().data().skeleton_asf, motion, amc).size(), 2u);
    // Read back what an animation tool would read.
    const Skeleton skeleton = ReadAsf(fs::path(amc).replace_extension(".asf"));
    const Motion back = ReadAmc(amc, skeleton);
    ASSERT_EQ(back.NumFrames(), 120);
    const Kinematics kinematics(skeleton);
    const std::vector<int> offsets = skeleton.ChannelOffsets();
    // CMU's own trials leave their ASF limits (lwrist.ry reaches 22 degrees over a limit of
    // 0), and the outer layer scales them by 1.25: a dof may go where the limits or the
    // model's training poses go, plus 10 degrees (the GP mean may overshoot between them).
    const std::vector<std::string> names = skeleton.ChannelNames();
    std::vector<double> low(names.size(), 0.0), high(names.size(), 0.0);
    const TrainingSet& set = Model().data().set;
    for (int c = 0; c < set.NumChannels(); ++c) {
      const int k = static_cast<int>(std::find(names.begin(), names.end(), set.channel_names[c]) - names.begin());
      ASSERT_LT(k, static_cast<int>(names.size()));
      low[k] = set.y_deg.col(c).minCoeff();
      high[k] = set.y_deg.col(c).maxCoeff();
    }
    double lowest = 1e9;
    for (int t = 0; t < back.NumFrames(); ++t) {
      const Eigen::Matrix3Xd p = kinematics.Compute(back.Frame(t));
      lowest = std::min(lowest, p.row(1).minCoeff());
      for (size_t b = 1; b < skeleton.bones.size(); ++b) {
        const Bone& bone = skeleton.bones[b];
        const double length = (p.col(b) - p.col(bone.parent)).norm();
        ASSERT_NEAR(length, bone.length * skeleton.MillimetresPerUnit(), 1e-6) << bone.name << " frame " << t;
        for (size_t d = 0; d < bone.limits.size(); ++d) {
          const int k = offsets[b] + static_cast<int>(d);
          const double value = back.values(t, k);
          ASSERT_GE(value, std::min(bone.limits[d].min, low[k]) - 10) << names[k] << " frame " << t;
          ASSERT_LE(value, std::max(bone.limits[d].max, high[k]) + 10) << names[k] << " frame " << t;
        }
      }
    }
    EXPECT_NEAR(lowest, 0.0, 1e-6);  // standing on the floor
  }
}

TEST(Synthesis, FeetAlternateAndOuterStridesAreLonger) {
  const Skeleton& skeleton = Model().skeleton();
  const auto lead = [&](SynthesisPath path) {
    return FootLead(skeleton, PosesToMotion(Model(), Synthesise(Model(), path).poses_deg, 30));
  };
  const std::vector<double> outer = lead(SynthesisPath::kOuterSpiral), inner = lead(SynthesisPath::kInnerSpiral);
  // Two walking cycles: each foot leads twice, so the lead changes sign about four times.
  EXPECT_GE(SignChanges(outer), 3);
  EXPECT_LE(SignChanges(outer), 5);
  EXPECT_GE(SignChanges(inner), 3);
  EXPECT_LE(SignChanges(inner), 5);
  EXPECT_GT(MaxAbs(outer), 1.5 * MaxAbs(inner)) << "outer " << MaxAbs(outer) << " inner " << MaxAbs(inner);
  EXPECT_GT(MaxAbs(outer), 300.0);  // a real stride, in mm

  // The line holds one pose and grows its stride: same leading foot, growing lead.
  const std::vector<double> line = lead(SynthesisPath::kLine);
  EXPECT_EQ(SignChanges(line), 0);
  EXPECT_GT(std::abs(line.back()), 1.5 * std::abs(line.front()));
}

TEST(Synthesis, StickFiguresAndBvh) {
  test::TempDir dir;
  const Motion motion = PosesToMotion(Model(), Synthesise(Model(), SynthesisPath::kOuterSpiral).poses_deg, 30);
  const std::vector<fs::path> written = WriteSynthesis(Model().skeleton(), Model().data().skeleton_asf, motion, dir.path() / "walk.bvh", dir.path() / "strip.png");
  ASSERT_EQ(written.size(), 2u);
  // 12 figures of 150 px side by side; each figure draws dark pixels (its bones).
  const cv::Mat strip = cv::imread((dir.path() / "strip.png").string(), cv::IMREAD_GRAYSCALE);
  ASSERT_EQ(strip.cols, 12 * 150);
  for (int f = 0; f < 12; ++f) {
    EXPECT_GT(cv::countNonZero(strip(cv::Rect(f * 150, 0, 150, 260)) < 100), 100) << "figure " << f;
  }
  const Bvh bvh = ReadBvh(dir.path() / "walk.bvh");
  EXPECT_EQ(bvh.frames.rows(), 120);
  ExpectInputError([&] { WriteSynthesis(Model().skeleton(), Model().data().skeleton_asf, motion, dir.path() / "walk.fbx"); }, {"walk.fbx", ".amc or .bvh"});
}

// The motion and its picture appear together or not at all: a picture that cannot be
// written (its folder is missing) leaves no motion behind either.
TEST(Synthesis, AllFilesOrNone) {
  test::TempDir dir;
  const Motion motion = PosesToMotion(Model(), Synthesise(Model(), SynthesisPath::kLine).poses_deg, 30);
  ExpectInputError([&] { WriteSynthesis(Model().skeleton(), Model().data().skeleton_asf, motion, dir.path() / "walk.amc", dir.path() / "no" / "strip.png"); },
                   {"strip.png", "does not exist"});
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(Synthesis, BadInput) {
  const auto pca = [] {
    TrainingOptions options;
    options.kind = ModelKind::kPca;
    std::vector<TrialId> trials = test::SplitTrials("train");
    trials.resize(2);
    const GaitDataset dataset = PrepareGaitDataset(test::CmuRoot(), "two", trials, GaitCycleOptions{});
    return TrainGaitModel(dataset, {dataset.trials[0].id.name, ReadTextFile(test::CmuRoot() / dataset.trials[0].asf, "asf")},
                          options);
  }();
  ExpectInputError([&] { Synthesise(*pca, SynthesisPath::kLine); }, {"pca model", "manifold"});
  SynthesisOptions bad;
  bad.frames = 1;
  ExpectInputError([&] { Synthesise(Model(), SynthesisPath::kLine, bad); }, {"frames"});
  bad = {};
  bad.cycles = std::nan("");
  ExpectInputError([&] { Synthesise(Model(), SynthesisPath::kOuterSpiral, bad); }, {"cycles"});
}

}  // namespace
}  // namespace jgpm
