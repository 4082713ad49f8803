// The head and foot points of the people in foreground masks, frame after frame, each
// numbered by walker: the evidence for calibrating a camera from the people who walk by
// (calibration/walker_calibration.h).
//
// A blob counts as one upright person, wholly in view, when it is tall enough to place a
// head to a pixel or two, taller than wide (a walker is 2-4 times taller than wide from the
// side or from above at 20-40 degrees; two people side by side, a car or a long shadow are
// not), and clear of the image's edges (a person cut off by the edge has no feet or no
// head). Its head point is the top edge of its top rows' middle, its foot point the bottom
// edge of its bottom rows' middle (between the feet). Blobs are linked into walkers by
// their foot points from frame to frame; short-lived walkers (clutter, a person split for
// a moment) are dropped.
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
  double end_share = 0.04;    // the share of the blob's rows averaged for the head's and
                              // foot's column (one or two rows at 50 px)
  double link = 0.25;         // a blob continues a walker when its foot point is within this
                              // share of its height of the walker's last one: a walker
                              // moves about 2% of their height per frame at 30 fps
  int max_gap_frames = 5;     // a walker unseen for longer (hidden, merged) starts anew
  int min_frames = 8;         // walkers seen in fewer frames are dropped
};

class WalkerPointFinder {
 public:
  WalkerPointFinder(int width, int height, const WalkerPointOptions& options = {});

  // One frame's mask (CV_8UC1, non-zero = foreground, the finder's size).
  void Add(const cv::Mat& mask);

  // Every walker's points seen in at least min_frames frames, walkers numbered from 0.
  std::vector<HeadFoot> Points() const;
  int frames() const { return frame_; }
  int width() const { return width_; }
  int height() const { return height_; }

 private:
  struct Track {
    int last_frame = 0;
    Eigen::Vector2d last_foot = Eigen::Vector2d::Zero();
    double last_height = 0;
  };
  WalkerPointOptions options_;
  int width_, height_;
  int frame_ = 0;
  std::vector<Track> tracks_;
  std::vector<HeadFoot> points_;  // walker = index into tracks_
};

}  // namespace jgpm
