// Several fixed cameras placed in one world from the people they all see walk by (`jgpm
// calibrate --walkers A.avi,B.avi`), after each was calibrated on its own from them
// (walker_calibration.h).
//
// One camera's calibration puts it above its own world's origin looking along +z: its
// floor is known up to a turn about the vertical and a shift, and its scale (its height)
// rests on the stature prior. A walker seen by two cameras at the same moment stands on one
// floor point. Each sighting's floor point is its foot pixel's ray down to the foot point's
// height (foot_share of a person's height, as in the calibration), so the two cameras'
// floor tracks of that walker differ by a similarity of the floor: a turn, a shift and a
// scale (the ratio of the two cameras' height errors). Cameras with synchronised clocks
// share frame numbers (HeadFoot::frame); otherwise each camera's offset is searched for.
//
// Which walker in one camera is which in another is not known, and several people may be in
// view at once. Every pair of walkers, one in the camera being placed and one in a camera
// already placed, seen together for at least min_shared_frames frames, proposes a
// similarity (Umeyama's least squares on their time-matched floor points); it is scored by
// how many of the camera's sightings then land within match_mm of a placed camera's at the
// same frame, and the best is refitted on all its matches (RANSAC whose hypotheses are the
// walker pairs: there are few, so all are tried). A placement needs two of the camera's
// walkers matched: one straight walk maps onto any other of its length by some similarity,
// so one walker cannot tell a right placement from clocks that disagree. And it must agree
// with what the placed cameras saw: most people it puts in their view must be there.
// Cameras are placed one at a time, the one with most matches first, against every camera
// already placed: one that shares no walker with cam0 is placed through another.
//
// Then every camera is refined with all the others (Ceres): its own calibration is a
// Gaussian prior on its focal length, tilt, roll and height (the fit's covariance), and
// every pair of sightings the placement found to be one person at one frame, in any two
// cameras, must be one floor point. One camera's tilt error stretches its floor away from
// it; seen from other directions, that stretch cannot be explained by a turn and a shift,
// so the cameras correct each other. The world's scale still rests on the people's stature:
// the refined heights agree with each other, and their common scale is the priors'
// (weighted by each camera's height uncertainty).
//
// The world is cam0's: its floor point below cam0 is the origin, +z its view's direction on
// the floor, y up, mm.
#pragma once

#include <vector>

#include "calibration/walker_calibration.h"

namespace jgpm {

// One camera: its own calibration and the head-foot points it was calibrated from (walker
// numbers its own; frames on the clock all cameras share).
struct RigCamera {
  WalkerCalibration calibration;
  std::vector<HeadFoot> points;
};

struct RigPlacementOptions {
  // The foot point's height above the floor: WalkerCalibrationOptions' foot_share of its
  // person_height_mm (a walker's own height changes it by under 15 mm).
  double foot_height_mm = 0.15 * 1700;
  // Two cameras' sightings at one frame are one person when their floor points are this
  // close: people walking side by side are 0.5-1 m apart, and the floor point of a walker
  // 20 m from a camera is known to about 200 mm (a pixel of foot at 30-60 px tall).
  double match_mm = 500;
  // A walker pair proposes a placement when seen together this long (a third of a second
  // at 30 fps: a few steps) and spread over at least min_spread_mm of floor (a person
  // standing still fixes no turn).
  int min_shared_frames = 10;
  double min_spread_mm = 300;
  // A camera is placed when at least this many of its sightings match, two of its walkers
  // each for min_shared_frames, and at least min_seen_share of the sightings it puts wholly
  // in a placed camera's view at a frame it recorded (heads at person_height_mm) were seen
  // there (refused with one line otherwise). People hidden by others or merged with them
  // go unseen: on the tests' crowds a right placement matched 94-99%, a wrong one 14-20%.
  int min_matches = 20;
  double min_seen_share = 0.5;
  double person_height_mm = 1700;
  // Two cameras' scales differ by the ratio of their height errors, each a few percent: a
  // similarity scaling by more than this is a wrong match.
  double max_scale_ratio = 1.3;
  // Two cameras' floor points of one person differ by the foot points' definition (the
  // centroid of the silhouette's lowest 30%, seen from two sides: within the feet's
  // footprint, about +-100 mm) and by the pixels' noise at distance: sd per axis.
  double match_sd_mm = 150;
  // Consecutive sightings share their errors (the stride's sway, a blob's shape): each pair
  // of cameras' matches count as one observation per this many (half a gait cycle: 15 at
  // 30 fps; `jgpm calibrate` sets it from the frame rate).
  double correlated_frames = 15;
  // Each camera's focal length, height, tilt and roll, refined, must be determined to
  // these (as WalkerCalibrationOptions'): a camera whose own walkers left one loose (its
  // calibration made with refuse_undetermined off) may be pinned down by the others.
  double max_relative_sd = 0.10;
  double max_angle_sd_deg = 3;
  // The cameras' clocks may disagree by up to this many frames (videos started by hand):
  // each camera is placed at the offset within it whose placement matches most (0: the
  // clocks agree). Offsets are tried every min_shared_frames / 2 frames, then frame by
  // frame around the best: a walker moves about 50 mm a frame, so a placement a few frames
  // off still matches most sightings within match_mm.
  int max_clock_offset_frames = 0;
  // The offset is refined over this many frames either side of the best (rig_placement.cc):
  // the frames a walker (1.4 m/s) takes to cross match_mm, over which the placement's
  // tightness falls by a quarter to a half. `jgpm calibrate` sets it from the frame rate.
  int offset_fit_frames = 10;
};

struct PlacedCamera {
  Camera camera;           // in the rig's world, named as its calibration's
  int placed_against = -1; // the placed camera it shared the most matches with (cam0: -1)
  int matches = 0;         // its sightings matched with placed cameras' when it was placed
  int clock_offset_frames = 0;  // added to its frame numbers puts them on cam0's clock
  double rms_mm = 0;       // its floor points' distance from other cameras' of the same
                           // person, RMS after the joint fit
  // Refined with the others: one standard deviation each (the focal length's 0 when given).
  Estimate focal_px, height_mm, tilt_deg, roll_deg;
  // Its place in the rig's world: its view's turn on the floor (YawOf, degrees) and the
  // floor point below it (x, z, mm), each with one standard deviation. cam0: zeros.
  Estimate yaw_deg, x_mm, z_mm;
};

struct RigPlacement {
  std::vector<PlacedCamera> cameras;  // in the order given
};

// InputError, in one line, when fewer than two cameras are given, naming the camera that
// shares too few walkers with the others (no common view, clocks not synchronised), or
// naming one left undetermined.
RigPlacement PlaceRig(const std::vector<RigCamera>& cameras, const RigPlacementOptions& options = {});

// A placed camera's view on the floor: the turn about the vertical of its optical axis's
// horizontal part from +z, degrees, positive towards +x (atan2(x, z)).
double YawOf(const Camera& camera);

}  // namespace jgpm
