#include "tracker/filter/multi_tracker.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

#include <opencv2/imgproc.hpp>

#include "io/base/error.h"
#include "tracker/filter/assignment.h"

namespace jgpm {
namespace {

// A source's frame as the people see it: its hidden pixels are the static occluders
// painted for its cameras (tracker/frames/occluder_masks.h), kept apart (Frame::painted)
// from the others' drawings that each person's frames add as hidden.
Frame PaintingApart(Frame frame) {
  frame.painted = std::move(frame.hidden);
  frame.hidden.clear();
  return frame;
}

}  // namespace

bool MultiTrackerOptions::Check(std::string* why) const {
  const auto fail = [why](const char* text) {
    if (why) *why = text;
    return false;
  };
  if (max_people < 1) return fail("max people: expected at least 1");
  if (birth_frames < 1 || birth_window < birth_frames) return fail("birth frames: expected 1 to the birth window");
  if (!(birth_speed_mm_s > 0 && restart_within_mm > 0 && birth_margin_mm >= 0 && birth_clear_mm >= 0 && duplicate_mm >= 0))
    return fail("birth and duplicate distances: expected non-negative numbers (a positive speed)");
  if (!(explained_grow >= 0 && explained_grow < 0.5 && min_birth_share >= 0 && min_birth_share < 1))
    return fail("explained grow and min birth share: expected shares of the image");
  if (confirm_frames < 1 || confirm_frames > birth_window || !(confirm_iou >= 0 && confirm_iou <= 1) || hidden_grow_px < 0)
    return fail("frame counts: expected positive");
  if (!(death_s > 0 && duplicate_s > 0 && duplicate_same_way_s > 0)) return fail("death and duplicate times: expected positive");
  if (!(max_stature_mm > 0)) return fail("max stature: expected a positive height in mm");
  return true;
}

struct MultiTracker::Person {
  int id = 0;
  std::unique_ptr<Tracker> tracker;
  int first_frame = 0;      // stepped from this frame on
  bool has_estimate = false;
  TrackedFrame last;
  std::vector<cv::Mat> drawn;  // the last estimate in each camera (empty: not drawn)
  double lost_s = 0;    // time in a row lost
  double unseen_s = 0;  // and not tracked (predicted or lost) with nobody in front
  bool giant = false;   // the last estimate stands taller than max_stature_mm
  double giant_s = 0;   // and time in a row so
  int stepped = 0;     // frames stepped
  int good = 0;        // of them, tracked at confirm_iou or more
  bool confirmed = false;
  bool reported = false;  // in a frame's people already
  std::vector<std::pair<int, TrackedFrame>> unreported;  // estimates before confirmation
  // The birth's start until gone back over (GoBackOver): the frames as the person saw them
  // and the first pass's estimates; then the second pass's, to be given (frame index,
  // estimate).
  bool going_back = false;
  std::vector<Frame> lead_frames;  // the birth's frames before first_frame (a lead-in)
  std::vector<Frame> held_frames;
  std::vector<TrackedFrame> held_estimates;
  std::vector<std::pair<int, TrackedFrame>> revised;
};

MultiTracker::MultiTracker(const GaitModel& model, const std::vector<Camera>& cameras, const TrackerOptions& tracker,
                           const MultiTrackerOptions& options, std::shared_ptr<const PoseTable> table)
    : model_(model), cameras_(cameras), tracker_options_(tracker), options_(options), table_(std::move(table)) {
  std::string why;
  if (!options_.Check(&why)) ThrowInputError("--people all", why);
  if (!tracker_options_.Check(&why)) ThrowInputError("tracker options", why);
  if (!table_) table_ = std::make_shared<const PoseTable>(model_, tracker_options_.table);
}

MultiTracker::~MultiTracker() = default;

const BodyModel& MultiTracker::body(int id) const {
  for (const auto* list : {&people_, &ended_})
    for (const auto& p : *list)
      if (p->id == id) return p->tracker->body();
  ThrowInputError("person " + std::to_string(id), "no such person");
}

std::vector<cv::Mat> MultiTracker::Drawn(int skip, int grow) const {
  std::vector<cv::Mat> masks(cameras_.size());
  for (size_t c = 0; c < cameras_.size(); ++c) masks[c] = cv::Mat::zeros(cameras_[c].height, cameras_[c].width, CV_8UC1);
  for (const auto& p : people_) {
    if (p->id == skip || p->drawn.empty() || p->last.status == TrackStatus::kLost) continue;
    for (size_t c = 0; c < cameras_.size(); ++c)
      if (!p->drawn[c].empty()) cv::bitwise_or(masks[c], p->drawn[c], masks[c]);
  }
  if (grow > 0) {
    const cv::Mat square = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * grow + 1, 2 * grow + 1));
    for (cv::Mat& m : masks) cv::dilate(m, m, square);
  }
  return masks;
}

bool MultiTracker::Contradicted(const PersonSighting& s, const std::vector<cv::Mat>& masks,
                                const std::vector<cv::Mat>& painted) const {
  for (size_t c = 0; c < cameras_.size() && c < masks.size(); ++c) {
    if (c < s.boxes.size() && !s.boxes[c].empty()) continue;
    Eigen::Vector2d feet, head;
    if (!cameras_[c].Project(Eigen::Vector3d(s.floor_mm.x(), 0, s.floor_mm.y()), &feet) ||
        !cameras_[c].Project(Eigen::Vector3d(s.floor_mm.x(), 1700, s.floor_mm.y()), &head))
      continue;
    const double tall = std::abs(feet.y() - head.y());
    const cv::Rect body(static_cast<int>(std::min(feet.x(), head.x()) - tall / 4),
                        static_cast<int>(std::min(feet.y(), head.y())), static_cast<int>(tall / 2 + std::abs(feet.x() - head.x())) + 1,
                        static_cast<int>(tall) + 1);
    const cv::Rect image(0, 0, masks[c].cols, masks[c].rows);
    if ((body & image) != body || body.area() < 20) continue;  // not wholly in this view
    int visible = body.area();  // not behind a painted object
    if (c < painted.size() && painted[c].size() == masks[c].size()) visible -= cv::countNonZero(painted[c](body));
    if (2 * visible < body.area()) continue;  // mostly behind one: no say
    if (20 * cv::countNonZero(masks[c](body)) < visible) return true;  // empty where a person would show
  }
  return false;
}

bool MultiTracker::Behind(const Person& p, const std::vector<cv::Mat>& painted) const {
  if (p.drawn.empty()) return false;
  std::vector<cv::Mat> covers = Drawn(p.id, 0);
  for (size_t c = 0; c < cameras_.size() && c < p.drawn.size(); ++c) {
    if (c < painted.size()) covers[c] = EitherHidden(covers[c], painted[c]);
    if (HalfUnder(p.drawn[c], covers[c])) return true;
  }
  return false;
}

double MultiTracker::ConfirmIou(const Person& p, const std::vector<cv::Mat>& painted) const {
  double sum = 0;
  int counted = 0;
  for (size_t c = 0; c < p.last.cameras.size(); ++c) {
    const CameraScore& score = p.last.cameras[c];
    if (score.observed_px == 0 && score.model_px == 0) continue;  // no evidence (MeanIou)
    if (c < p.drawn.size() && c < painted.size() && HalfUnder(p.drawn[c], painted[c])) continue;
    sum += score.Iou();
    ++counted;
  }
  return counted > 0 ? sum / counted : p.last.MeanIou();
}

bool MultiTracker::PersonShaped(const PersonSighting& s) const {
  if (s.height_mm <= 0) return false;  // feet or head unseen
  for (size_t c = 0; c < s.boxes.size() && c < s.areas.size(); ++c) {
    const double tall = s.boxes[c].height;
    if (tall > 0 && s.areas[c] >= options_.shaped_area * tall * tall) return true;
  }
  return false;
}

bool MultiTracker::Clear(const Eigen::Vector2d& floor_mm) const {
  for (const auto& p : people_) {
    if (!p->has_estimate || p->last.status == TrackStatus::kLost || p->last.joints_mm.cols() == 0) continue;
    const Eigen::Vector2d at(p->last.joints_mm(0, 0), p->last.joints_mm(2, 0));
    if ((at - floor_mm).norm() < options_.birth_clear_mm) return false;
  }
  return true;
}

void MultiTracker::Look(const Frame& unexplained, bool final_batch) {
  int min_px = 60;
  for (const Camera& c : cameras_)
    min_px = std::max(min_px, static_cast<int>(std::lround(options_.min_birth_share * c.width * c.height)));
  std::vector<PersonSighting> sightings;
  std::vector<bool> shaped;  // PersonShaped, per sighting
  const std::optional<Eigen::Vector3d> light = shadow_light_ ? shadow_light_->light() : std::nullopt;
  for (const PersonSighting& s : LocatePeople(cameras_, unexplained.masks, min_px, true, HiddenPixels(unexplained),
                                              unexplained.painted, light)) {
    const bool whole_person = PersonShaped(s);
    if (s.found && s.whole && (whole_person || Clear(s.floor_mm)) &&
        !Contradicted(s, unexplained.masks, unexplained.painted)) {
      sightings.push_back(s);
      shaped.push_back(whole_person);
    }
  }
  // Each sighting continues the candidate it can be (within a walker's reach of where that
  // was last seen), at least total distance; the others are new candidates.
  const int n = static_cast<int>(sightings.size()), m = static_cast<int>(candidates_.size());
  Eigen::MatrixXd cost(n, m);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      const Candidate& c = candidates_[j];
      const double reach = options_.birth_speed_mm_s * (unexplained.time_s - c.last_time_s) + options_.birth_margin_mm;
      // Out of reach costs more than any pairing in reach, so it never displaces one.
      cost(i, j) = std::min((sightings[i].floor_mm - c.floor_mm).norm() / reach, 1.0 + n + m);
    }
  }
  const std::vector<int> pair = MinCostAssignment(cost, 1.0);
  for (int i = 0; i < n; ++i) {
    if (pair[i] >= 0) {
      Candidate& c = candidates_[pair[i]];
      c.floor_mm = sightings[i].floor_mm;
      c.last_time_s = unexplained.time_s;
      c.seen.push_back(unexplained.index);
      c.places.push_back(sightings[i].floor_mm);
      c.boxes.push_back(sightings[i].boxes);
      c.shaped = shaped[i];
    } else {
      candidates_.push_back({sightings[i].floor_mm, unexplained.time_s, unexplained.index, {unexplained.index},
                             {sightings[i].floor_mm}, {sightings[i].boxes}, shaped[i]});
    }
  }
  // Forget sightings older than the window; a candidate seen nowhere in it is gone.
  const int oldest = unexplained.index - options_.birth_window + 1;
  if (!final_batch) {
    for (Candidate& c : candidates_) {
      while (!c.seen.empty() && c.seen.front() < oldest) {
        c.seen.erase(c.seen.begin());
        c.places.erase(c.places.begin());
        c.boxes.erase(c.boxes.begin());
      }
    }
  }
  candidates_.erase(std::remove_if(candidates_.begin(), candidates_.end(),
                                   [](const Candidate& c) { return c.seen.empty(); }),
                    candidates_.end());
  if (final_batch) return;  // Start bears them once it has seen every frame
  BearQualified(options_.birth_frames, std::vector<Frame>(recent_.begin(), recent_.end()), false,
                unexplained.index + 1);
}

bool MultiTracker::Same(const Candidate& a, const Candidate& b) const {
  const auto inside = [&](const Eigen::Vector2d& place, const std::vector<cv::Rect>& boxes) {
    for (size_t c = 0; c < boxes.size() && c < cameras_.size(); ++c) {
      Eigen::Vector2d pixel;
      if (boxes[c].empty() || !cameras_[c].Project(Eigen::Vector3d(place.x(), 900, place.y()), &pixel)) continue;
      // The blob grown by its width each side: a shadow or a cut-off foot moves a camera's
      // place along the floor, and with it the other camera's view of it sideways.
      const cv::Rect& b = boxes[c];
      const cv::Rect around(b.x - b.width, b.y - b.height / 4, 3 * b.width, b.height + b.height / 2);
      if (around.contains(cv::Point(static_cast<int>(pixel.x()), static_cast<int>(pixel.y())))) return true;
    }
    return false;
  };
  // Seen by different cameras only (each camera's blob went to one of them).
  const auto apart = [](const std::vector<cv::Rect>& x, const std::vector<cv::Rect>& y) {
    for (size_t c = 0; c < x.size() && c < y.size(); ++c)
      if (!x[c].empty() && !y[c].empty()) return false;
    return true;
  };
  for (size_t i = 0; i < a.seen.size(); ++i) {
    for (size_t j = 0; j < b.seen.size(); ++j) {
      if (a.seen[i] != b.seen[j]) continue;
      // Each camera's blob (or a merged blob's part, split at its heads) is one sighting's:
      // blobs of one camera in one frame are two people, however near.
      if (!apart(a.boxes[i], b.boxes[j])) continue;
      if ((a.places[i] - b.places[j]).norm() < options_.birth_clear_mm) return true;
      if (inside(a.places[i], b.boxes[j]) || inside(b.places[j], a.boxes[i])) return true;
    }
  }
  return false;
}

void MultiTracker::BearQualified(int needed, const std::vector<Frame>& frames, bool from_first_seen, int next_frame) {
  std::stable_sort(candidates_.begin(), candidates_.end(),
                   [](const Candidate& a, const Candidate& b) { return a.seen.size() > b.seen.size(); });
  std::vector<Candidate> left, chosen;
  for (Candidate& c : candidates_) {
    const bool ready = static_cast<int>(c.seen.size()) >= std::max(1, needed) && (c.shaped || Clear(c.floor_mm));
    if (!ready) {
      left.push_back(std::move(c));
      continue;
    }
    // One of a person's candidates is born; the others are forgotten with it.
    if (std::any_of(chosen.begin(), chosen.end(), [&](const Candidate& b) { return Same(c, b); })) continue;
    if (static_cast<int>(people_.size()) >= options_.max_people) continue;
    std::vector<Frame> from;
    for (const Frame& f : frames)
      if (f.index >= c.seen.front()) from.push_back(f);
    Bear(c, from, from_first_seen ? c.seen.front() : next_frame, !from_first_seen);
    chosen.push_back(std::move(c));
  }
  candidates_ = std::move(left);
}

bool MultiTracker::Bear(const Candidate& c, const std::vector<Frame>& frames, int first_frame, bool past) {
  auto p = std::make_unique<Person>();
  p->id = next_id_;
  TrackerOptions options = tracker_options_;
  options.annealing.seed = tracker_options_.annealing.seed + 1000003ull * static_cast<uint64_t>(p->id - 1);
  options.restart_within_mm = options_.restart_within_mm;
  options.split_merged_starts = true;  // as the birth saw them
  options.hidden_is_painted = false;   // the others' drawings are hidden too
  options.walk_on_as_seen = TrackerOptions::WalkOn::kBehindPainting;  // (TrackerOptions)
  // Among others, a camera whose reading of the place differs is most likely seeing
  // someone else, and a body turned to any heading fits a neighbour: neither is tried
  // (the 3-walker crossing from its videos, 4 seeds: MOTA 0.976 -> 0.952 with turns of
  // every 20th particle).
  options.starts_try_each_camera = false;
  options.turn_every = 0;
  // A frame explained badly is fitted to what shows, not left as predicted: among others
  // it is mostly someone partly behind another (Tracker::Behind handles the rest). Left
  // unfitted, 4 seeds, MOTA from the masks / from the video: the 3-walker crossing 0.977 /
  // 0.976 -> 0.954 / 0.975 (half a switch), the plaza 0.869 / 0.882 -> 0.824 / 0.911.
  options.predict_bad_frames = false;
  // The start's own choice: the person nearest where the candidate was first seen (the
  // start's first frame).
  options.person = PersonPreference::Near(c.places.front(), options_.birth_clear_mm);
  p->tracker = std::make_unique<Tracker>(model_, cameras_, options, table_);
  if (shadow_light_) p->tracker->AdoptShadowLight(*shadow_light_);
  if (!p->tracker->StartFromFrames(frames, past)) return false;
  p->first_frame = first_frame;
  p->going_back = tracker_options_.start_backwards_s > 0;
  // Born from the frames the person was seen in: the second pass goes on back into them
  // (StartBackOver's lead-in), within start_backwards_s of the birth.
  if (p->going_back)
    for (const Frame& f : frames)
      if (f.index < first_frame && frames.back().time_s - f.time_s < tracker_options_.start_backwards_s)
        p->lead_frames.push_back(f);
  ++next_id_;
  people_.push_back(std::move(p));
  return true;
}

void MultiTracker::GoBackOver(Person* p, const Frame& mine) const {
  if (!p->going_back) return;
  const auto done = [p] {
    p->going_back = false;
    p->lead_frames.clear();
    p->held_frames.clear();
    p->held_estimates.clear();
  };
  if (p->last.status == TrackStatus::kLost) return done();  // the frames stand as tracked
  p->held_frames.push_back(mine);
  p->held_estimates.push_back(p->last);
  if (mine.time_s - p->held_frames.front().time_s < tracker_options_.start_backwards_s) return;
  // The lead-in first, with no estimates of the first pass (the person was not born yet).
  std::vector<Frame> frames = p->lead_frames;
  frames.insert(frames.end(), p->held_frames.begin(), p->held_frames.end());
  std::vector<TrackedFrame> first(p->lead_frames.size());
  for (size_t i = 0; i < first.size(); ++i) first[i].index = p->lead_frames[i].index;
  first.insert(first.end(), p->held_estimates.begin(), p->held_estimates.end());
  StartBackOver::SecondPass back = StartBackOver::GoBack(*p->tracker, frames, first, p->lead_frames.size());
  if (back.kept)
    for (TrackedFrame& e : back.estimates) p->revised.emplace_back(e.index, std::move(e));
  done();
}

void MultiTracker::Start(const std::vector<Frame>& frames) {
  std::vector<Frame> kept;
  for (const Frame& source : frames) {
    if (source.dropped) continue;
    const Frame f = PaintingApart(source);
    kept.push_back(f);
    recent_.push_back(f);
    Look(f, true);
    looked_until_ = f.index;
  }
  while (static_cast<int>(recent_.size()) > tracker_options_.start_frames) recent_.pop_front();
  // Everyone seen in birth_frames of the frames, or in most of them when they are fewer.
  BearQualified(std::min<int>(options_.birth_frames, (static_cast<int>(kept.size()) + 1) / 2), kept, true, 0);
  candidates_.clear();
}

PeopleFrame MultiTracker::Step(const Frame& frame) {
  const auto started = std::chrono::steady_clock::now();
  PeopleFrame out;
  out.index = frame.index;
  out.time_s = frame.time_s;
  // Nearest the first camera first; those without an estimate yet last, by id.
  std::vector<Person*> order;
  for (const auto& p : people_)
    if (p->first_frame <= frame.index) order.push_back(p.get());
  const Eigen::Vector3d eye = cameras_.empty() ? Eigen::Vector3d::Zero() : cameras_[0].CentreInWorld();
  const auto depth = [&](const Person* p) {
    return p->has_estimate && p->last.joints_mm.cols() > 0 ? (p->last.joints_mm.col(0) - eye).norm()
                                                           : std::numeric_limits<double>::infinity();
  };
  std::stable_sort(order.begin(), order.end(), [&](const Person* a, const Person* b) { return depth(a) < depth(b); });
  const std::vector<cv::Mat>& painted = frame.hidden;  // the source's hidden pixels (PaintingApart)
  for (Person* p : order) {
    Frame mine = PaintingApart(frame);
    if (!frame.dropped) {
      // Drawn, the others hide whatever is under them; the mask keeps what is under the
      // painting, the evidence of someone in front of a painted object.
      mine.hidden = Drawn(p->id, options_.hidden_grow_px);
      for (size_t c = 0; c < mine.masks.size() && c < mine.hidden.size(); ++c) {
        if (mine.hidden[c].empty() || mine.hidden[c].size() != frame.masks[c].size()) continue;
        mine.masks[c] = frame.masks[c].clone();
        mine.masks[c].setTo(0, mine.hidden[c]);
      }
    }
    p->last = p->tracker->Step(mine);
    p->has_estimate = p->last.state.size() > 0;
    ++p->stepped;
    p->drawn.assign(cameras_.size(), cv::Mat());
    p->tracker->DrawEstimate(p->last, &p->drawn);
    p->giant = p->has_estimate && p->tracker->StatureMm(p->last) > options_.max_stature_mm;
    if (p->last.status == TrackStatus::kTracked && ConfirmIou(*p, painted) >= options_.confirm_iou && !p->giant)
      ++p->good;
    p->confirmed = p->confirmed || p->good >= options_.confirm_frames;
    GoBackOver(p, mine);
    if (!shadow_light_ && p->tracker->shadow_light().light()) {
      shadow_light_ = p->tracker->shadow_light();
      shadow_light_frame_ = frame.index;
      for (const auto& q : people_) q->tracker->AdoptShadowLight(*shadow_light_);
    }
  }
  // Deaths: lost too long, unseen too long while nobody hides them, or one person followed
  // twice. Runs add up frame intervals (the first frame counts as one at 30 frames/s), and
  // end within half a frame of their time.
  const double dt = stepped_ ? std::max(0.0, frame.time_s - last_time_s_) : 1.0 / 30;
  const double tolerance = 0.5 * dt;
  stepped_ = true;
  last_time_s_ = frame.time_s;
  std::vector<int> ending;
  for (Person* p : order) {
    p->lost_s = p->last.status == TrackStatus::kLost ? p->lost_s + dt : 0;
    p->unseen_s = p->last.status == TrackStatus::kTracked || frame.dropped || Behind(*p, painted) ? 0 : p->unseen_s + dt;
    p->giant_s = p->giant ? p->giant_s + dt : 0;
    if (p->lost_s >= options_.death_s - tolerance || p->unseen_s >= options_.death_s - tolerance ||
        p->giant_s >= options_.death_s - tolerance ||
        (!p->confirmed && p->stepped >= options_.birth_window))
      ending.push_back(p->id);
  }
  for (size_t a = 0; a < order.size(); ++a) {
    for (size_t b = 0; b < order.size(); ++b) {
      Person* p = order[a];
      Person* q = order[b];
      if (p->id >= q->id || !p->has_estimate || !q->has_estimate || p->last.status == TrackStatus::kLost ||
          q->last.status == TrackStatus::kLost)
        continue;
      const double apart = std::hypot(p->last.joints_mm(0, 0) - q->last.joints_mm(0, 0),
                                      p->last.joints_mm(2, 0) - q->last.joints_mm(2, 0));
      const double turn = std::remainder(p->last.heading_rad - q->last.heading_rad, 2 * std::numbers::pi);
      const bool same_way = std::abs(turn) < options_.duplicate_heading_deg * std::numbers::pi / 180;
      auto& [run, same_way_run] = together_[{p->id, q->id}];
      run = apart < options_.duplicate_mm ? run + dt : 0;
      same_way_run = apart < options_.duplicate_mm && same_way ? same_way_run + dt : 0;
      if (run >= options_.duplicate_s - tolerance || same_way_run >= options_.duplicate_same_way_s - tolerance)
        ending.push_back(q->id);
    }
  }
  for (auto it = people_.begin(); it != people_.end();) {
    if (std::find(ending.begin(), ending.end(), (*it)->id) != ending.end()) {
      if ((*it)->confirmed) out.ended.push_back((*it)->id);
      for (auto t = together_.begin(); t != together_.end();)
        t = t->first.first == (*it)->id || t->first.second == (*it)->id ? together_.erase(t) : std::next(t);
      ended_.push_back(std::move(*it));
      it = people_.erase(it);
    } else {
      ++it;
    }
  }
  for (const auto& p : people_) {
    if (p->first_frame > frame.index) continue;
    if (!p->confirmed) {
      for (auto& [index, estimate] : p->revised) {
        const int at = index;  // (clang 14 cannot capture a structured binding)
        const auto held = std::find_if(p->unreported.begin(), p->unreported.end(), [&](const auto& u) { return u.first >= at; });
        if (held != p->unreported.end() && held->first == at) {
          held->second = std::move(estimate);
        } else {  // the lead-in, before the birth
          p->unreported.emplace(held, at, std::move(estimate));
        }
      }
      p->revised.clear();
      p->unreported.emplace_back(frame.index, p->last);
      continue;
    }
    out.people.push_back({p->id, p->last});
    if (!p->reported) {
      out.born.push_back(p->id);
      for (auto& [index, estimate] : p->unreported) out.earlier.push_back({index, {p->id, std::move(estimate)}});
      p->unreported.clear();
    }
    for (auto& [index, estimate] : p->revised) out.earlier.push_back({index, {p->id, std::move(estimate)}});
    p->revised.clear();
    p->reported = true;
  }
  // Births, from what nobody explains (frames Start looked at are not looked at again).
  if (!frame.dropped && frame.index > looked_until_) {
    const int grow = cameras_.empty() ? 1 : std::max(1, static_cast<int>(std::lround(options_.explained_grow * cameras_[0].height)));
    const std::vector<cv::Mat> explained = Drawn(-1, grow);
    Frame unexplained;
    unexplained.index = frame.index;
    unexplained.time_s = frame.time_s;
    for (size_t c = 0; c < frame.masks.size(); ++c) {
      unexplained.masks.push_back(frame.masks[c].clone());
      if (c < explained.size()) unexplained.masks.back().setTo(0, explained[c]);
    }
    unexplained.hidden = explained;  // a new person's feet may be behind someone tracked
    unexplained.painted = frame.hidden;
    recent_.push_back(unexplained);
    while (static_cast<int>(recent_.size()) > tracker_options_.start_frames) recent_.pop_front();
    Look(recent_.back(), false);
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return out;
}

void PlaceEarlier(std::vector<PeopleFrame>* frames) {
  if (frames->empty()) return;
  PeopleFrame& now = frames->back();
  for (const auto& [frame_index, person] : now.earlier) {
    const int index = frame_index;  // (clang 14 cannot capture a structured binding)
    const auto at = std::find_if(frames->rbegin(), frames->rend(), [&](const PeopleFrame& t) { return t.index == index; });
    if (at == frames->rend()) continue;
    // Born at the first frame they are in (a lead-in may reach before the frame given so).
    bool born_later = false;
    for (auto later = at.base(); later != frames->end(); ++later) born_later = std::erase(later->born, person.id) > 0 || born_later;
    if (born_later) at->born.push_back(person.id);
    const auto place = std::lower_bound(at->people.begin(), at->people.end(), person.id,
                                        [](const PersonFrame& p, int id) { return p.id < id; });
    if (place != at->people.end() && place->id == person.id) {
      *place = person;
    } else {
      at->people.insert(place, person);
    }
  }
}

std::vector<PeopleFrame> TrackPeople(FrameSource* source, MultiTracker* tracker,
                                     const std::function<void(const Frame&, PeopleFrame&)>& on_frame,
                                     const std::function<bool()>& stop) {
  std::vector<PeopleFrame> tracked;
  RunSource(
      source, tracker->tracker_options().start_frames, [tracker](const std::vector<Frame>& first) { tracker->Start(first); },
      [&](const Frame& f) {
        tracked.push_back(tracker->Step(f));
        if (on_frame) on_frame(f, tracked.back());
        PlaceEarlier(&tracked);
      },
      stop);
  return tracked;
}

}  // namespace jgpm
