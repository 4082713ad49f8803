// Where the person is, from foreground masks alone: the tracker's automatic start and its
// recovery after a loss. In each camera the bottom of a blob's body (its lowest pixels near
// the axis of its upper half, so that a shadow cast sideways along the floor is not taken
// for the feet) is where the feet touch the floor (y = 0), so its ray meets the floor at
// the person's place; with the light known (ShadowLight), the feet are where the far end
// of the shadow in the blob says they are; the ray through the blob's top, at that place,
// gives the height. A
// blob cut by the image's bottom edge (a camera near the walk) stands where its top ray
// is an adult's 1.7 m above the floor, but no farther than where the bottom edge meets
// the floor, if it shows at least 0.8 m of a person there, its height unknown; so does one
// resting on `hidden` pixels (a nearer person's drawing, a painted table: their legs are
// behind it), if it shows a head and shoulders (on the plaza clip a walker born behind
// another was placed 1.2 m too far and 0.77 of their size from their blob's bottom). Its
// feet are then also nearer than the blob's bottom but no nearer than where the hidden
// run below it ends (lower, they would show), and its head at 1.7 +- 0.1 m: it is placed
// in the middle of where both hold. From a camera near head height the head alone says
// little (behind a table, subject 35 seen from 1.5 m up: 2.1-6.2 m away by the head,
// 3.9-6.4 m by the table; the middle 160 mm from the truth, the head at 1.7 m 740 mm).
// The middle errs towards the far side for a short walker (a 1.65 m one in the locator's
// test: 1133 mm off, the head alone 856), the head alone nearer for a tall one (1.85 m:
// 2697 mm, in front of the table; the middle 622). One cut at the top edge
// has no height either. One cut by a side edge (someone entering or leaving) is a slice,
// an arm, a leg or a back, whose top is not a head: its height is unknown, and a person
// seen only so is not `whole` (on a phone's portrait video an arm alone was placed as an
// adult 4 m away; the tracker starts only on people wholly in some view, tracker.h). Blobs
// one above the other with a small gap (an occluder across the body) are one person; when
// asked, one blob with two heads side by side at its top (people walking together) is two,
// split between the heads, and one too tall for a person (one behind another, seen from
// above) is cut across (person_locator.cc).
// Blobs that cannot be a person standing on the floor (under 1 m or over 2.3 m tall, as
// clutter in the air is; seen whole, with an upper half whose rows are at the median wider
// than 0.7 of the height, or filling more than 0.96 of its convex hull, as a ball, a cart
// or a clutter blob is, the last also when something hides its feet, as a clutter disc
// resting on a painted pillar's top; a blob with a painted object above its top as well
// as below is in front of it, not behind it) are passed over; with several cameras the
// place that most cameras' blobs agree on (within 1 m) is taken, and the answer is the
// median of those blobs.
// Several people: the same, again and again, over the blobs not yet taken, so each blob is
// one person's; the caller chooses among them (the strongest, the nearest to a place where
// a tracked person is expected, or to a pixel a user pointed at).
#pragma once

#include <limits>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "calibration/camera.h"

namespace jgpm {

struct PersonSighting {
  bool found = false;
  Eigen::Vector2d floor_mm = Eigen::Vector2d::Zero();  // (x, z)
  double height_mm = 0;                                // floor to the top of the head (0:
                                                       // no camera saw both ends)
  int cameras = 0;                                     // cameras that saw a blob
  bool feet_seen = false;                              // the place is read from feet (else
                                                       // from the head at an adult's height)
  bool whole = true;                                   // some camera's blob is clear of the
                                                       // image's side edges
  std::vector<cv::Rect> boxes;                         // per camera: the blob's box (empty if none)
  std::vector<int> areas;                              // and its pixels (0 if none)
  // Per camera: where its blob's feet put the person (NaN when it has no blob here, or
  // read it from a head). The place is their median; a shadow at the feet or clutter
  // merged with the blob moves one camera's reading a metre while the others agree.
  std::vector<Eigen::Vector2d> camera_floor_mm;
};

// Every person the masks show, the best evidence first (the most cameras agreeing, then
// the largest blobs); each camera's blob is one person's. Blobs smaller than `min_blob_px`
// are not a person. `split_merged`: a blob with two heads side by side is split between
// them, and one too tall for a person is cut across (people born with --people all, and
// their starts). Off where a tracked person is looked for again near where they are
// expected (the tracker's second looks, a hidden person's return, a loss): there the
// parts of a crossing's blob misled it (the 3-walker crossing clip's MOTA over 4 seeds:
// 0.893 without splitting, 0.868 splitting everywhere, 0.889 at births and starts only;
// keeping the parts from the second looks alone gave 0.868).
// `hidden` (optional, per camera, CV_8UC1 of the mask's size): where people nearer are drawn
// (several tracked at once) and static occluders painted (tracker/frames/occluder_masks.h);
// a blob resting on them has its feet hidden, and is placed by its head and the hidden
// run below it. `painted` (optional, likewise): the static occluders alone, when known; a
// blob with one right above its top as well is in front of it, not behind (a drawing of
// someone is an estimate a few pixels off, and does not count). `light` (unit, towards it;
// ShadowLight's, when found): the masks hold the people's shadows, and a blob's lowest
// pixels may be its shadow's tip rather than its feet (FeetAboveShadow, person_locator.cc).
std::vector<PersonSighting> LocatePeople(const std::vector<Camera>& cameras, const std::vector<cv::Mat>& masks,
                                         int min_blob_px = 60, bool split_merged = false,
                                         const std::vector<cv::Mat>& hidden = {},
                                         const std::vector<cv::Mat>& painted = {},
                                         const std::optional<Eigen::Vector3d>& light = {});

// Which one, when several people are seen.
struct PersonPreference {
  enum class Kind {
    kStrongest,  // the best evidence (the first of LocatePeople)
    kNearPlace,  // the nearest to floor_mm, if within within_mm
    kNearPixel,  // the one whose box in `camera` is nearest `pixel` (0 inside it)
  };
  Kind kind = Kind::kStrongest;
  Eigen::Vector2d floor_mm = Eigen::Vector2d::Zero();
  double within_mm = std::numeric_limits<double>::infinity();
  int camera = 0;
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();

  static PersonPreference Near(const Eigen::Vector2d& floor_mm,
                               double within_mm = std::numeric_limits<double>::infinity()) {
    PersonPreference p;
    p.kind = Kind::kNearPlace, p.floor_mm = floor_mm, p.within_mm = within_mm;
    return p;
  }
};

// The preferred one of `people` (found false when none qualifies).
PersonSighting ChoosePerson(const std::vector<PersonSighting>& people, const PersonPreference& prefer);

// One place from several cameras' readings of it (`readings`, per camera, NaN where a
// camera has none), each trusted across its line of sight more than along it: a blob's
// column gives the bearing within a few degrees, while a shadow at the feet, clutter
// merged with the blob or an occluder moves its lowest row, and with it the reading along
// the line of sight by a metre or more (a coated walker 5 m from a level camera, a shadow
// and a passing blob merged with hers: 1.4 m nearer, 4 degrees off). Each reading counts
// with a standard deviation of kAlong of its distance from its camera along that line and
// kAcross of it (plus 100 mm) across; the place is their information-weighted mean, where
// the lines of sight of cameras seeing it from different sides meet. False when fewer
// than two cameras read it.
bool FuseReadings(const std::vector<Camera>& cameras, const std::vector<Eigen::Vector2d>& readings,
                  Eigen::Vector2d* place);

// The preferred one of LocatePeople (all of whom go to `everyone`, when given).
PersonSighting LocatePerson(const std::vector<Camera>& cameras, const std::vector<cv::Mat>& masks,
                            int min_blob_px = 60, const PersonPreference& prefer = {},
                            const std::vector<cv::Mat>& hidden = {}, const std::vector<cv::Mat>& painted = {},
                            std::vector<PersonSighting>* everyone = nullptr,
                            const std::optional<Eigen::Vector3d>& light = {});

}  // namespace jgpm
