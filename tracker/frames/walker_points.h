// The head and foot points of the people in foreground masks, frame after frame, each
// numbered by walker: the evidence for calibrating a camera from the people who walk by
// (calibration/walker_calibration.h).
//
// A blob counts as one upright person, wholly in view, when it is tall enough to place a
// head to a pixel or two, taller than wide (a walker is 2-4 times taller than wide from the
// side or from above at 20-40 degrees; two people side by side, a car or a long shadow are
// not), and clear of the image's edges (a person cut off by the edge has no feet or no
// head). Its head point is the top edge below the middle of its top rows; its foot point
// the centroid of its lowest 30%: both legs below mid-thigh, whatever the stride, about
// 15% of the person's height above the floor (calibration/walker_calibration.h,
// foot_share). The lowest pixel would be the nearest toe or heel, off the person's
// vertical by up to half a stride. Blobs are linked into walkers by their head points from
// frame to frame; blobs of a height unlike their neighbours' and short-lived walkers
// (clutter, a person split for a moment) are dropped.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "calibration/walker_calibration.h"

namespace jgpm {

struct WalkerPointOptions {
  double min_height = 0.06;   // of the image's rows (14 px at 240, 29 at 480): a head to
                              // about a pixel is 3-7% of the person
  double min_aspect = 1.4;    // height over width, above: a walker with arms and legs apart
                              // seen from 40 degrees up is still 1.6-2
  int margin_px = 2;          // a blob this close to an edge is cut off by it
  double head_share = 0.04;   // the share of the blob's rows averaged for the head's
                              // column (one or two rows at 50 px)...
  double foot_share = 0.30;   // ...and the lowest share whose centroid is the foot point
                              // (must match WalkerCalibrationOptions::foot_share's rule)
  double link = 0.25;         // a blob continues a walker when its head point is within
                              // this share of its height of the walker's last one: a
                              // walker moves about 2% of their height per frame at 30 fps
                              // (the head, not the feet: background subtraction loses dark
                              // legs more often than a head)
  int max_gap_frames = 5;     // a walker unseen for longer (hidden, merged) starts anew
  int min_frames = 8;         // walkers seen in fewer frames are dropped
  // A blob more than height_tolerance taller or shorter than the median of its walker's
  // blobs over height_window_frames lost or gained a part (legs the subtraction missed, a
  // shadow, a passer-by): dropped. A walker's height in pixels changes by a few percent in
  // half a second (walking toward a camera 5 m away at 1.4 m/s: 14%/s).
  double height_tolerance = 0.08;
  int height_window_frames = 15;
};

class WalkerPointFinder {
 public:
  WalkerPointFinder(int width, int height, const WalkerPointOptions& options = {});

  // One frame's mask (CV_8UC1, non-zero = foreground, the finder's size).
  void Add(const cv::Mat& mask);
  // A frame the video lost (dropped): the clock moves on, nothing is seen.
  void Skip() { ++frame_; }

  // Every walker's points seen in at least min_frames frames, walkers numbered from 0,
  // each point's frame the number of frames added or skipped before it.
  std::vector<HeadFoot> Points() const;
  int frames() const { return frame_; }  // added and skipped

 private:
  struct Track {
    int last_frame = 0;
    Eigen::Vector2d last_head = Eigen::Vector2d::Zero();
    double last_height = 0;
  };
  WalkerPointOptions options_;
  int width_, height_;
  int frame_ = 0;
  std::vector<Track> tracks_;
  std::vector<HeadFoot> points_;  // walker = index into tracks_
  std::vector<double> heights_;   // each point's blob height, px
};

}  // namespace jgpm
