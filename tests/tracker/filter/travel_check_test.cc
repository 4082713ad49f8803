// The travel check (tracker/filter/travel_check.h) on walks by hand, 30 frames a second:
// a walk going the way its dynamics move it never fires; going against them at a walking
// pace it fires once the window (0.5 s: frame 15) is full and the streak (5 frames) is
// run, at frame 19, and then, the check started again, every 20 frames; too slow, or off by
// less than max_angle_deg, or a streak broken, it does not fire.
#include "tracker/filter/travel_check.h"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace jgpm {
namespace {

constexpr double kFps = 30;

// The frames at which the check fires over `frames` frames of a walk at `speed_mm_s`
// towards `travel_deg` (0: +z), its dynamics moving it towards `direction_deg`.
std::vector<int> Fires(double speed_mm_s, double travel_deg, double direction_deg, int frames,
                       const TravelCheckOptions& options = {}) {
  TravelCheck check(options);
  const double travel = travel_deg * std::numbers::pi / 180;
  std::vector<int> fired;
  for (int k = 0; k < frames; ++k) {
    const double t = k / kFps;
    const Eigen::Vector2d at = speed_mm_s * t * Eigen::Vector2d(std::sin(travel), std::cos(travel));
    if (check.Against(t, at, direction_deg * std::numbers::pi / 180)) fired.push_back(k);
  }
  return fired;
}

TEST(TravelCheck, AWalkGoingAgainstItsDynamicsIsSeenOnceTheWindowAndStreakAreFull) {
  EXPECT_EQ(Fires(1200, 30, 30, 60), (std::vector<int>{}));             // forwards
  EXPECT_EQ(Fires(1200, 30, 30 + 180, 60), (std::vector<int>{19, 39, 59}));  // against
  EXPECT_EQ(Fires(1200, 30, 30 + 130, 60), (std::vector<int>{19, 39, 59}));  // beyond 120
  EXPECT_EQ(Fires(1200, 30, 30 + 100, 60), (std::vector<int>{}));        // an arc's lag
  EXPECT_EQ(Fires(250, 30, 30 + 180, 60), (std::vector<int>{}));         // a shuffle
  TravelCheckOptions never;
  never.streak = 0;
  EXPECT_EQ(Fires(1200, 30, 30 + 180, 60, never), (std::vector<int>{}));
}

// The speed over the window, by hand: unknown (< 0) until the window is full, then the
// walk's, whichever way it goes and whether or not the check is on; and its direction,
// towards (-0.6, 0.8) in (x, z), atan2(-0.6, 0.8) about +y.
TEST(TravelCheck, TheSpeedIsTheWindowsTravelOverItsSpan) {
  TravelCheckOptions never;
  never.streak = 0;
  for (const TravelCheckOptions& options : {TravelCheckOptions{}, never}) {
    TravelCheck check(options);
    for (int k = 0; k < 30; ++k) {
      const double t = k / kFps;
      check.Against(t, Eigen::Vector2d(-600 * t, 800 * t), 0);  // 1 m/s
      if (t < options.window_s - 1e-9) EXPECT_LT(check.Speed(), 0) << k;
      else EXPECT_NEAR(check.Speed(), 1000, 1e-9) << k;
      if (t >= options.window_s) EXPECT_NEAR(check.Direction(), std::atan2(-0.6, 0.8), 1e-12) << k;
    }
    check.Clear();
    EXPECT_LT(check.Speed(), 0);
  }
}

// A frame whose place jumps back (a relocation) goes the dynamics' way over the window and
// breaks the streak, which starts again.
TEST(TravelCheck, AStreakBrokenStartsAgain) {
  TravelCheck check;
  const double against = std::numbers::pi;  // the dynamics move it towards -z; it walks +z
  std::vector<int> fired;
  for (int k = 0; k < 40; ++k) {
    const double t = k / kFps;
    Eigen::Vector2d at(0, 1200 * t);
    if (k == 17) at.y() -= 1200;  // back behind where it was half a second ago
    if (check.Against(t, at, against)) fired.push_back(k);
  }
  // Against from frame 15; frame 17 goes the dynamics' way; 18-22 against again.
  EXPECT_EQ(fired, (std::vector<int>{22}));
}

// Time going back (another source) starts the window again.
TEST(TravelCheck, TimeGoingBackStartsAgain) {
  TravelCheck check;
  for (int k = 0; k < 18; ++k) EXPECT_FALSE(check.Against(k / kFps, Eigen::Vector2d(0, 40.0 * k), std::numbers::pi));
  for (int k = 0; k < 19; ++k) EXPECT_FALSE(check.Against(k / kFps, Eigen::Vector2d(0, 40.0 * k), std::numbers::pi)) << k;
  EXPECT_TRUE(check.Against(19 / kFps, Eigen::Vector2d(0, 40.0 * 19), std::numbers::pi));
}

TEST(TravelCheck, BadOptionsAreNamed) {
  std::string why;
  EXPECT_TRUE(TravelCheckOptions{}.Check(&why));
  for (const auto& change : std::vector<void (*)(TravelCheckOptions*)>{
           [](TravelCheckOptions* o) { o->window_s = 0; },
           [](TravelCheckOptions* o) { o->window_s = std::nan(""); },
           [](TravelCheckOptions* o) { o->min_speed_mm_s = -1; },
           [](TravelCheckOptions* o) { o->max_angle_deg = 45; },
           [](TravelCheckOptions* o) { o->max_angle_deg = 200; },
           [](TravelCheckOptions* o) { o->streak = -1; },
       }) {
    TravelCheckOptions options;
    change(&options);
    why.clear();
    EXPECT_FALSE(options.Check(&why));
    EXPECT_NE(why.find("travel check"), std::string::npos) << why;
  }
}

}  // namespace
}  // namespace jgpm
