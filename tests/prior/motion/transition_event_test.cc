// Transition events (prior/motion/transition_event.h) on synthetic motions whose event frame is
// known by construction (the oracle): a root that starts moving with constant acceleration
// after a short false start, the same played backwards (a stop), a thigh swung by a
// logistic step (the foot is fastest at its midpoint), a ballistic jump, a dip of the root;
// and the event list's parser.
#include "prior/motion/transition_event.h"

#include <cmath>

#include <gtest/gtest.h>

#include "io/mocap/asf.h"
#include "test_support.h"

namespace jgpm {
namespace {

using test::ExpectInputError;

constexpr double kFps = 120;
constexpr double kMmPerUnit = 25.4 / 0.45;  // the test skeleton's length unit

struct Fixture {
  Skeleton skeleton = ParseAsf(test::GaitAsfText(), "gait.asf");
  int Channel(const std::string& name) const {
    const std::vector<std::string> names = skeleton.ChannelNames();
    const auto it = std::find(names.begin(), names.end(), name);
    EXPECT_NE(it, names.end()) << name;
    return static_cast<int>(it - names.begin());
  }
  Motion Still(int frames) const {
    Motion m;
    m.values = RowMatrixXd::Zero(frames, skeleton.NumChannels());
    m.values.col(Channel("root.ty")).setConstant(1000 / kMmPerUnit);
    return m;
  }
};

// Standing for 1 s (with a 0.1 s shuffle at 0.5 m/s at t = 0.4 s, too short to be a
// start), then accelerating at 1 m/s^2 along z: the speed crosses 0.3 m/s at t = 1.3 s,
// frame 156.
Motion StartingWalk(const Fixture& f) {
  Motion m = f.Still(360);
  const int tz = f.Channel("root.tz");
  double z = 0;
  for (int i = 0; i < 360; ++i) {
    const double t = i / kFps;
    const double v = t >= 0.4 && t < 0.5 ? 0.5 : t > 1 ? (t - 1) : 0;  // m/s
    m.values(i, tz) = z / kMmPerUnit;
    z += v * 1000 / kFps;
  }
  return m;
}

TEST(TransitionEvent, StartIsTheHeldCrossingNotTheShuffle) {
  const Fixture f;
  const int at = FindTransitionFrame(f.skeleton, StartingWalk(f), TransitionKind::kStart, {}, "walk");
  EXPECT_NEAR(at, 156, 1);
  TransitionRules no_hold;
  no_hold.hold_s = 0;  // the shuffle counts then: the hold is what rejects it
  EXPECT_LT(FindTransitionFrame(f.skeleton, StartingWalk(f), TransitionKind::kStart, no_hold, "walk"), 70);
}

TEST(TransitionEvent, StopIsTheStartPlayedBackwards) {
  const Fixture f;
  Motion m = StartingWalk(f);
  m.values = m.values.colwise().reverse().eval();
  const int n = m.NumFrames();
  EXPECT_NEAR(FindTransitionFrame(f.skeleton, m, TransitionKind::kStop, {}, "walk"), n - 156, 1);
  // Played backwards it never starts: it is moving from its first frame, and the shuffle
  // at its end is too short.
  ExpectInputError([&] { FindTransitionFrame(f.skeleton, m, TransitionKind::kStart, {}, "walk"); }, {"no start"});
}

// The left thigh swings 70 degrees by a logistic step centred at t = 1.5 s (frame 180);
// the right one sways slowly. The left foot's speed peaks at the step's midpoint.
TEST(TransitionEvent, KickIsTheFastestFootsPeak) {
  const Fixture f;
  Motion m = f.Still(360);
  const int left = f.Channel("lfemur.rx"), right = f.Channel("rfemur.rx");
  for (int i = 0; i < 360; ++i) {
    const double t = i / kFps;
    m.values(i, left) = -70 / (1 + std::exp(-(t - 1.5) / 0.05));
    m.values(i, right) = 10 * std::sin(t);
  }
  EXPECT_NEAR(FindTransitionFrame(f.skeleton, m, TransitionKind::kKick, {}, "kick"), 180, 1);
}

// On the floor until frame 150, then a ballistic flight at 3.5 m/s up: frame 150 is the
// last on the floor (frame 151 is 29 mm up, past the 25 mm of contact).
TEST(TransitionEvent, JumpIsTheLastFrameOnTheFloor) {
  const Fixture f;
  Motion m = f.Still(300);
  const int ty = f.Channel("root.ty");
  for (int i = 150; i < 300; ++i) {
    const double t = (i - 150) / kFps, up_mm = std::max(0.0, 3500 * t - 0.5 * 9810 * t * t);
    m.values(i, ty) += up_mm / kMmPerUnit;
  }
  EXPECT_EQ(FindTransitionFrame(f.skeleton, m, TransitionKind::kJump, {}, "jump"), 150);
  ExpectInputError([&] { FindTransitionFrame(f.skeleton, f.Still(300), TransitionKind::kJump, {}, "still"); },
                   {"still", "no jump"});
}

TEST(TransitionEvent, DuckIsTheRootsLowestPoint) {
  const Fixture f;
  Motion m = f.Still(300);
  const int ty = f.Channel("root.ty");
  for (int i = 0; i < 300; ++i) {
    const double t = i / kFps;
    m.values(i, ty) -= 300 * std::exp(-(t - 1.2) * (t - 1.2) / (2 * 0.3 * 0.3)) / kMmPerUnit;
  }
  EXPECT_NEAR(FindTransitionFrame(f.skeleton, m, TransitionKind::kDuck, {}, "duck"), 144, 1);
}

TEST(TransitionEvent, RefusesWhatHasNoEvent) {
  const Fixture f;
  ExpectInputError([&] { FindTransitionFrame(f.skeleton, f.Still(200), TransitionKind::kStart, {}, "still.amc"); },
                   {"still.amc", "no start", "0.3 m/s"});
  const Skeleton footless = ParseAsf(test::SmallAsfText(), "small.asf");
  Motion m;
  m.values = RowMatrixXd::Zero(50, footless.NumChannels());
  ExpectInputError([&] { FindTransitionFrame(footless, m, TransitionKind::kKick, {}, "m.amc"); }, {"m.amc", "feet"});
  m.values(3, 0) = NAN;
  ExpectInputError([&] { FindTransitionFrame(footless, m, TransitionKind::kDuck, {}, "m.amc"); }, {"non-finite"});
  TransitionRules bad;
  bad.contact_mm = 60;
  ExpectInputError([&] { FindTransitionFrame(f.skeleton, f.Still(50), TransitionKind::kJump, bad, "m"); },
                   {"contact_mm"});
}

TEST(TransitionEvent, ParsesTheEventList) {
  const std::vector<TransitionEvent> events = ParseTransitionEvents(
      "# events\n131_03 start tune\n\n10_01 kick @2210   # the kick\n118_02 jump\n", "events.txt");
  ASSERT_EQ(events.size(), 3u);
  EXPECT_EQ(events[0].trial, "131_03");
  EXPECT_EQ(events[0].kind, TransitionKind::kStart);
  EXPECT_TRUE(events[0].tune);
  EXPECT_FALSE(events[0].frame_number.has_value());
  EXPECT_EQ(events[1].kind, TransitionKind::kKick);
  EXPECT_EQ(events[1].frame_number.value_or(0), 2210);
  EXPECT_FALSE(events[1].tune);
  EXPECT_EQ(events[1].line, 4);
  EXPECT_EQ(events[2].kind, TransitionKind::kJump);

  ExpectInputError([] { ParseTransitionEvents("131_03 hop\n", "e.txt"); }, {"e.txt:1", "start, stop, kick", "hop"});
  ExpectInputError([] { ParseTransitionEvents("131_03\n", "e.txt"); }, {"e.txt:1", "TRIAL KIND"});
  ExpectInputError([] { ParseTransitionEvents("x1 start\n", "e.txt"); }, {"e.txt:1", "trial id"});
  ExpectInputError([] { ParseTransitionEvents("131_03 start @0\n", "e.txt"); }, {"e.txt:1", "@FRAME"});
  ExpectInputError([] { ParseTransitionEvents("\n131_03 start @x\n", "e.txt"); }, {"e.txt:2", "@FRAME"});
  ExpectInputError([] { ParseTransitionEvents("131_03 start tune tune\n", "e.txt"); }, {"e.txt:1", "tune"});
  ExpectInputError([] { ParseTransitionEvents("# nothing\n", "e.txt"); }, {"e.txt", "no events"});
}

}  // namespace
}  // namespace jgpm
