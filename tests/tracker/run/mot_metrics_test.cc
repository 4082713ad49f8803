// CLEAR MOT on hand-made tracks whose figures are counted by hand.
#include "tracker/run/mot_metrics.h"

#include <stdexcept>

#include <gtest/gtest.h>

namespace jgpm {
namespace {

MotPoint At(int id, double x, double z) { return {id, Eigen::Vector2d(x, z)}; }

// Two people over 6 frames: person 1 walks along x and tracked id 10 follows it exactly;
// person 2 stands at (0, 1000), followed 100 mm off by id 20 in frames 0-1, by nobody in
// 2-3, and by a new id 30 in 4-5; in frame 3 a false id 99 is far from anyone.
//   person-frames 12, pairs 6 + 4, misses 2, false positives 1, switches 1 (20 -> 30),
//   fragmentations 1; MOTA = 1 - (2 + 1 + 1) / 12 = 2/3; MOTP = 4 x 100 / 10 = 40 mm.
TEST(ClearMot, CountsAHandMadeSceneAsByHand) {
  std::vector<MotFrame> frames(6);
  for (int t = 0; t < 6; ++t) {
    frames[t].truth = {At(1, 100 * t, 0), At(2, 0, 1000)};
    frames[t].tracked.push_back(At(10, 100 * t, 0));
    if (t < 2) frames[t].tracked.push_back(At(20, 0, 1100));
    if (t >= 4) frames[t].tracked.push_back(At(30, 0, 900));
    if (t == 3) frames[t].tracked.push_back(At(99, 5000, 5000));
  }
  const MotResult r = ClearMot(frames);
  EXPECT_EQ(r.frames, 6);
  EXPECT_EQ(r.truth, 12);
  EXPECT_EQ(r.truth_tracks, 2);
  EXPECT_EQ(r.pairs, 10);
  EXPECT_EQ(r.misses, 2);
  EXPECT_EQ(r.false_positives, 1);
  EXPECT_EQ(r.id_switches, 1);
  EXPECT_EQ(r.fragmentations, 1);
  EXPECT_NEAR(r.mota, 2.0 / 3, 1e-12);
  EXPECT_NEAR(r.motp_mm, 40, 1e-9);
  ASSERT_EQ(r.paired.size(), 10u);
  EXPECT_EQ(r.paired.back().truth_id, 2);
  EXPECT_EQ(r.paired.back().tracked_id, 30);
}

// Two people 600 mm apart whose tracks drift towards each other: frame 1's nearest pairing
// would swap them (250 + 250 against 350 + 350), but each track is still within 500 mm of
// its person, so the correspondences are kept and nobody switched.
TEST(ClearMot, KeepsCorrespondencesThatStillHold) {
  std::vector<MotFrame> frames(2);
  frames[0].truth = frames[1].truth = {At(1, 0, 0), At(2, 600, 0)};
  frames[0].tracked = {At(7, 0, 0), At(8, 600, 0)};
  frames[1].tracked = {At(7, 350, 0), At(8, 250, 0)};
  const MotResult r = ClearMot(frames);
  EXPECT_EQ(r.id_switches, 0);
  EXPECT_EQ(r.pairs, 4);
  EXPECT_NEAR(r.motp_mm, 175, 1e-9);
  EXPECT_NEAR(r.mota, 1, 1e-12);
  // Beyond 500 mm a correspondence breaks: the nearest pairing takes over, and both
  // people changed tracks.
  frames[1].tracked = {At(7, 520, 0), At(8, 80, 0)};
  const MotResult broken = ClearMot(frames);
  EXPECT_EQ(broken.id_switches, 2);
  EXPECT_NEAR(broken.mota, 1 - 2.0 / 4, 1e-12);
}

// A track between two people goes to the one it leaves fewer people unpaired with, even
// when the other is nearer; and nobody anywhere is a perfect score.
TEST(ClearMot, PairsAsManyAsCanBePairedAndHandlesEmptyScenes) {
  std::vector<MotFrame> frames(1);
  frames[0].truth = {At(1, 0, 0), At(2, 450, 0)};
  frames[0].tracked = {At(5, 300, 0), At(6, -400, 0)};  // 5 nearer to 2, 6 only reaches 1
  const MotResult r = ClearMot(frames);
  EXPECT_EQ(r.pairs, 2);
  EXPECT_NEAR(r.motp_mm, (150 + 400) / 2.0, 1e-9);
  EXPECT_EQ(ClearMot(std::vector<MotFrame>(3)).mota, 1);
  std::vector<MotFrame> made_up(1);
  made_up[0].tracked = {At(1, 0, 0)};
  EXPECT_EQ(ClearMot(made_up).false_positives, 1);
  EXPECT_LT(ClearMot(made_up).mota, 0);
  frames[0].tracked.push_back(At(5, 1, 1));
  EXPECT_THROW(ClearMot(frames), std::invalid_argument);
}

}  // namespace
}  // namespace jgpm
