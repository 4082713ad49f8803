// A static camera calibrated from the people who walk past it (`jgpm calibrate --walkers`),
// without a chessboard: its focal length, its height above the floor, its tilt and roll.
//
// The evidence is a head point and a foot point per walker per frame (the silhouette's top,
// and the centroid of its lowest part: tracker/frames/walker_points.h finds them). Every
// person stands upright on one floor, so each pair lies on a vertical line: the foot
// pixel's ray falls to the foot point's height (a share of the walker's height) at F, and
// the head pixel's ray must pass through the vertical line through F (the head-foot lines
// meet at the vertical vanishing point) at the walker's height. Walkers seen at several
// distances fix the horizon and the focal length (Lv, Zhao and Nevatia, "Camera
// calibration from video of a walking human", PAMI 2006); the scale, the camera's height,
// comes only from how tall people are, so each walker's height is a parameter under a
// prior of adult stature (Krahnstoever and Mendonca, "Bayesian autocalibration for
// surveillance", ICCV 2005). The fit is Ceres least squares over
//   per frame:  (height of the head on F's vertical - H_walker) / sd_within
//               (head ray's miss of that vertical - lean_walker, mm) / sd_line
//   per walker: (H_walker - person_height) / person_height_sd, lean_walker / lean_sd
// with a Huber loss on the frames (a blob that merged with a shadow or a bag), and each
// parameter's uncertainty from the fit's covariance at the minimum, scaled up by the
// residuals' spread when they are wider than the stated noise; beside it, how far the
// camera moves with other walkers (a jackknife over groups of them: see
// WalkerCalibrationOptions::jackknife_groups).
//
// The camera found is placed in a world of its own: above the world origin, looking along
// +z (yaw and the position on the floor are not observable from one camera); y up, floor
// y = 0, mm, as everywhere. Principal point at the image centre and no lens distortion,
// unless the user's intrinsics (a chessboard calibration) are given: then they are kept and
// only the height, tilt and roll are fitted.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "calibration/camera.h"
#include "calibration/walker_camera.h"

namespace jgpm {

// One walker in one frame, pixels.
struct HeadFoot {
  Eigen::Vector2d head_px = Eigen::Vector2d::Zero();  // top of the head
  Eigen::Vector2d foot_px = Eigen::Vector2d::Zero();  // low on the legs (foot_share below)
  int walker = 0;                                     // same number: same person
  int frame = 0;  // when: the frame's number on the video's clock (several cameras placed
                  // together, calibration/rig_placement.h, match their walkers by it)
};

struct WalkerCalibrationOptions {
  // Adult stature (top of the head above the floor): a mixed population's mean and spread
  // (about 1.75 m for men and 1.62 m for women, each with a 70 mm spread).
  double person_height_mm = 1700;
  double person_height_sd_mm = 90;
  // One walker's head above the floor from frame to frame: the gait's bob (about +-25 mm)
  // plus the silhouette's edges, each known to about edge_sd_px; at a person height of P
  // pixels a pixel is person_height_mm / P mm, so
  //   sd_within = hypot(within_sd_mm, edge_sd_px * person_height_mm / P).
  double within_sd_mm = 25;
  double edge_sd_px = 1.5;
  // The foot point's height, as a share of the walker's: the centroid of the silhouette's
  // lowest 30% (the legs below mid-thigh, both of them whatever the stride; the lowest
  // pixel alone is the nearest toe or heel, 30-235 mm nearer the camera than the person and
  // it biased the tilt by 3 degrees). Measured through the cameras that rendered the clean
  // tracking suite's clips (ring rig, 263 views): 0.152 +- 0.026.
  double foot_share = 0.15;
  // The head's radius: seen from above, a round head's silhouette top lies above its top
  // point (walker_calibration.cc, HeadOnVertical). An adult head is about 150 mm wide and
  // 195 mm long.
  double head_radius_mm = 90;
  // The head's sideways miss of the foot's vertical: each walker leans (a walker leans
  // forward by 3-5 degrees, 90-150 mm at the head: the lean seen from the camera is a
  // parameter per walker under this prior), and from frame to frame arms and legs move
  // the blob's middles (on rendered walks through the cameras that rendered them: 2-5% of
  // the height about each walker's own mean, which ranged over -3..+8%).
  //   sd_line = hypot(line_sd_mm, edge_sd_px * person_height_mm / P).
  double lean_sd_mm = 100;
  double line_sd_mm = 60;
  // A walker's frames are not independent: the errors above (the bob, the silhouette's
  // shape, the lean) repeat over a stride. Each walker's frames count as one observation
  // per `correlated_frames` (half a gait cycle: 15 at 30 fps; `jgpm calibrate` sets it
  // from the video's frame rate): their noise is scaled up by
  // sqrt(min(correlated_frames, the walker's frames)). Without it, on rendered walks
  // each spanning under a metre of depth, systematic within-walk trends of 10-190 mm/m
  // outweighed the stature prior and put a 4761 mm camera at 3691 mm.
  double correlated_frames = 15;
  // The fit's covariance holds only if every walker is the model's: upright, their head
  // and foot points at the stated shares of their height, their errors independent of the
  // others'. Real walkers are not (coats and skirts move the foot point, hair and hats
  // the head's top, a bag the blob's middle), and each such walker pulls the camera its
  // own way for all of their frames. So the walkers are also dealt round-robin into
  // this many groups, the fit redone without each group (from the fit found), and the
  // spread of those fits, scaled as a jackknife's ((G-1)/G times the sum of squares), is
  // reported beside the covariance's (on vtest.avi three times it). Ten: the delete-a-
  // group jackknife's usual count, each refit a tenth of the walkers short; with fewer
  // walkers each is its own group, under 3 none (0: not measured). The refusals below
  // read the covariance's, which says whether the walkers' geometry determines the camera.
  int jackknife_groups = 10;
  // The user's calibration: its intrinsics and distortion are kept (only the pose fitted).
  std::optional<Camera> intrinsics;
  // Refused (InputError) when the walkers do not determine a parameter better than this
  // (one standard deviation): the focal length and height relative, the angles in degrees.
  double max_relative_sd = 0.10;
  double max_angle_sd_deg = 3;
  // Off when other cameras will determine it further (rig_placement.h checks it after).
  bool refuse_undetermined = true;
  int min_points = 20;
};

struct Estimate {
  double value = 0;
  double sd = 0;  // one standard deviation
  // How much the value moves with the walkers who happened to pass (0: not measured):
  // a delete-a-group jackknife over them (WalkerCalibrationOptions::jackknife_groups).
  double walkers_sd = 0;
};

struct WalkerCalibration {
  Camera camera;  // placed as above, named "cam0"
  Estimate focal_px, height_mm, tilt_deg, roll_deg;
  int walkers = 0;
  double rms_line_px = 0;       // the head rays' sideways miss, px
  double rms_height_mm = 0;     // heads around their walker's height, mm
  std::vector<double> walker_heights_mm;  // each walker's height found, in walker order
  // The fit itself (walker_camera.h) and its covariance, scaled as the uncertainties above
  // (the focal length's row and column zero when the intrinsics were given): for refining
  // the camera with others that see the same walkers (rig_placement.h).
  WalkerCameraParameters parameters{};
  Eigen::Matrix4d covariance = Eigen::Matrix4d::Zero();
};

// The camera from head-foot pairs seen in an image of `width` x `height` pixels. Walker
// numbers may be any integers. InputError, in one line, when there are too few pairs, when
// the pairs cannot be a person on a floor (foot points above the horizon of every
// plausible camera), or when a parameter is not determined (the message names it, its
// uncertainty, and what would help: walkers nearer and farther from the camera).
WalkerCalibration CalibrateFromWalkers(const std::vector<HeadFoot>& points, int width, int height,
                                       const WalkerCalibrationOptions& options = {});

// InputError naming `where` and the first of the four not determined to the options'
// bounds (a focal length given by the user has sd 0).
void RequireDetermined(const std::string& where, const Estimate& focal_px, const Estimate& height_mm,
                       const Estimate& tilt_deg, const Estimate& roll_deg, const WalkerCalibrationOptions& options);

// The same four numbers read off any placed camera (for comparing with a calibration):
// tilt down from level, and roll, in the convention of CalibrateFromWalkers; the height
// is the centre's y.
struct CameraAngles {
  double tilt_deg = 0, roll_deg = 0, height_mm = 0;
};
CameraAngles AnglesOf(const Camera& camera);

}  // namespace jgpm
