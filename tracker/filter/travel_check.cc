#include "tracker/filter/travel_check.h"

#include <cmath>
#include <numbers>
#include <string>

namespace jgpm {

bool TravelCheckOptions::Check(std::string* why) const {
  if (window_s > 0 && min_speed_mm_s >= 0 && max_angle_deg >= 90 && max_angle_deg <= 180 && streak >= 0) return true;
  if (why) *why = "travel check: window_s > 0, min_speed_mm_s >= 0, max_angle_deg in [90, 180], streak >= 0 (0: never)";
  return false;
}

void TravelCheck::Clear() {
  seen_.clear();
  streak_ = 0;
  speed_mm_s_ = -1;
}

bool TravelCheck::Against(double time_s, const Eigen::Vector2d& floor_mm, double direction_rad) {
  if (!seen_.empty() && !(time_s > seen_.back().time_s)) Clear();  // time went back: another source
  seen_.push_back({time_s, floor_mm});
  // The window starts at the latest estimate at least window_s old.
  while (seen_.size() > 2 && time_s - seen_[1].time_s >= options_.window_s) seen_.pop_front();
  const double span = time_s - seen_.front().time_s;
  speed_mm_s_ = -1;
  bool against = false;
  if (span >= options_.window_s) {
    const Eigen::Vector2d travel = floor_mm - seen_.front().floor_mm;
    speed_mm_s_ = travel.norm() / span;
    direction_rad_ = std::atan2(travel.x(), travel.y());
    const Eigen::Vector2d direction(std::sin(direction_rad), std::cos(direction_rad));
    against = travel.norm() >= options_.min_speed_mm_s * span &&
              travel.dot(direction) < std::cos(options_.max_angle_deg * std::numbers::pi / 180) * travel.norm();
  }
  streak_ = against ? streak_ + 1 : 0;
  if (options_.streak == 0 || streak_ < options_.streak) return false;
  Clear();
  return true;
}

}  // namespace jgpm
