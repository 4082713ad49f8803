// Painted occluders in depth: an object hides only the people behind it.
//
// A painting (tracker/frames/occluder_masks.h) says where a static object is in the image,
// not how far away it stands, and the likelihood took its pixels out for every body: a
// person walking in front of a painted object lost, as evidence, every pixel where they
// covered it, and a body drawn in front of it where nobody is seen paid nothing there. On
// the one-camera clip of the tracking suite (35_12-1cam) with a pillar painted standing
// behind the walk, 50 px wide and 150 rows tall, which the walker passes in front of for a
// quarter of the clip: 4 seeds 61.2 51.5 46.3 41.3 mm; now 54.9 48.7 42.1 37.4, the same as
// with no painting.
//
// Painted objects stand on the floor (y = 0), and an object's lowest pixel is its nearest
// foot: it stands as far from the camera, along the floor, as the ray through that pixel's
// lower edge meets the floor. It hides a body whose centre is farther than that, and not
// one nearer. An object cut by the image's bottom edge, or whose lowest pixel looks above
// the horizon (hanging, or beyond the floor the camera sees), stands at an unseen distance
// and hides every body, as before.
//
// Tried and not kept:
// - A cut object standing where the image's bottom row meets the floor. Its foot is
//   nearer, by how much unseen, and a body between the two is behind it: near a webcam,
//   where most objects are cut, a walker 2.0 m away passing behind a pillar whose bottom
//   row meets the floor at 2.5 m was charged for the pillar, and the tracker kept them
//   beyond 2.5 m (probe suite, 07_02-webcam-all, 93.5 -> 722 mm). The harsh webcam clips
//   gained from it (35_10-webcam-harsh-nocal 202.8 -> 73.7 mm: bodies drawn big and near
//   over a cut pillar were charged), which a cut object's unknown foot does not justify.
// - A body whose feet show below an object (in a column it covers, the floor point under
//   the body projects below its lowest pixel) taken to be in front of it. On the harsh
//   one-camera clip behind a table (35_15-1cam-harsh, the walker's shadow on the floor
//   under the table) it stopped the tracker putting the walker 0.7-0.9 m nearer, feet on
//   the shadow (528 -> 188 mm, 4 seeds), but a camera 1.5 m up sees the floor under a
//   table's top well behind the table, and walkers behind tables seen through that gap were
//   charged for the top (35_12-1cam-occluders 56.8 -> 126.8). Which of the two a body is
//   needs the table's far edge, which a painting does not give.
//
// Several people tracked at once: each person's frames keep the painting apart from the
// others' drawings (Frame::painted), so each person is layered the same way (a wall painted
// behind two walkers leaves both tracks as without it; mixed with the drawings, it hid
// their upper bodies and moved a joint by up to 718 mm: tests/tracker/filter/
// multi_tracker_test.cc).
//
// What it assumes: painted objects stand on the floor (a sign hanging from a ceiling is
// taken to stand where its lower edge's ray meets the floor, too far: a person under it,
// nearer, is charged for its pixels), and a body is in front of an object or behind it as
// a whole, its centre deciding.
#pragma once

#include <limits>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "calibration/camera.h"
#include "tracker/body/body_model.h"

namespace jgpm {

// One painted object.
struct PaintedObject {
  cv::Mat pixels;  // CV_8UC1, 255 on it, the painting's size
  // Of its nearest foot, along the floor; infinity when unseen (cut by the image's bottom
  // edge, or above the horizon).
  double distance_mm = std::numeric_limits<double>::infinity();
};

// The painting's objects (its 8-connected components), in the order found. `camera` is the
// one whose pixels the painting is in (at the painting's size).
std::vector<PaintedObject> SplitPainting(const cv::Mat& painting, const Camera& camera);

// The floor point (y = 0) under the body's centre: its capsules' midpoints averaged.
Eigen::Vector3d FloorPointUnder(const std::vector<Capsule>& capsules);

// Whether `object` (seen from `camera_centre_mm`) hides a body standing at `floor_point_mm`.
bool Hides(const PaintedObject& object, const Eigen::Vector3d& floor_point_mm, const Eigen::Vector3d& camera_centre_mm);

}  // namespace jgpm
