// Whether an estimate goes the way its dynamics move it. The state models move a walker
// along their heading, forwards or, with a negative cadence, backwards; the silhouettes
// say little of which way the walk goes through time (each frame is scored alone, and the
// annealing puts the place and the phase where the frame says, whatever the dynamics
// predicted). So a track can go on with the walk's direction wrong: started facing away
// from the walker and walking forwards, or turned (TrackerOptions::turn_every,
// reverse_every) to face the walker but walking the other way. Its estimates still follow
// the walker, against their own dynamics: this check sees that in the estimates' travel,
// and the tracker turns the cadence's sign (tracker.h).
//
// The check keeps the estimates of the last `window_s` seconds (frames explained well)
// and compares their travel with the direction the dynamics move them. Constants, by rule:
// - window_s 0.5: a walker's travel in it (0.5-0.75 m at 1-1.5 m/s) is more than ten times
//   a tracked estimate's jitter from frame to frame (20-40 mm), and it is half a walking
//   cycle, long enough for the hips' sway within a cycle to average out.
// - min_speed_mm_s 300: half a slow walk (0.6 m/s); below it, starting, stopping and
//   shuffling on the spot say little of a direction.
// - max_angle_deg 120: walking in an arc or turning, the travel over half a second lags the
//   heading by up to 90 degrees (a turn of 180 degrees in a second); beyond 120 the
//   estimate goes the other way.
// - streak 5: frames in a row, a sixth of a second, as TrackerOptions::mirror_streak (one
//   frame's travel can be off by chance: a relocation's jump).
#pragma once

#include <deque>
#include <string>

#include <Eigen/Core>

namespace jgpm {

struct TravelCheckOptions {
  double window_s = 0.5;
  double min_speed_mm_s = 300;
  double max_angle_deg = 120;
  int streak = 5;  // 0: never

  bool Check(std::string* why) const;
};

class TravelCheck {
 public:
  explicit TravelCheck(const TravelCheckOptions& options = {}) : options_(options) {}

  // Forgets the estimates (a start, a restart, the direction turned).
  void Clear();
  // A frame's estimate, explained well: its time, its place on the floor (x, z), and the
  // direction its dynamics move it (radians about +y: towards (sin, cos) in (x, z)). True
  // when the place has gone against that direction, at min_speed_mm_s or faster over
  // window_s, in `streak` frames in a row (then the check starts again).
  bool Against(double time_s, const Eigen::Vector2d& floor_mm, double direction_rad);
  // The estimates' speed over the window at the last Against (mm/s), whichever way they
  // went; < 0 while the window is not yet full (after a Clear).
  double Speed() const { return speed_mm_s_; }
  // And which way (radians about +y, as direction_rad); meaningless while Speed() < 0.
  double Direction() const { return direction_rad_; }

 private:
  struct Seen {
    double time_s;
    Eigen::Vector2d floor_mm;
  };
  TravelCheckOptions options_;
  std::deque<Seen> seen_;
  int streak_ = 0;
  double speed_mm_s_ = -1;
  double direction_rad_ = 0;
};

}  // namespace jgpm
