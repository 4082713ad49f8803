// The benchmark's tables: one line per row (track.csv), per row and joint (joints.csv) and
// per row and frame (frames.csv), with the values given, in the order given. The prior's
// floors: on the model's own skeleton the best size can only improve on size 1 (which is
// the subject floor there); on another subject's skeleton the same angles land elsewhere.
#include "tracker/run/track_bench.h"

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "io/base/text_reader.h"
#include "io/gait/gait_dataset.h"
#include "io/mocap/kinematics.h"
#include "io/mocap/asf.h"
#include "io/mocap/amc.h"
#include "prior/model/train.h"
#include "test_support.h"

namespace jgpm {
namespace {

TEST(TrackBench, TablesHoldEveryRowJointAndFrame) {
  TrackBenchRow a;
  a.clip = "c1", a.model = "m", a.method = "prior", a.cameras = 4, a.frames = 3, a.seeds = 2;
  a.bt14_mm = 12.345, a.fps = 30.5, a.evaluations_per_frame = 930;
  a.joints = {"lfemur", "rfemur"};
  a.per_joint_mm = {10.004, 20.5};
  a.per_frame_mm = {1, std::nan(""), 3.25};
  TrackBenchRow b = a;
  b.method = "joint-space", b.floor_g17_root_mm = -1;
  const std::string track = TrackBenchCsv({a, b});
  EXPECT_EQ(std::count(track.begin(), track.end(), '\n'), 3);
  EXPECT_NE(track.find("\nc1,m,prior,4,3,2,12.35,"), std::string::npos) << track;
  EXPECT_NE(track.find("\nc1,m,joint-space,4,3,2,"), std::string::npos) << track;
  // A crowd row's CLEAR MOT columns, at the end.
  TrackBenchRow crowd = a;
  crowd.method = "people", crowd.walkers = 3, crowd.mota = 0.9125, crowd.motp_mm = 34.5, crowd.id_switches = 0.5;
  crowd.people_per_frame = 2.875, crowd.ms_per_person = 24.25;
  const std::string with_crowd = TrackBenchCsv({crowd});
  EXPECT_NE(with_crowd.find(",walkers,mota,motp_mm,misses,false_positives,id_switches,fragmentations,people_per_frame,"
                            "ms_per_person\n"),
            std::string::npos)
      << with_crowd;
  EXPECT_NE(with_crowd.find(",3,0.9125,34.50,0.00,0.00,0.50,0.00,2.875,24.25\n"), std::string::npos) << with_crowd;
  EXPECT_NE(track.find(",0,-1.0000,-1.00,"), std::string::npos) << track;  // one-walker rows: not measured
  EXPECT_EQ(TrackBenchJointsCsv({a}),
            "clip,model,method,joint,mm\nc1,m,prior,lfemur,10.00\nc1,m,prior,rfemur,20.50\n");
  EXPECT_EQ(TrackBenchFramesCsv({a}),
            "clip,model,method,frame,mm\nc1,m,prior,0,1.00\nc1,m,prior,1,nan\nc1,m,prior,2,3.25\n");
}

TEST(TrackBench, LostCountsOnlyWhileInViewWithTheLongestRun) {
  using S = TrackStatus;
  const std::vector<S> status{S::kLost, S::kLost, S::kTracked, S::kLost, S::kLost, S::kLost, S::kPredicted, S::kLost};
  const std::vector<bool> in_view{false, true, true, true, true, false, true, true};
  const LostInView counted = CountLostInView(status, in_view);
  EXPECT_EQ(counted.frames, 4);   // frames 1, 3, 4 and 7
  EXPECT_EQ(counted.longest, 2);  // 3-4 (frame 5 is out of view)
  EXPECT_EQ(CountLostInView({}, {}).frames, 0);
}

TEST(TrackBench, PersonInViewWhenHalfTheJointsAreInAnImage) {
  ClipGroundTruth truth;
  truth.cameras.push_back(LookAtCamera("c", 320, 240, 280, {0, 1000, -5000}, {0, 1000, 0}));
  ClipFrame frame;
  frame.joints_mm.resize(3, 4);
  frame.joints_mm << 0, 0, 0, 0, 1000, 1500, 500, 100, 0, 0, 0, 0;  // a column of joints at the target
  truth.frames.push_back(frame);
  frame.joints_mm.row(0).setConstant(20000);  // far to the side
  truth.frames.push_back(frame);
  frame.joints_mm.row(0) << 0, 0, 20000, 20000;  // half in
  truth.frames.push_back(frame);
  frame.joints_mm.row(0) << 0, 20000, 20000, 20000;  // a quarter
  truth.frames.push_back(frame);
  EXPECT_TRUE(PersonInView(truth, 0));
  EXPECT_FALSE(PersonInView(truth, 1));
  EXPECT_TRUE(PersonInView(truth, 2));
  EXPECT_FALSE(PersonInView(truth, 3));
  // The cameras that rendered the images decide, when the clip has them.
  truth.render_cameras.push_back(LookAtCamera("r", 320, 240, 280, {20000, 1000, -5000}, {20000, 1000, 0}));
  EXPECT_FALSE(PersonInView(truth, 0));
  EXPECT_TRUE(PersonInView(truth, 1));
}

TEST(TrackBench, PersonHiddenBehindAnObjectIsNotInView) {
  // A column of joints 1.5 m tall, 5 m from a camera of focal 280 px: 84 px tall, so it
  // shows when the exact mask holds kShowsArea * 84^2 = 318 px or more.
  ClipGroundTruth truth;
  truth.cameras.push_back(LookAtCamera("cam0", 320, 240, 280, {0, 1000, -5000}, {0, 1000, 0}));
  ClipFrame frame;
  frame.joints_mm.resize(3, 4);
  frame.joints_mm << 0, 0, 0, 0, 0, 500, 1000, 1500, 0, 0, 0, 0;
  for (int k = 0; k < 4; ++k) truth.frames.push_back(frame);
  test::TempDir dir;
  const ClipPaths paths{dir.path()};
  std::filesystem::create_directories(paths.MaskFolder("cam0"));
  const auto write = [&](int k, int pixels) {  // a mask with `pixels` set
    cv::Mat mask = cv::Mat::zeros(240, 320, CV_8UC1);
    for (int i = 0; i < pixels; ++i) mask.at<uint8_t>(100 + i / 20, 150 + i % 20) = 255;
    ASSERT_TRUE(cv::imwrite(paths.Mask("cam0", k).string(), mask));
  };
  write(0, 0);    // wholly behind a pillar
  write(1, 300);  // a leg beside it
  write(2, 340);  // a third of the person
  // frame 3 was dropped: no mask, the joints decide
  EXPECT_FALSE(PersonInView(truth, 0, dir.path()));
  EXPECT_FALSE(PersonInView(truth, 1, dir.path()));
  EXPECT_TRUE(PersonInView(truth, 2, dir.path()));
  EXPECT_TRUE(PersonInView(truth, 3, dir.path()));
  EXPECT_TRUE(PersonInView(truth, 0));  // no folder: the joints alone
}

TEST(TrackBench, TriangulatedByTheWrittenCamerasIsWhereTheyPutTheTruth) {
  const Skeleton skeleton = ReadAsf(test::CmuRoot() / "subjects/35/35.asf");
  const Motion motion = ReadAmc(test::CmuRoot() / "subjects/35/35_01.amc", skeleton);
  ClipGroundTruth truth;
  truth.joint_names = skeleton.BoneNames();
  for (int k = 0; k < 20; ++k) {
    ClipFrame frame;
    frame.joints_mm = Kinematics(skeleton).Compute(motion.Frame(4 * k));
    truth.frames.push_back(frame);
  }
  const Eigen::Vector3d at(truth.frames[0].joints_mm(0, 0), 900, truth.frames[0].joints_mm(2, 0));
  const Eigen::Vector3d side(4500, 700, 300), front(-200, 900, 5000);
  truth.render_cameras = {LookAtCamera("a", 320, 240, 300, at + side, at), LookAtCamera("b", 320, 240, 300, at + front, at)};
  // Written cameras all moved by the same 50 mm: they place everything 50 mm over.
  const Eigen::Vector3d moved(30, 0, -40);
  truth.cameras = {LookAtCamera("a", 320, 240, 300, at + side + moved, at + moved),
                   LookAtCamera("b", 320, 240, 300, at + front + moved, at + moved)};
  EXPECT_NEAR(TriangulatedByWrittenCameras(truth, 20), 50, 1e-6);
  // The rendering cameras themselves: nothing lost.
  truth.cameras = truth.render_cameras;
  EXPECT_NEAR(TriangulatedByWrittenCameras(truth, 20), 0, 1e-6);
  // One camera turned by half a degree about its own centre: some tens of millimetres at 4.5 m.
  truth.cameras[0] = LookAtCamera("a", 320, 240, 300, at + side, at + Eigen::Vector3d(0, 0, 40));
  const double turned = TriangulatedByWrittenCameras(truth, 20);
  EXPECT_GT(turned, 5);
  EXPECT_LT(turned, 60);
  // Not applicable: exact cameras (no rendering ones written), or one camera.
  truth.render_cameras.clear();
  EXPECT_EQ(TriangulatedByWrittenCameras(truth, 20), -1);
  truth.render_cameras = {truth.cameras[0]};
  truth.cameras.resize(1);
  EXPECT_EQ(TriangulatedByWrittenCameras(truth, 20), -1);
}

ClipGroundTruth Trial(const std::string& subject, const std::string& trial, int frames) {
  ClipGroundTruth truth;
  truth.source_asf = (test::CmuRoot() / "subjects" / subject / (subject + ".asf")).string();
  truth.source_amc = (test::CmuRoot() / "subjects" / subject / (trial + ".amc")).string();
  for (int k = 0; k < frames; ++k) {
    ClipFrame frame;
    frame.time_s = k / 30.0;
    frame.source_frame = 4 * k;
    truth.frames.push_back(frame);
  }
  return truth;
}

TEST(TrackBench, FloorsOnTheSubjectsAndTheModelsSkeleton) {
  const std::vector<TrialId> trials = {{"35", "35_01"}, {"35", "35_02"}, {"35", "35_03"}};
  const GaitDataset dataset = PrepareGaitDataset(test::CmuRoot(), "three", trials, GaitCycleOptions{});
  TrainingOptions training;
  training.kind = ModelKind::kPca;
  const auto model = TrainGaitModel(
      dataset, {"35_01", ReadTextFile(test::CmuRoot() / "subjects/35/35.asf", "asf")}, training);
  const PriorFloors own = ModelFloors(*model, Trial("35", "35_12", 40), 40);
  EXPECT_GT(own.subject_g17, 5);
  EXPECT_GT(own.subject_bt14, 5);
  EXPECT_LE(own.model_g17, own.subject_g17 + 1e-9);
  EXPECT_GT(own.model_g17, 0.8 * own.subject_g17);
  const PriorFloors other = ModelFloors(*model, Trial("39", "39_12", 40), 40);
  EXPECT_GT(other.subject_g17, 5);
  EXPECT_GT(other.model_g17, other.subject_g17 + 10);
  const PriorFloors none = ModelFloors(*model, Trial("39", "no_such_trial", 40), 40);
  EXPECT_EQ(none.subject_g17, -1);
  EXPECT_EQ(none.model_g17, -1);
  std::printf("floors (mm, 17 joints): 35_12 %.1f / %.1f, 39_12 %.1f / %.1f (subject's / model's skeleton)\n",
              own.subject_g17, own.model_g17, other.subject_g17, other.model_g17);
}

}  // namespace
}  // namespace jgpm
