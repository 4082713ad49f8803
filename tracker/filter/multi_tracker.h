// Several people at once (jgpm track --people all): one Tracker (tracker.h) per person, each
// with its own particles, prior, refinement and build, all reading the same masks.
//
// Interaction. People hide one another and walk through each other's pixels. Each frame the
// people are updated one after another, nearest the first camera first (the nearest are the
// least hidden, so their estimates are the surest; a person behind is then updated knowing
// where they are). A person's masks lose the pixels where the others' latest estimates are
// drawn (grown by hidden_grow_px), and those pixels are `hidden` for them
// (observation.h): not foreground to explain, not background to avoid, so a body behind
// another is not penalised for the mask it cannot see and is not pulled onto the other's
// pixels. Updating in sequence rather than jointly keeps the cost linear in the number of
// people (one person's filter per person), where a joint state's particles would have to
// grow with its dimension; its price is that a person updated first sees the others where
// they were a frame before.
//
// Birth. What no tracked person explains (the masks less everyone's drawings, grown by
// explained_grow of the image height) is searched for people as a single tracker's start
// does (person_locator.h: a blob standing on the floor, 1-2.3 m tall, wholly in some view;
// one resting on someone's drawing is behind them, placed by the head: the plaza's walker
// born behind another was placed 1.2 m too far, 0.77 of their size, from their blob's
// bottom, and tracked 24 frames before the masks set them right);
// a place seen in birth_frames of the last birth_window frames, always within a walker's
// reach of where it was seen before (birth_speed_mm_s), farther than birth_clear_mm from
// everyone tracked or a whole person's shape (its height read, its blob at least
// shaped_area of its height squared: someone walking beside a tracked person, not a
// sliver of their pixels that their estimate leaves over), at least min_birth_share of an
// image's pixels, and not contradicted by a camera that has the place in view and sees
// nothing there, starts a new person: the start-up of tracker.h on those frames'
// unexplained masks, choosing the person nearest that place, placed where the walk
// fitted through them is at the last of them (at 10 frames/s a walker seen in 8 frames
// has gone a metre since the first). Sightings of one frame with blobs in the same camera
// are different people (the locator gives each blob, or each part of a merged blob split
// at its heads, to one), however near. A shadow on the floor (no height), a blob in the
// air or a flicker seen in a frame or two does not start anyone.
//
// Confirmation. A new person is reported once confirm_frames of their first birth_window
// frames are tracked with a mean IoU of confirm_iou or more (over the cameras in which
// they do not stand behind a painted object: a walker wholly behind a pillar in one
// camera, explained at 0.5 in the other, was held back for 15 frames by the first
// camera's 0); one who is not by then was something else (a blob one camera places far
// away, which no body explains: clutter crossing a webcam's view was started as a person
// 9 m away and explained at IoU 0.2 by the best body; walkers are explained at 0.4-0.7)
// and ends unreported.
//
// Death. A person lost (tracker.h: explained badly, or out of every view), or not tracked
// while nobody and nothing stands in front of them (half their drawing under others' or
// under a painted object in some camera), for death_s in a row ends: a single tracker
// keeps a person it cannot see predicted for up to two seconds, taking them for hidden,
// but among several people tracked the ones who could hide them are known (and each
// tracker, told where the others are drawn, predicts its person while behind them rather
// than drop them: tracker.h). A person standing taller than max_stature_mm for death_s in
// a row ends: what only a giant explains is not a person (a clutter blob drifting over a
// plaza's far side was followed 11 m away as a body 2.5 m tall, and a man at a car's open
// boot at vtest.avi's edge, legs hidden, 56 m away as one 2.24 m tall: the silhouette fit
// grows a body to its bounds, 2.3-2.5 m, and holds it there); such a frame does not count
// towards confirmation either. Two people within duplicate_mm of each other on the floor
// for duplicate_s in a row (a second: people crossing share a place for a third of one),
// or duplicate_same_way_s walking the same way, are one person followed twice (two bodies
// do not stand in one place): the one born later ends.
//
// A birth's start is gone over backwards, as a single tracker's is (tracker.h,
// TrackerOptions::start_backwards_s): start_backwards_s after the first frame a person was
// stepped in, their tracker goes back over those frames as the person saw them (the
// others' drawings hidden), and the second pass's estimates replace the first's where
// they explain the masks as well (back_over_margin); they are given in that frame's
// `earlier`. Only the birth's start: a person lost before then stays as tracked. The
// second pass goes on back into the frames the birth saw them in, before the frame they
// were stepped from, while it explains them well (StartBackOver's lead-in, tracker.h):
// a birth takes birth_frames of birth_window frames, which were frames missed.
//
// Identities are the trackers': each follows its own person by its own dynamics (place,
// heading, speed, gait phase) and build, and looks again for them only near where those put
// them.
//
// Constants. birth_frames / birth_window: a third of a second at 30 fps, past a mask's
// flicker (clutter blobs and segmentation noise come and go frame to frame) and short
// against the seconds a walker stays in view. birth_clear_mm and duplicate_mm: a body is
// about 400-500 mm across the shoulders; two people closer than that overlap, and a part of
// a tracked person left over by a slightly wrong estimate lies within 700 mm of its root.
// min_birth_share 0.1%: a 60 px tall person (the smallest the surveillance rigs show) covers
// about 600 px of 640x480, half of that, as a share so that it holds at any working size.
// death_s: half a second, the time for a tracker to find a person again after a short
// occlusion (tracker.h keeps a hidden person predicted meanwhile).
// max_stature_mm: the tallest adult (kMaxAdultMm, 2.05 m: the mean and 3.5 standard
// deviations) read 7% tall, the most a fitted body's height has been off for a real walker
// (one elevated camera, a coat and a shadow: walkers of 1.6-1.8 m read up to 2.18 m in the
// plaza clips; vtest.avi's walkers, at most 1.9 m).
#pragma once

#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "tracker/filter/tracker.h"

namespace jgpm {

struct MultiTrackerOptions {
  int max_people = 8;
  int birth_frames = 5;
  int birth_window = 8;
  double birth_speed_mm_s = 3000;  // a brisk walk is 1.5-2 m/s; 3 m/s with the locator's error
  double birth_margin_mm = 400;    // ...plus this, the locator's error on clean masks
  double birth_clear_mm = 700;
  double shaped_area = 0.1;        // a walker's blob covers 0.2-0.25 of its height squared
  double explained_grow = 0.0125;  // share of the image height (6 px at 480)
  double min_birth_share = 0.001;
  int confirm_frames = 3;        // a new person is reported once this many of its first
  double confirm_iou = 0.3;      // birth_window frames explain the masks this well (mean IoU)
  // In seconds, not frames, so that a surveillance camera's 10 frames/s keeps a stale body
  // as briefly as 30 frames/s does (15 frames were 1.5 s of a body walking on in vtest.avi's
  // plaza, where the person was not); runs are counted in frame intervals, to half a frame.
  double death_s = 0.5;
  double max_stature_mm = 2200;  // ...or as long taller than this (Death, above)
  double duplicate_mm = 400;
  double duplicate_s = 1;                 // ...or this long when they walk the same way
  double duplicate_same_way_s = 1.0 / 3;  // (heading within duplicate_heading_deg)
  double duplicate_heading_deg = 45;
  int hidden_grow_px = 1;
  // A person's tracker restarts only on someone this near where they were last explained
  // well: half a second's lost frames at a brisk 2 m/s and the locator's error; farther is
  // someone else's, or a leftover of their pixels (a sliver placed 8 m away was taken).
  double restart_within_mm = 1500;

  bool Check(std::string* why) const;
};

// One person in a frame.
struct PersonFrame {
  int id = 0;  // 1, 2, ... in order of birth; never reused
  TrackedFrame frame;
};

struct PeopleFrame {
  int index = 0;
  double time_s = 0;
  std::vector<PersonFrame> people;  // those alive and confirmed, by id
  std::vector<int> born;            // ids in their first frame reported
  std::vector<int> ended;           // ids that ended at this frame (not in `people`)
  double seconds = 0;               // wall time of the frame's tracking, everyone's
  // Estimates of frames before this one (frame index, estimate), each new or replacing
  // the person's estimate given for that frame before: the frames before a person's
  // confirmation (in `born`), from the first they were stepped in, which were not reported
  // then; and a birth's first start_backwards_s gone back over. A live consumer shows
  // people once confirmed; a recording's output (TrackPeople) puts these in their frames,
  // so that a track begins where the person was first followed, not confirm_frames later
  // (at the start of a clip every walker's first 2 frames: 6 of the 3-walker crossing's
  // 18.5 misses a run).
  std::vector<std::pair<int, PersonFrame>> earlier;
};

class MultiTracker {
 public:
  // InputError for bad options (as Tracker's). `tracker`: every person's options; person i
  // runs with annealing seed `seed + 1000003 (i - 1)`, so that each has its own random
  // numbers and the first is a single tracker's.
  MultiTracker(const GaitModel& model, const std::vector<Camera>& cameras, const TrackerOptions& tracker,
               const MultiTrackerOptions& options, std::shared_ptr<const PoseTable> table = nullptr);
  ~MultiTracker();

  const MultiTrackerOptions& options() const { return options_; }
  const TrackerOptions& tracker_options() const { return tracker_options_; }
  // The light casting the walkers' shadows in the masks, once found, and the frame it was
  // found at (-1: none).
  const std::optional<ShadowLight>& shadow_light() const { return shadow_light_; }
  int shadow_light_frame() const { return shadow_light_frame_; }
  const BodyModel& body(int id) const;  // a person's body as drawn (alive or not)

  // Looks at the first frames of a source for everyone in view (a place seen in
  // birth_frames of them, or in most of them when they are fewer): each starts at the
  // first of them it was seen in. Step must then be given these frames again, in order.
  void Start(const std::vector<Frame>& frames);
  // One frame: everyone alive updated, then deaths and births.
  PeopleFrame Step(const Frame& frame);

 private:
  struct Person;
  struct Candidate {
    Eigen::Vector2d floor_mm;
    double last_time_s = 0;
    int first_frame = 0;
    std::vector<int> seen;                  // frame indices
    std::vector<Eigen::Vector2d> places;    // where, in those frames
    std::vector<std::vector<cv::Rect>> boxes;  // and the blobs, per camera (empty: none)
    bool shaped = false;                     // the last sighting PersonShaped
  };
  // Whether two candidates are one person: in a frame both were seen in by different
  // cameras only (blobs of one camera are different people), their places are within
  // birth_clear_mm, or one's place (a body's middle above it) falls beside the other's blob
  // (a camera alone places a person along its ray, and a shadow or a cut-off foot moves
  // that place: two cameras' single sightings of one person can lie a metre or more apart).
  bool Same(const Candidate& a, const Candidate& b) const;
  // The candidates that qualify (seen in `needed` frames), one per person, the most seen
  // first, born from the frames in `frames` that they were seen in or after.
  void BearQualified(int needed, const std::vector<Frame>& frames, bool from_first_seen, int next_frame);
  // Each camera's pixels where person `skip`'s others are drawn (skip -1: everyone's),
  // grown by `grow` pixels.
  std::vector<cv::Mat> Drawn(int skip, int grow) const;
  // The sightings of this frame's unexplained masks feed the candidates; any that qualify
  // (not in the final batch: Start bears them at its end) are born from the recent
  // unexplained frames.
  void Look(const Frame& unexplained, bool final_batch);
  // A person started on the candidate from `frames`, stepped from `first_frame` on; `past`:
  // the frames are behind (a birth while tracking), so the start is where the walker is at
  // the last of them.
  bool Bear(const Candidate& c, const std::vector<Frame>& frames, int first_frame, bool past);
  bool Clear(const Eigen::Vector2d& floor_mm) const;
  // Whether a sighting of what nobody explains is a whole person's shape in some camera
  // (its height read, its blob's pixels at least shaped_area of its height squared): then
  // it is someone beside a tracked person, not a leftover of their pixels.
  bool PersonShaped(const PersonSighting& s) const;
  // Whether a camera that did not see the sighting has it wholly in view and, where a
  // 1.7 m person standing there would show, under 5% foreground (a blob one camera places
  // far away, clutter or a shadow, that another camera would see as a person and does not).
  // The pixels of `painted` objects (per camera, may be empty) are not seen: where a
  // painting covers half that place or more, the camera has no say (a walker wholly behind
  // a pillar in one camera was never born from the other camera's clear view of them).
  bool Contradicted(const PersonSighting& s, const std::vector<cv::Mat>& masks,
                    const std::vector<cv::Mat>& painted) const;
  // The person's last estimate's mean IoU (TrackedFrame::MeanIou) over the cameras in which
  // at most half of their drawing is under the `painted` objects (per camera, may be
  // empty); over all of them when there are none such.
  double ConfirmIou(const Person& p, const std::vector<cv::Mat>& painted) const;
  // Whether at least half of the person's drawing is under others' or under the `painted`
  // objects (per camera, may be empty) in some camera.
  bool Behind(const Person& p, const std::vector<cv::Mat>& painted) const;
  // Holds the frame the person was just stepped in (`mine`, as they saw it) while their
  // birth's start is not gone back over; once start_backwards_s has passed, goes back over
  // it (Tracker::BackOver) and keeps the second pass's estimates in p->revised.
  void GoBackOver(Person* p, const Frame& mine) const;

  const GaitModel& model_;
  std::vector<Camera> cameras_;
  TrackerOptions tracker_options_;
  MultiTrackerOptions options_;
  std::shared_ptr<const PoseTable> table_;
  std::vector<std::unique_ptr<Person>> people_;   // alive, by id
  std::vector<std::unique_ptr<Person>> ended_;    // kept for body(id)
  std::vector<Candidate> candidates_;
  // The light casting the walkers' shadows, once anyone's tracker has found it: one scene,
  // one light, given to everyone tracked and born since (Tracker::AdoptShadowLight).
  std::optional<ShadowLight> shadow_light_;
  int shadow_light_frame_ = -1;
  std::deque<Frame> recent_;  // unexplained masks of the last frames (start_frames)
  int next_id_ = 1;
  int looked_until_ = -1;     // frames Start has looked at already
  // (id, later id): time in a row within duplicate_mm, and within it walking the same way.
  std::map<std::pair<int, int>, std::pair<double, double>> together_;  // seconds
  double last_time_s_ = 0;  // the last frame's
  bool stepped_ = false;
};

// Puts the last frame's `earlier` estimates into the frames before it in `frames` (in
// place of the person's estimate there, if any), each person born at the first frame they
// are in.
void PlaceEarlier(std::vector<PeopleFrame>* frames);

// Tracks every frame of a source: the first start_frames are looked at to start everyone
// seen, then tracked like the rest. `on_frame` and `stop` as TrackSource's; `on_frame`
// sees each frame as it was tracked, the frames returned also hold each person's
// estimates from before they were confirmed (PeopleFrame::earlier).
std::vector<PeopleFrame> TrackPeople(FrameSource* source, MultiTracker* tracker,
                                     const std::function<void(const Frame&, PeopleFrame&)>& on_frame = {},
                                     const std::function<bool()>& stop = {});

}  // namespace jgpm
