#include "tracker/filter/tracker.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <numbers>
#include <optional>

#include <opencv2/core.hpp>

#include "io/base/enum_name.h"
#include "io/base/error.h"
#include "tracker/filter/person_locator.h"
#include "tracker/state/joint_space_state.h"
#include "tracker/state/latent_state.h"
#include "tracker/state/manifold_state.h"

namespace jgpm {
namespace {


// The head's top above its bone end: the body model's head radius there (mm).
constexpr double kHeadTopMm = 88;
// How far apart two cameras' readings of one person may be (MeetingPlaces): 3 m, each
// moved along its line of sight by up to a quarter of 6 m (FuseReadings' spread; the
// ring's and a webcam's walks are 3-7 m away), one nearer, the other farther.
constexpr double kPairMm = 3000;

cv::Rect Grow(const cv::Rect& box, double margin, int width, int height) {
  if (box.empty()) return box;
  const int dx = static_cast<int>(margin * box.width) + 8, dy = static_cast<int>(margin * box.height) + 8;
  return cv::Rect(box.x - dx, box.y - dy, box.width + 2 * dx, box.height + 2 * dy) & cv::Rect(0, 0, width, height);
}

// The share of the box of `joints`' images that lies inside `camera`'s image (0 when none
// is in front of it).
double ShareInView(const Camera& camera, const Eigen::Matrix3Xd& joints) {
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (int j = 0; j < joints.cols(); ++j) {
    Eigen::Vector2d p;
    if (!camera.Project(joints.col(j), &p)) continue;
    x0 = std::min(x0, p.x()), y0 = std::min(y0, p.y()), x1 = std::max(x1, p.x()), y1 = std::max(y1, p.y());
  }
  if (!(x1 > x0 && y1 > y0)) return 0;
  const double w = std::min<double>(x1, camera.width) - std::max(x0, 0.0);
  const double h = std::min<double>(y1, camera.height) - std::max(y0, 0.0);
  return w > 0 && h > 0 ? w * h / ((x1 - x0) * (y1 - y0)) : 0;
}

cv::Mat CameraOf(const std::vector<cv::Mat>& masks, size_t c) { return c < masks.size() ? masks[c] : cv::Mat(); }

// The top of the head above the floor of a body whose bone ends are `joints` (world, mm)
// at `size`: the head bone's end (or, without one, the highest) and its radius above it.
double HeadTopMm(const Eigen::Matrix3Xd& joints, int head, double size) {
  const double top = head >= 0 && head < joints.cols() ? joints(1, head) : joints.row(1).maxCoeff();
  return top + kHeadTopMm * size;
}

}  // namespace

std::string_view TrackStatusName(TrackStatus status) {
  switch (status) {
    case TrackStatus::kTracked: return "tracked";
    case TrackStatus::kPredicted: return "predicted";
    case TrackStatus::kLost: return "lost";
  }
  return "?";
}

bool TrackerOptions::Check(std::string* why) const {
  const char* problem = nullptr;
  if (threads < 1 || threads > 256) problem = "threads must be in [1, 256]";
  else if (start_frames < 1 || start_frames > 1000) problem = "start_frames must be in [1, 1000]";
  else if (start_seen_frames < 1 || start_seen_frames > start_frames) problem = "start_seen_frames must be in [1, start_frames]";
  else if (start_particle_factor < 1 || start_particle_factor > 100) problem = "start_particle_factor must be in [1, 100]";
  else if (start_layers < 1 || start_layers > 100) problem = "start_layers must be in [1, 100]";
  else if (!(start_backwards_s >= 0)) problem = "start_backwards_s must be >= 0 (0: never)";
  else if (!(back_over_margin >= 0)) problem = "back_over_margin must be >= 0";
  else if (!(lost_iou >= 0 && lost_iou < 1)) problem = "lost_iou must be in [0, 1)";
  else if (lost_frames < 1) problem = "lost_frames must be >= 1";
  else if (!(region_margin >= 0 && region_margin <= 10)) problem = "region_margin must be in [0, 10]";
  else if (!(mirror_margin >= 0)) problem = "mirror_margin must be >= 0";
  else if (mirror_streak < 1) problem = "mirror_streak must be >= 1";
  else if (mirror_every < 0) problem = "mirror_every must be >= 0 (0: never)";
  else if (mirror_frames < 0) problem = "mirror_frames must be >= 0";
  else if (legs_trial_frames < 0) problem = "legs_trial_frames must be >= 0 (0: never)";
  else if (!(legs_trial_margin >= 0)) problem = "legs_trial_margin must be >= 0";
  else if (!shadow.Check(nullptr)) problem = "shadow: every, looks, idle_after and idle_every must be >= 1, min_gain >= 0";
  else if (turn_every < 0) problem = "turn_every must be >= 0 (0: never)";
  else if (reverse_every < 0) problem = "reverse_every must be >= 0 (0: never)";
  else if (relocate_every < 0 || relocate_share < 1 || !(relocate_distance_mm >= 0) || !(relocate_merged >= 1))
    problem = "bad relocation options";
  else if (!(max_hidden_s >= 0)) problem = "max_hidden_s must be >= 0";
  else if (!(restart_within_mm > 0)) problem = "restart_within_mm must be > 0";
  else if (!(min_in_view >= 0 && min_in_view <= 1)) problem = "min_in_view must be in [0, 1]";
  else if (person.kind == PersonPreference::Kind::kNearPixel && !(person.camera >= 0 && person.pixel.allFinite()))
    problem = "person: a camera index >= 0 and a finite pixel";
  if (problem) {
    if (why) *why = problem;  // `why` may be null
    return false;
  }
  return annealing.Check(why) && likelihood.Check(why) && table.Check(why) && alignment.Check(why) &&
         shape.Check(why) && travel.Check(why);
}

double TrackedFrame::MeanIou(double none) const {
  double sum = 0;
  int counted = 0;
  for (const CameraScore& c : cameras) {
    if (c.observed_px == 0 && c.model_px == 0) continue;  // nobody there, nothing drawn: no evidence
    sum += c.Iou();
    ++counted;
  }
  return counted > 0 ? sum / counted : none;
}

Tracker::Tracker(const GaitModel& model, const std::vector<Camera>& cameras, const TrackerOptions& options,
                 std::shared_ptr<const PoseTable> table)
    : model_(model),
      cameras_(cameras),
      options_(options),
      pool_(options.threads),
      body_(model.skeleton(), {.detail = options.body_detail}, "the model's skeleton"),
      likelihood_(cameras, options.likelihood),
      placer_(model.skeleton()),
      alignment_(cameras, options.alignment),
      shape_([&options] {
        BodyShapeOptions shape = options.shape;
        shape.lengths = shape.lengths && !options.known_size;  // the subject's own bones
        return shape;
      }()),
      travel_(options.travel),
      shadow_light_(options.shadow) {
  std::string why;
  if (!options.Check(&why)) ThrowInputError("tracking options", why);
  if (cameras.empty()) ThrowInputError("cameras", "the tracker needs at least one camera");
  if (options.person.camera >= static_cast<int>(cameras.size()))
    ThrowInputError("person", "camera " + std::to_string(options.person.camera) + " of " +
                                  std::to_string(cameras.size()));
  next_choice_ = options.person;
  painted_objects_.resize(cameras.size());
  if (options.space == StateSpace::kJointSpace) {
    state_model_ = std::make_unique<JointSpaceStateModel>(model, options.known_size);
  } else {
    PoseTableOptions table_options = options.table;
    table_options.threads = options.threads;
    table_ = table ? std::move(table) : std::make_shared<const PoseTable>(model, table_options);
    if (table_->manifold() != model.HasManifold() || table_->NumBones() != static_cast<int>(model.skeleton().bones.size()) ||
        table_->NumChannels() != model.NumChannels())
      ThrowInputError("pose table", "made for another model");
    if (model.HasManifold()) {
      ManifoldDynamics dynamics;
      if (options.known_size) dynamics.size_noise = dynamics.size_diffusion = 0, dynamics.min_size = dynamics.max_size = 1;
      if (!options.pace) dynamics.min_cadence = dynamics.walking_min_cadence;
      state_model_ = std::make_unique<ManifoldStateModel>(model, *table_, dynamics);
    } else {
      LatentDynamics dynamics;
      if (options.known_size) dynamics.size_noise = dynamics.size_diffusion = 0, dynamics.min_size = dynamics.max_size = 1;
      state_model_ = std::make_unique<LatentStateModel>(model, *table_, dynamics);
    }
  }
  legs_by_phase_ = model.HasManifold() && options.space == StateSpace::kModel;
  filter_ = std::make_unique<AnnealedFilter>(*state_model_, likelihood_, body_, options.annealing, &pool_);
  if (options.refinement.enabled && options.space == StateSpace::kModel) {
    RefinementOptions refinement = options.refinement;
    refinement.refine_size = refinement.refine_size && !options.known_size;
    refinement.seed = options.annealing.seed;  // one seed for the run
    refiner_ = std::make_unique<PoseRefiner>(model, likelihood_, body_, refinement, &pool_);
  }
  // The model's height at size 1, over poses spread by the prior.
  head_ = model.skeleton().FindBone("head");
  Eigen::VectorXd state(state_model_->Dimension());
  Eigen::Matrix3Xd joints;
  InitialGuess origin;
  origin.floor_std_mm = 0;
  origin.size_std = 0;
  double sum = 0;
  for (int i = 0; i < 64; ++i) {
    Random random(12345, i);
    state_model_->Sample(origin, &random, state.data());
    state_model_->Evaluate(state.data(), &joints);
    sum += HeadTopMm(joints, head_, 1);
  }
  model_height_mm_ = sum / 64;
}

Tracker::~Tracker() = default;

void Tracker::LookFor(const Frame& frame) {
  unstarted_.push_back(Locate(frame));
  if (unstarted_.size() > static_cast<size_t>(std::max(1, options_.start_frames))) unstarted_.erase(unstarted_.begin());
  // From nobody, not before there are enough frames to follow someone through.
  const bool wait = next_choice_.kind == PersonPreference::Kind::kStrongest &&
                    unstarted_.size() < static_cast<size_t>(options_.start_seen_frames);
  if (!frame.dropped && !wait) StartFrom(std::vector<Sightings>(unstarted_), /*at_last=*/true);  // a copy: a start clears them
}

Tracker::Sightings Tracker::Locate(const Frame& frame) const {
  Sightings seen;
  seen.index = frame.index;
  seen.time_s = frame.time_s;
  seen.may_hide = !frame.hidden.empty() || !frame.painted.empty();
  if (!frame.dropped)
    seen.people = LocatePeople(cameras_, frame.masks, 60, options_.split_merged_starts, HiddenPixels(frame), Painted(frame),
                               shadow_light_.light());
  return seen;
}

std::vector<Tracker::Sightings> Tracker::LocateAll(const std::vector<Frame>& frames) const {
  std::vector<Sightings> seen;
  for (const Frame& f : frames) seen.push_back(Locate(f));
  return seen;
}

bool Tracker::Guess(const std::vector<Frame>& frames, InitialGuess* guess, const PersonPreference& prefer,
                    std::vector<cv::Rect>* boxes, bool at_last) const {
  return Guess(LocateAll(frames), guess, prefer, boxes, at_last);
}

bool Tracker::ComingIn(const std::vector<PersonSighting>& chain, size_t first, Eigen::Vector2d* direction) const {
  size_t before = first;
  while (before > 0 && !chain[before - 1].found) --before;
  if (before == 0) return false;
  const PersonSighting& slice = chain[before - 1];
  const PersonSighting& whole = chain[first];
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  int cameras = 0;
  for (size_t c = 0; c < cameras_.size() && c < slice.boxes.size() && c < whole.boxes.size(); ++c) {
    const cv::Rect& cut = slice.boxes[c];
    const cv::Rect& clear = whole.boxes[c];
    if (cut.area() == 0 || clear.area() == 0) continue;
    const auto at_left = [](const cv::Rect& box) { return box.x <= 0; };
    const auto at_right = [&](const cv::Rect& box) { return box.x + box.width >= cameras_[c].width; };
    const bool from_left = at_left(cut) && !at_left(clear);
    const bool from_right = at_right(cut) && !at_right(clear);
    if (from_left == from_right) continue;
    // Across the view: the image's horizontal on the floor (the camera's right axis).
    const Eigen::Vector3d right = cameras_[c].cam_from_world_rotation.row(0).transpose();
    const Eigen::Vector2d across = Eigen::Vector2d(right.x(), right.z()).normalized();
    if (!across.allFinite()) continue;  // looking straight down
    sum += from_left ? across : Eigen::Vector2d(-across);
    ++cameras;
  }
  // Cameras that disagree (one saw them come in from the left, another going the opposite
  // way) say nothing.
  if (cameras == 0 || !(sum.norm() > 0.5 * cameras)) return false;
  *direction = sum.normalized();
  return true;
}

bool Tracker::Guess(const std::vector<Sightings>& seen, InitialGuess* guess, const PersonPreference& prefer,
                    std::vector<cv::Rect>* boxes, bool at_last) const {
  if (seen.empty()) return false;
  std::vector<double> times;
  for (const Sightings& s : seen) times.push_back(s.time_s - seen.front().time_s);
  // The person followed from a first sighting: in each frame the one nearest where they
  // were last found, within the locator's agreement (1 m) and a brisk walk (2 m/s) since;
  // after it, and before it (where they were coming into view: slices cut by a side edge).
  const auto follow = [&](size_t first, const PersonSighting& from) {
    std::vector<PersonSighting> chain(seen.size());
    chain[first] = from;
    for (size_t i = first + 1, last = first; i < seen.size(); ++i) {
      chain[i] = ChoosePerson(seen[i].people, PersonPreference::Near(chain[last].floor_mm,
                                                                1000 + 2000 * (times[i] - times[last])));
      if (chain[i].found) last = i;
    }
    for (size_t i = first, next = first; i-- > 0;) {
      chain[i] = ChoosePerson(seen[i].people, PersonPreference::Near(chain[next].floor_mm,
                                                                1000 + 2000 * (times[next] - times[i])));
      if (chain[i].found) next = i;
    }
    return chain;
  };
  // A start is made on someone wholly in some view: a slice cut by an image's side edge
  // (someone entering) can be anything from an arm to a back; the frames after may follow
  // it. The first frame with such a person (the one `prefer` asks for: a restart's, seen
  // within reach, may be out of it in the frames before).
  const auto whole = [](const PersonSighting& s) { return s.whole; };
  size_t first = 0;
  std::vector<PersonSighting> sightings;
  for (; first < seen.size(); ++first) {
    std::vector<PersonSighting> wholes;
    std::copy_if(seen[first].people.begin(), seen[first].people.end(), std::back_inserter(wholes), whole);
    if (wholes.empty()) continue;
    if (prefer.kind == PersonPreference::Kind::kStrongest) {
      // Someone seen in too few frames is a flicker (TrackerOptions::start_seen_frames):
      // the next frame with someone wholly in view may hold a person.
      int most = -1;
      for (const PersonSighting& candidate : wholes) {
        std::vector<PersonSighting> chain = follow(first, candidate);
        const int found = static_cast<int>(std::count_if(chain.begin(), chain.end(), [](const PersonSighting& s) { return s.found; }));
        if (found > most) most = found, sightings = std::move(chain);
      }
      if (most >= std::min<int>(options_.start_seen_frames, static_cast<int>(seen.size()))) break;
      continue;
    }
    const PersonSighting chosen = ChoosePerson(wholes, prefer);
    if (chosen.found) {
      sightings = follow(first, chosen);
      break;
    }
  }
  if (first == seen.size()) return false;
  if (boxes) {
    size_t last = first;
    for (size_t i = first; at_last && i < sightings.size(); ++i)
      if (sightings[i].found) last = i;
    *boxes = sightings[last].boxes;
  }
  // Where the person was at the first frame: a straight walk fitted through the places
  // found (least squares in time), so a first frame where nobody was found still starts
  // in the right place.
  // Places read from feet when some frames have them (a walker's feet are cut off only
  // near a camera); the adult-height guesses, less sure, otherwise. The slices before the
  // first whole sighting are not used: a slice's place is pinned to the image's edge (its
  // axis is there) while the walker comes in, so through them the walk went backwards
  // (tracker_test's walker coming in from the side: the slices 70 mm ahead of the whole
  // one, 250 mm of travel).
  const bool feet = std::any_of(sightings.begin() + static_cast<std::ptrdiff_t>(first), sightings.end(),
                                [](const PersonSighting& s) { return s.found && s.feet_seen; });
  const auto used = [feet](const PersonSighting& s) { return s.found && s.feet_seen == feet; };
  std::vector<double> heights;
  double n = 0, st = 0, stt = 0;
  Eigen::Vector2d sp = Eigen::Vector2d::Zero(), stp = Eigen::Vector2d::Zero();
  for (size_t i = first; i < sightings.size(); ++i) {
    const PersonSighting& s = sightings[i];
    if (!used(s)) continue;
    if (s.height_mm > 0) heights.push_back(s.height_mm);
    n += 1, st += times[i], stt += times[i] * times[i];
    sp += s.floor_mm, stp += times[i] * s.floor_mm;
  }
  if (n == 0) return false;
  const double det = n * stt - st * st;
  const Eigen::Vector2d start = det > 1e-9 ? Eigen::Vector2d((stt * sp - st * stp) / det) : Eigen::Vector2d(sp / n);
  const Eigen::Vector2d velocity = det > 1e-9 ? Eigen::Vector2d((n * stp - st * sp) / det) : Eigen::Vector2d::Zero();
  guess->floor_mm = at_last ? Eigen::Vector2d(start + velocity * times.back()) : start;
  guess->floor_std_mm = feet ? 120 : 400;
  // Each camera's own reading at the frame started from, where it differs from the place
  // the cameras agreed on there by more than the locator's own error (relocate_distance_mm,
  // 300 mm), is another place for the start to try. On the surveillance quad with a coat, a
  // shadow and passing clutter, two of three cameras' readings were a metre off (one with
  // the shadow in its blob, one with a ball merged with it), and the median with them: the
  // first ten frames were 300-800 mm off. (Past the start's spread, 120 mm, instead, with
  // the readings averaged over the start's frames: the realism suite's surveillance quad
  // lost 31.9 -> 44.5 mm, 4 seeds, its particles spread over places the locator's jitter
  // made.)
  if (options_.starts_try_each_camera) {
    const auto from = at_last ? std::find_if(sightings.rbegin(), sightings.rend(), used).base() - 1
                              : std::find_if(sightings.begin(), sightings.end(), used);
    const PersonSighting& at = *from;
    for (const Eigen::Vector2d& own : at.camera_floor_mm) {
      const Eigen::Vector2d offset = own - at.floor_mm;
      if (own.allFinite() && offset.norm() > options_.relocate_distance_mm)
        guess->other_floors_mm.push_back(guess->floor_mm + offset);
    }
    // And where another camera's blob's line of sight meets theirs (MeetingPlaces).
    for (const Eigen::Vector2d& place : MeetingPlaces(at, seen[from - sightings.begin()].people))
      guess->other_floors_mm.push_back(guess->floor_mm + place - at.floor_mm);
  }
  if (options_.known_size) {
    guess->size = 1, guess->size_std = 0;
  } else if (heights.empty()) {
    guess->size_seen = false;
  } else {
    std::sort(heights.begin(), heights.end());
    guess->size = SizeOf(heights[heights.size() / 2]);
    guess->size_std = 0.04;
  }
  // A walker faces where they go: the fitted walk gives the heading and the speed, when
  // it went far enough in the frames looked at to be told from noise.
  const double travelled = velocity.norm() * times.back();
  if (travelled > 60) {
    guess->heading_rad = std::atan2(velocity.x(), velocity.y());
    guess->heading_std_rad = 25 * std::numbers::pi / 180;
    guess->speed_mm_s = velocity.norm();
  } else if (Eigen::Vector2d in; first > 0 && ComingIn(sightings, first, &in)) {
    // Coming in from a side edge, seen whole too briefly to see them go: away from it,
    // across the view, give or take 45 degrees (a walker crossing it obliquely). The
    // image's horizontal rather than across the line of sight was chosen on the tuning
    // clips (README, "People entering, leaving, cut off"; 35_29 49.1 against 49.8 mm).
    guess->heading_rad = std::atan2(in.x(), in.y());
    guess->heading_std_rad = 45 * std::numbers::pi / 180;
  } else {
    guess->heading_std_rad = std::numbers::pi;  // standing or unseen: any heading
  }
  return true;
}

void Tracker::StartAt(const InitialGuess& guess, int frame) {
  if (refiner_) refiner_->Reset();
  // A start may be someone else: the model's build again.
  shape_.Reset();
  ApplyBuild();
  filter_->Initialise(guess, options_.annealing.particles * options_.start_particle_factor, frame);
  started_ = true;
  fresh_ = true;
  unconfirmed_ = false;
  unstarted_.clear();
  // A start that knows the pose (--init truth) knows which leg is forward.
  frames_since_start_ = guess.coordinates.size() > 0 ? options_.mirror_frames : 0;
  legs_trial_due_ = true;
  other_legs_.reset();
  bad_frames_ = 0;
  out_of_view_ = 0;
  last_drawn_.clear();
  hidden_ = behind_ = false;
  held_size_ = 0;
  start_boxes_.clear();
  last_good_time_s_ = -1e9;  // nothing to hold to until a good frame
  travel_.Clear();
}

bool Tracker::StartFromFrames(const std::vector<Frame>& frames, bool at_last) {
  return StartFrom(LocateAll(frames), at_last);
}

bool Tracker::StartFrom(const std::vector<Sightings>& seen, bool at_last) {
  if (seen.empty()) return false;
  InitialGuess guess;
  std::vector<cv::Rect> boxes;
  // A restart looks for the person within a brisk walk (2 m/s) of where they were last
  // explained well, and the locator's 1 m: a ball passing 4 m away is not them (tuning clip
  // 35_28: a walker lost behind a pillar was restarted on one, 4.2 m off, size 0.76).
  PersonPreference prefer = next_choice_;
  if (prefer.kind == PersonPreference::Kind::kNearPlace && last_good_time_s_ > -1e8)
    prefer.within_mm = std::min(prefer.within_mm, 1000 + 2000 * (seen.back().time_s - last_good_time_s_));
  if (!Guess(seen, &guess, prefer, &boxes, at_last)) return false;
  StartAt(guess, at_last ? seen.back().index : seen.front().index);
  unconfirmed_ = prefer.kind == PersonPreference::Kind::kStrongest;
  start_boxes_ = boxes;  // where to look at the start: the person's blobs then
  // Where something may hide the feet (others, painted occluders): a head alone is no size.
  const bool may_hide = seen.back().may_hide;
  held_size_ = !guess.size_seen && may_hide && !options_.known_size ? guess.size : 0;
  return true;
}

std::vector<cv::Rect> Tracker::Regions(const std::vector<Frame>*) const {
  std::vector<cv::Rect> regions(cameras_.size());
  if (fresh_ && !start_boxes_.empty()) {
    for (size_t c = 0; c < cameras_.size(); ++c) {
      // A camera that did not see the person at the start looks everywhere.
      regions[c] = start_boxes_[c].empty()
                       ? cv::Rect(0, 0, cameras_[c].width, cameras_[c].height)
                       : Grow(start_boxes_[c], 2 * options_.region_margin, cameras_[c].width, cameras_[c].height);
    }
    return regions;
  }
  // The union of where a spread of the particles would be seen.
  const StateMatrix& particles = filter_->particles();
  const int n = static_cast<int>(particles.rows());
  const int samples = std::min(n, 24);
  std::vector<double> x0(cameras_.size(), 1e300), y0(cameras_.size(), 1e300), x1(cameras_.size(), -1e300),
      y1(cameras_.size(), -1e300);
  Eigen::Matrix3Xd joints;
  for (int k = 0; k < samples; ++k) {
    state_model_->Evaluate(particles.row(static_cast<Eigen::Index>(k) * n / samples).data(), &joints);
    for (size_t c = 0; c < cameras_.size(); ++c) {
      for (int j = 0; j < joints.cols(); ++j) {
        Eigen::Vector2d p;
        if (!cameras_[c].Project(joints.col(j), &p)) continue;
        x0[c] = std::min(x0[c], p.x());
        y0[c] = std::min(y0[c], p.y());
        x1[c] = std::max(x1[c], p.x());
        y1[c] = std::max(y1[c], p.y());
      }
    }
  }
  for (size_t c = 0; c < cameras_.size(); ++c) {
    if (x1[c] < x0[c]) continue;
    const double limit = 4.0 * (cameras_[c].width + cameras_[c].height);
    const auto clamp = [&](double v) { return static_cast<int>(std::clamp(v, -limit, limit)); };
    const cv::Rect box(cv::Point(clamp(std::floor(x0[c])), clamp(std::floor(y0[c]))),
                       cv::Point(clamp(std::ceil(x1[c])) + 1, clamp(std::ceil(y1[c])) + 1));
    regions[c] = Grow(box, options_.region_margin, cameras_[c].width, cameras_[c].height);
  }
  return regions;
}

TrackedFrame Tracker::Step(const Frame& frame) {
  const auto start = std::chrono::steady_clock::now();
  TrackedFrame out;
  out.index = frame.index;
  out.time_s = frame.time_s;
  auto finish = [&](TrackedFrame* f) {
    f->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    f->shadow_light = shadow_light_.light();
    last_time_s_ = frame.time_s;
  };
  if (!started_) LookFor(frame);
  if (!started_) {
    out.status = TrackStatus::kLost;
    finish(&out);
    return out;
  }
  const double dt = fresh_ ? 0.0 : frame.time_s - last_time_s_;
  if (!fresh_) filter_->Predict(dt, frame.index);
  likelihood_.SetShadow(shadow_light_.light(), shape_.drawn().floor_mm);
  if (legs_by_phase_ && !fresh_ && !frame.dropped && options_.mirror_every > 0 &&
      frames_since_start_ < options_.mirror_frames) {
    filter_->Shift(0, 0.5, options_.mirror_every);
    ++leg_order_epoch_;
  }
  // Each estimate's leg order is judged against the last one's, and a trial's second
  // tracker holds its particles to it.
  const bool ordered = last_order_ && !fresh_;
  if (holds_order_ && ordered) {
    filter_->Transform([this, dt](double* s) {
      if (!OtherLegOrder(s[0], *last_order_, dt)) return;
      s[0] += 0.5;
      state_model_->Normalise(s);
    });
  }
  ++frames_since_start_;
  // Where the dynamics put the person now (walking on at their speed and heading).
  Eigen::Vector2d predicted_floor_mm;
  {
    const Eigen::VectorXd mean = filter_->Mean();
    const PlacementIndex p = state_model_->placement();
    predicted_floor_mm = Eigen::Vector2d(mean[p.x], mean[p.z]);
  }
  // How far from there a sighting may be and still be the person: the locator's own error
  // (half a metre) and 0.5 m/s of speed the prediction may have wrong since the last frame
  // explained well.
  const auto near_prediction = [&](const PersonSighting& s) {
    return s.found &&
           (s.floor_mm - predicted_floor_mm).norm() <= 500 + 500 * (frame.time_s - last_good_time_s_);
  };
  // Where the masks alone put the person: looked for once a frame, when first needed.
  std::optional<PersonSighting> sighting;
  std::vector<PersonSighting> everyone;  // all the sightings it was chosen from
  const auto located = [&]() -> const PersonSighting& {
    if (!sighting)
      sighting = LocatePerson(cameras_, frame.masks, 60, PersonPreference::Near(predicted_floor_mm), HiddenPixels(frame),
                              Painted(frame), &everyone, shadow_light_.light());
    return *sighting;
  };
  if (!fresh_ && !frame.dropped && options_.relocate_every > 0 && frames_since_start_ % options_.relocate_every == 0) {
    const PersonSighting& seen = located();
    const double away = (seen.floor_mm - predicted_floor_mm).norm();
    const double reach = options_.relocate_distance_mm + 2000 * options_.relocate_every * std::max(dt, 1.0 / 60);
    // A blob far wider for its height than the estimate's drawing holds someone else too
    // (two walkers passing): its place is neither's.
    bool merged = false;
    for (size_t c = 0; c < last_drawn_.size() && c < seen.areas.size(); ++c) {
      const CameraScore& drawn = last_drawn_[c];
      const double blob_rows = seen.boxes[c].height;
      merged = merged || (drawn.model_rows > 0 && blob_rows > 0 &&
                          seen.areas[c] / (blob_rows * blob_rows) >
                              options_.relocate_merged * drawn.model_px / (double(drawn.model_rows) * drawn.model_rows));
    }
    // Farther than a walker goes is someone else, unless their blob has the estimate's head
    // at its top: then it is the person, and the estimate is off in depth.
    if (seen.found && seen.feet_seen && !merged && away > options_.relocate_distance_mm &&
        (away <= reach || HeadOnBlob(seen))) {
      // With the person's height read, the relocated bodies take it.
      const double size = seen.height_mm > 0 && !options_.known_size ? SizeOf(seen.height_mm) : 0;
      filter_->Relocate(seen.floor_mm, 120, options_.relocate_share, frame.index, size, options_.relocate_size_std);
    } else if (options_.starts_try_each_camera && seen.found && seen.feet_seen && HeadOnBlob(seen)) {
      // The person where expected in some view, the estimate's head on their blob, but
      // perhaps off in depth along that camera's line of sight, which another camera's
      // blob, not counted as theirs, would say: where the lines of sight meet.
      for (const Eigen::Vector2d& place : MeetingPlaces(seen, everyone)) {
        if ((place - predicted_floor_mm).norm() <= options_.relocate_distance_mm) continue;
        filter_->Relocate(place, 120, options_.relocate_share, frame.index, 0, 0);
        break;
      }
    }
  }
  if (hidden_ && !frame.dropped) {
    // Hidden: predicted until the person is seen near where the dynamics put them (then
    // tracked again), or for max_hidden_s at most (then a restart from whoever is seen).
    const PersonSighting& seen = located();
    const double since = frame.time_s - last_good_time_s_;
    // Hidden behind others while the prediction is drawn under them; no longer, and not
    // seen where predicted, the person is looked for again as after a loss (near where
    // they were last explained well): a prediction gone astray behind someone must not
    // keep them from being found beside it.
    bool still_behind = true;
    if (behind_) {
      TrackedFrame predicted;
      predicted.state = filter_->Mean();
      SetEstimate(&predicted);
      still_behind = Behind(predicted, frame);
    }
    if (near_prediction(seen)) {
      hidden_ = false;
    } else if (since >= options_.max_hidden_s || !still_behind) {
      hidden_ = false;
      started_ = false;
      out.status = TrackStatus::kLost;
      if (seen.found) LookFor(frame);
      finish(&out);
      return out;
    }
  }
  if (frame.dropped || hidden_) {
    out.status = TrackStatus::kPredicted;
    out.state = filter_->Mean();
    SetEstimate(&out);
    // Hidden in view; predicted out of every view, they have left it.
    if (hidden_) out_of_view_ = InView(out.joints_mm) ? 0 : out_of_view_ + 1;
    if (hidden_ && out_of_view_ >= options_.lost_frames) {
      hidden_ = false;
      started_ = false;
      out.status = TrackStatus::kLost;
      if (located().found) LookFor(frame);
    }
    finish(&out);
    return out;
  }
  const std::vector<cv::Rect> regions = Regions(nullptr);
  // Each camera's mask prepared on its own thread (hole filling and the distance transform
  // take about a millisecond per camera).
  std::vector<CameraObservation> observations(frame.masks.size());
  pool_.For(static_cast<int>(frame.masks.size()), [&](int begin, int end, int) {
    for (int c = begin; c < end; ++c) {
      observations[c] = Observe(frame, c, regions[c]);
    }
  });
  if (held_size_ > 0 && !frame.dropped) {
    const PersonSighting& seen = located();
    if (seen.found && seen.feet_seen && near_prediction(seen)) held_size_ = 0;
    else filter_->Set(state_model_->placement().size, held_size_);
  }
  // Turns to any heading (TrackerOptions::turn_every), with two cameras or more after a
  // frame explained well.
  if (legs_by_phase_ && !fresh_ && options_.turn_every > 0 && cameras_.size() >= 2 && bad_frames_ == 0)
    filter_->Reorient(options_.turn_every, frame.index);
  if (legs_by_phase_ && !fresh_ && options_.reverse_every > 0) {
    // Turned round, walking the other way (TrackerOptions::reverse_every).
    const PlacementIndex p = state_model_->placement();
    int k = 0;
    filter_->Transform(
        [&](double* s) {
          s[p.heading] += std::numbers::pi;
          s[p.rate] = -s[p.rate];
          s[0] += 0.5 * (k++ % 2);
        },
        options_.reverse_every);
  }
  // A frame the annealed estimate explains badly (mean IoU under lost_iou: the person
  // hidden, their blob gone aside) leaves the particles as the dynamics put them, any turn
  // among them: fitted to whatever shows, they shrank and shortened their stride, and then,
  // hidden, walked on at a fifth of the walker's speed (the hidden-person test, seeds 4, 6).
  const bool judged = !fresh_ && options_.predict_bad_frames;
  const StateMatrix predicted = judged ? filter_->particles() : StateMatrix();
  AnnealingReport report = filter_->Update(observations, frame.index, fresh_ ? options_.start_layers : 0);
  if (judged && ExplainsBadly(report.estimate, observations)) {
    filter_->Reset(predicted);
    report.estimate = filter_->Mean();
  }
  if (fresh_) {
    mirror_evidence_ = 0;
    mirror_streak_ = 0;
  }
  fresh_ = false;
  out.state = report.estimate;
  out.ess = report.ess;
  out.evaluations = report.evaluations + (judged ? 1 : 0);
  if (legs_by_phase_ && !holds_order_) {
    // Which leg is forward: the estimate against itself half a cycle on.
    Eigen::VectorXd mirror = out.state;
    mirror[0] += 0.5;
    state_model_->Normalise(mirror.data());
    const double difference = filter_->Score(out.state.data(), observations, nullptr) -
                              filter_->Score(mirror.data(), observations, nullptr);
    mirror_evidence_ = 0.8 * mirror_evidence_ + difference;
    mirror_streak_ = difference > 0 ? mirror_streak_ + 1 : 0;
    out.evaluations += 2;
    if (mirror_evidence_ > options_.mirror_margin && mirror_streak_ >= options_.mirror_streak) {
      filter_->Shift(0, 0.5);
      ++leg_order_epoch_;
      out.state = mirror;
      mirror_evidence_ = 0;
      mirror_streak_ = 0;
    }
  }
  if (legs_by_phase_) {
    if (ordered && OtherLegOrder(out.state[0], *last_order_, dt)) ++leg_order_epoch_;
    last_order_ = Eigen::Vector2d(out.state[0], out.state[state_model_->placement().rate]);
  }
  SetEstimate(&out);
  const PlacementIndex p = state_model_->placement();
  if (refiner_) {
    const Eigen::Vector3d latent = model_.HasManifold()
                                       ? model_.ManifoldToLatent({out.state[0], out.state[1], out.state[2]})
                                       : Eigen::Vector3d(out.state[0], out.state[1], out.state[2]);
    const PoseRefiner::Result r = refiner_->Refine(out.pose_deg, latent, out.state[p.x], out.state[p.z],
                                                   out.state[p.heading], out.state[p.size], out.width, observations,
                                                   frame.index);
    out.pose_deg = r.pose_deg;
    out.size = r.size;
    out.heading_rad = r.heading_rad;
    out.evaluations += r.evaluations;
    placer_.Place(out.pose_deg.data(), r.x_mm, r.z_mm, r.heading_rad, r.size, &out.joints_mm);
  }
  out.build = shape_.drawn();
  {
    SilhouetteLikelihood::Workspace workspace = likelihood_.NewWorkspace();
    std::vector<Capsule> capsules;
    body_.Place(out.joints_mm, out.size * out.width, out.build.widths, out.build.garment, &capsules);
    likelihood_.Cost(capsules, observations, &workspace, &out.cameras);
    if (out.MeanIou() >= options_.lost_iou) {
      if (shadow_light_.Due()) LookForShadowLight(out, capsules, observations, frame.index);
      if (alignment_.active()) AlignViews(capsules, observations, out);
      int views = 0;  // cameras that see the person and draw them
      for (const CameraScore& c : out.cameras) views += c.observed_px > 0 && c.model_px > 0;
      // The estimate (its pose, place, heading and size) drawn with each build, scored on
      // the pool's threads.
      std::vector<SilhouetteLikelihood::Workspace> workspaces;
      for (int w = 0; w < pool_.size(); ++w) workspaces.push_back(likelihood_.NewWorkspace());
      shape_.Update(
          [&](const std::vector<Build>& builds) {
            std::vector<double> costs(builds.size());
            pool_.For(static_cast<int>(builds.size()), [&](int begin, int end, int worker) {
              Eigen::Matrix3Xd joints;
              std::vector<Capsule> drawn;
              std::vector<CameraScore> scores;
              for (int i = begin; i < end; ++i) {
                placer_.Place(out.pose_deg.data(), out.joints_mm(0, 0), out.joints_mm(2, 0), out.heading_rad,
                              out.size, builds[i].lengths, builds[i].floor_mm, &joints);
                body_.Place(joints, out.size * out.width, builds[i].widths, builds[i].garment, &drawn);
                likelihood_.Cost(drawn, observations, &workspaces[worker], &scores);
                costs[i] = ShapeCost(scores);
              }
            });
            return costs;
          },
          views >= 2);
      ApplyBuild();
    }
  }
  // Evidence of loss: the cameras that see something where the person is expected, or
  // draw the estimate, explaining it badly. A camera that sees nobody there and whose
  // estimate is out of its view says nothing. When the estimate explains the views
  // badly, is anyone there at all? A person-sized blob standing on the floor in some
  // camera, not a segmentation's specks (LocatePerson).
  last_drawn_ = out.cameras;
  PersonSighting seen;
  if (out.MeanIou() < options_.lost_iou) {
    seen = located();
    ++bad_frames_;
  } else {
    bad_frames_ = 0;
    unconfirmed_ = false;
    last_good_time_s_ = frame.time_s;
  }
  const bool nobody = bad_frames_ > 0 && !seen.found;
  bool evidence = false;  // some camera sees someone where expected, or draws the estimate
  bool drawn = false;     // some camera draws the estimate
  for (const CameraScore& c : out.cameras) {
    evidence = evidence || c.observed_px > 0 || c.model_px > 0;
    drawn = drawn || c.model_px > 0;
  }
  // Drawn in no camera for lost_frames frames: the person has left every view, and
  // whoever is seen (the nearest to where they were) is tracked instead. A prediction
  // walking on out of view while others walk by in it tells nobody anything.
  out_of_view_ = drawn && InView(out.joints_mm) ? 0 : out_of_view_ + 1;
  // A restart looks first where the person was last seen and explained well.
  if (drawn && bad_frames_ == 0)
    next_choice_ = PersonPreference::Near(Eigen::Vector2d(out.joints_mm(0, 0), out.joints_mm(2, 0)),
                                          options_.restart_within_mm);
  const bool left = out_of_view_ >= options_.lost_frames;
  if (left && !seen.found) seen = located();
  // Someone seen far from where the dynamics put the person is someone or something else:
  // the person is hidden (an occluder, a failed segmentation), and is predicted, not
  // restarted on it, for up to max_hidden_s; hidden in view, not having left it. Having
  // left, they are lost, whatever is still seen.
  const bool recent = frame.time_s - last_good_time_s_ < options_.max_hidden_s;
  const bool elsewhere = seen.found && recent && !near_prediction(seen);
  // Behind the others tracked with them (several people at once): a poor fit is what being
  // hidden looks like, and the masks, the others' pixels taken out, show nobody there. Not
  // evidence of loss: predicted, as behind an occluder, until seen again near the
  // prediction.
  const bool behind = !left && recent && bad_frames_ > 0 && Behind(out, frame);
  if (behind || (!left && bad_frames_ >= options_.lost_frames && elsewhere)) {
    out.status = TrackStatus::kPredicted;
    if (!hidden_) WalkOnAsSeen(out, frame);
    hidden_ = true;
    behind_ = behind;
  } else if (nobody || bad_frames_ >= options_.lost_frames || left) {
    out.status = TrackStatus::kLost;
    // Start again from the masks as soon as someone is seen.
    started_ = false;
    if (seen.found) LookFor(frame);
  } else {
    // Out of every view and seen by none, or never yet explained well since a start from
    // nobody: the estimate is the prediction.
    out.status = evidence && !unconfirmed_ ? TrackStatus::kTracked : TrackStatus::kPredicted;
  }
  // Going against its dynamics: the walk's direction turned (TrackerOptions::travel).
  if (legs_by_phase_ && out.status == TrackStatus::kTracked && bad_frames_ == 0) {
    const double direction = out.state[p.heading] + (out.state[p.rate] < 0 ? std::numbers::pi : 0);
    if (travel_.Against(frame.time_s, Eigen::Vector2d(out.state[p.x], out.state[p.z]), direction)) {
      filter_->Transform([&](double* s) { s[p.rate] = -s[p.rate]; });
    } else if (options_.pace && travel_.Speed() >= 0 && dt > 0) {
      // The cadence follows the pace the estimates go (TrackerOptions::pace).
      const double share = std::min(1.0, dt / options_.travel.window_s), speed = travel_.Speed();
      filter_->Transform([&](double* s) { state_model_->Pace(speed, share, s); });
    }
  }
  if (legs_by_phase_ && tries_other_legs_) TryOtherLegs(frame, &out);
  finish(&out);
  return out;
}

void Tracker::WalkOnAsSeen(const TrackedFrame& estimate, const Frame& frame) {
  using WalkOn = TrackerOptions::WalkOn;
  if (options_.walk_on_as_seen == WalkOn::kNever || !legs_by_phase_ ||
      !(travel_.Speed() >= options_.travel.min_speed_mm_s))
    return;
  if (options_.walk_on_as_seen == WalkOn::kBehindPainting) {
    const std::vector<cv::Mat>& painted = Painted(frame);
    std::vector<cv::Mat> drawn(cameras_.size());
    DrawEstimate(estimate, &drawn);
    bool behind = false;
    for (size_t c = 0; c < drawn.size() && c < painted.size(); ++c) behind = behind || HalfUnder(drawn[c], painted[c]);
    if (!behind) return;
  }
  const PlacementIndex p = state_model_->placement();
  const Eigen::VectorXd mean = filter_->Mean();
  const double going = mean[p.heading] + (mean[p.rate] < 0 ? std::numbers::pi : 0);
  const double turn = std::remainder(travel_.Direction() - going, 2 * std::numbers::pi);
  const double speed = travel_.Speed();
  filter_->Transform([&](double* s) {
    s[p.heading] += turn;
    state_model_->Pace(speed, 1, s, /*cover=*/true);
  });
}

bool OtherLegOrder(double phase, const Eigen::Vector2d& last, double dt) {
  const double off = phase - (last[0] + last[1] * dt);
  return std::abs(off - std::round(off)) > 0.25;
}

namespace {

double TotalCost(const TrackedFrame& frame) {
  double cost = 0;
  for (const CameraScore& c : frame.cameras) cost += c.cost;
  return cost;
}

}  // namespace

bool Tracker::LegsSettled() const {
  if (!legs_by_phase_ || !tries_other_legs_ || options_.legs_trial_frames == 0) return true;
  if (other_legs_) return false;
  return !legs_trial_due_ || frames_since_start_ >= options_.mirror_frames + options_.legs_trial_frames;
}

void Tracker::TryOtherLegs(const Frame& frame, TrackedFrame* out) {
  const bool tracked = out->status == TrackStatus::kTracked && bad_frames_ == 0;
  if (!other_legs_) {
    if (!legs_trial_due_ || options_.legs_trial_frames == 0 || !tracked ||
        frames_since_start_ < options_.mirror_frames)
      return;
    legs_trial_due_ = false;
    other_legs_ = Follower(options_.annealing.layers);
    other_legs_->filter_->Shift(0, 0.5);
    other_legs_->holds_order_ = true;
    other_legs_->last_order_ = Eigen::Vector2d(out->state[0] + 0.5, out->state[state_model_->placement().rate]);
    other_legs_->last_time_s_ = frame.time_s;
    other_legs_->last_good_time_s_ = last_good_time_s_;
    other_legs_->travel_ = travel_;
    other_legs_frames_ = 0;
    own_cost_ = other_legs_cost_ = 0;
    return;
  }
  TrackedFrame other = other_legs_->Step(frame);
  out->evaluations += other.evaluations;
  // Either lost or explaining badly: no fair comparison; the trial ends as it is.
  if (!tracked || other.status != TrackStatus::kTracked || other_legs_->bad_frames_ > 0) {
    other_legs_.reset();
    return;
  }
  // The second tracker began from particles fitted to the other order, moved: the first
  // half of its trial is it settling, and only the second half is compared.
  const int judged = options_.legs_trial_frames - options_.legs_trial_frames / 2;
  if (++other_legs_frames_ > options_.legs_trial_frames - judged) {
    own_cost_ += TotalCost(*out);
    other_legs_cost_ += TotalCost(other);
  }
  if (other_legs_frames_ < options_.legs_trial_frames) return;
  if ((own_cost_ - other_legs_cost_) / judged > options_.legs_trial_margin) {
    filter_->Reset(other_legs_->filter_->particles());
    ++leg_order_epoch_;
    shape_ = other_legs_->shape_;
    ApplyBuild();
    alignment_ = other_legs_->alignment_;
    if (refiner_ && other_legs_->refiner_) refiner_->ContinueFrom(*other_legs_->refiner_);
    travel_ = other_legs_->travel_;
    mirror_evidence_ = 0;
    mirror_streak_ = 0;
    other.evaluations = out->evaluations;
    *out = std::move(other);
  }
  other_legs_.reset();
}

std::unique_ptr<Tracker> Tracker::Follower(int layers) const {
  TrackerOptions options = options_;
  options.annealing.layers = layers;
  options.shadow.enabled = false;  // this one's light, when found, is the follower's
  auto follower = std::make_unique<Tracker>(model_, cameras_, options, table_);
  follower->tries_other_legs_ = false;
  follower->filter_->Reset(filter_->particles());
  follower->shape_ = shape_;
  follower->ApplyBuild();
  follower->alignment_ = alignment_;
  if (shadow_light_.light()) follower->shadow_light_ = shadow_light_;
  if (refiner_ && follower->refiner_) follower->refiner_->ContinueFrom(*refiner_);
  follower->started_ = true;
  follower->frames_since_start_ = frames_since_start_;
  follower->mirror_evidence_ = mirror_evidence_;
  follower->mirror_streak_ = mirror_streak_;
  follower->held_size_ = held_size_;
  follower->next_choice_ = next_choice_;
  follower->last_drawn_ = last_drawn_;
  return follower;
}

bool Tracker::ExplainedWell(const TrackedFrame& estimate) const {
  const bool drawn = std::any_of(estimate.cameras.begin(), estimate.cameras.end(),
                                 [](const CameraScore& c) { return c.model_px > 0; });
  return estimate.status == TrackStatus::kTracked && drawn && estimate.MeanIou() >= options_.lost_iou;
}

std::vector<TrackedFrame> Tracker::BackOver(const std::vector<Frame>& frames, size_t lead) const {
  if (!legs_by_phase_ || !started_ || frames.size() < 2) return {};
  // The second pass starts from particles that have found the person: it searches with
  // half the layers. On the tuning clips the same (94.2 mm either way, 4 seeds), and a
  // start's second costs 1.19x its first pass on `07_01-4cam` instead of 1.30x.
  const std::unique_ptr<Tracker> follower = Follower(std::max(1, options_.annealing.layers / 2));
  Tracker& back = *follower;
  const int rate = state_model_->placement().rate;
  const auto turn = [rate](double* s) { s[rate] = -s[rate]; };
  back.filter_->Transform(turn);
  // Time runs on forwards for the second tracker: each frame's time and index mirrored
  // about the last frame's.
  const Frame& last = frames.back();
  back.last_time_s_ = last_time_s_;
  back.last_good_time_s_ = last_good_time_s_ > -1e8 ? last.time_s : last_good_time_s_;
  std::vector<TrackedFrame> out;
  for (size_t i = frames.size() - 1; i-- > 0;) {
    Frame f = frames[i];
    f.index = 2 * last.index - frames[i].index;
    f.time_s = 2 * last.time_s - frames[i].time_s;
    TrackedFrame estimate = back.Step(f);
    if (estimate.status == TrackStatus::kLost || (i < lead && !ExplainedWell(estimate))) break;
    estimate.index = frames[i].index;
    estimate.time_s = frames[i].time_s;
    turn(estimate.state.data());
    out.push_back(std::move(estimate));
  }
  std::reverse(out.begin(), out.end());
  return out;
}

bool Tracker::ExplainsBadly(const Eigen::VectorXd& estimate, const std::vector<CameraObservation>& observations) const {
  TrackedFrame probe;
  filter_->Score(estimate.data(), observations, &probe.cameras);
  return probe.MeanIou() < options_.lost_iou;
}

bool Tracker::Behind(const TrackedFrame& estimate, const Frame& frame) const {
  const std::vector<cv::Mat> hidden = HiddenPixels(frame);
  if (hidden.empty()) return false;
  std::vector<cv::Mat> drawn(cameras_.size());
  DrawEstimate(estimate, &drawn);
  for (size_t c = 0; c < drawn.size() && c < hidden.size(); ++c) {
    if (drawn[c].empty() || hidden[c].empty() || drawn[c].size() != hidden[c].size()) continue;
    const int own = cv::countNonZero(drawn[c]);
    const int under = cv::countNonZero(drawn[c] & hidden[c]);
    // ...and under a third of it lies on empty floor (neither under them nor on the mask):
    // someone who has gone (left through a door, or never there) leaves the rest of their
    // drawing there. Counted against the whole drawing, not its rest: a prediction wholly
    // behind someone but for a sliver at the edge (14 of 610 px) is still behind them.
    const int seen = c < frame.masks.size() && frame.masks[c].size() == drawn[c].size()
                         ? cv::countNonZero(drawn[c] & frame.masks[c] & ~hidden[c])
                         : 0;
    if (own > 0 && 2 * under >= own && 3 * (own - under - seen) < own) return true;
  }
  return false;
}

double Tracker::StatureMm(const TrackedFrame& estimate) const {
  if (estimate.joints_mm.cols() == 0) return std::numeric_limits<double>::quiet_NaN();
  return HeadTopMm(estimate.joints_mm, head_, estimate.size) - estimate.build.floor_mm;
}

double Tracker::SizeOf(double height_mm) const { return std::clamp(height_mm / model_height_mm_, 0.8, 1.25); }

const std::vector<cv::Mat>& Tracker::Painted(const Frame& frame) const {
  static const std::vector<cv::Mat> none;
  if (!frame.painted.empty()) return frame.painted;
  return options_.hidden_is_painted ? frame.hidden : none;
}

CameraObservation Tracker::Observe(const Frame& frame, int c, const cv::Rect& region) {
  // Others' drawings are in the model's cameras already: not aligned again.
  const cv::Mat painting = CameraOf(Painted(frame), c);
  const cv::Mat others = frame.painted.empty() && options_.hidden_is_painted ? cv::Mat() : CameraOf(frame.hidden, c);
  const cv::Mat mask = alignment_.Apply(c, frame.masks[c]);
  CameraObservation observation = likelihood_.Observe(mask, region, EitherHidden(others, painting));
  if (painting.empty()) return observation;
  // A frame's painting is its own copy: split again only when it differs from the last.
  auto& [last, objects] = painted_objects_[c];
  if (last.size() != painting.size() || cv::countNonZero(last != painting) > 0) {
    last = painting.clone();
    objects = SplitPainting(painting, likelihood_.renderer(c).camera());
  }
  // The objects a body drawn near the region could be in front of, the three most in view
  // there at most (the others stay hidden for every body).
  const cv::Rect& window = observation.window();
  std::vector<std::pair<int, size_t>> near;  // (pixels in the window, object)
  for (size_t k = 0; k < objects.size(); ++k) {
    const int in_window = window.empty() ? 0 : cv::countNonZero(objects[k].pixels(window));
    if (in_window > 0 && std::isfinite(objects[k].distance_mm)) near.emplace_back(in_window, k);
  }
  if (near.empty()) return observation;
  std::sort(near.begin(), near.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  near.resize(std::min<size_t>(near.size(), 3));
  std::vector<PaintedObject> chosen;
  for (const auto& [pixels, k] : near) chosen.push_back(objects[k]);
  std::vector<CameraObservation> by_subset;
  for (unsigned s = 0; s + 1 < (1u << chosen.size()); ++s) {
    cv::Mat fewer = painting.clone();
    for (size_t j = 0; j < chosen.size(); ++j)
      if (!(s & (1u << j))) fewer.setTo(0, chosen[j].pixels);
    by_subset.push_back(likelihood_.Observe(mask, region, EitherHidden(others, fewer)));
  }
  observation.SetPaintedObjects(std::move(chosen), std::move(by_subset));
  return observation;
}

std::vector<Eigen::Vector2d> Tracker::MeetingPlaces(const PersonSighting& at,
                                                   const std::vector<PersonSighting>& people) const {
  std::vector<Eigen::Vector2d> places;
  for (const PersonSighting& other : people) {
    if (!other.found || !other.feet_seen || other.floor_mm == at.floor_mm ||
        (other.floor_mm - at.floor_mm).norm() > kPairMm)
      continue;
    std::vector<Eigen::Vector2d> readings = at.camera_floor_mm;
    bool adds = false, shared = false;
    for (size_t c = 0; c < readings.size() && c < other.camera_floor_mm.size(); ++c) {
      if (!other.camera_floor_mm[c].allFinite()) continue;
      (readings[c].allFinite() ? shared : adds) = true;
      readings[c] = other.camera_floor_mm[c];
    }
    Eigen::Vector2d fused;
    if (adds && !shared && FuseReadings(cameras_, readings, &fused)) places.push_back(fused);
  }
  return places;
}

bool Tracker::HeadOnBlob(const PersonSighting& seen) const {
  TrackedFrame estimate;
  estimate.state = filter_->Mean();
  SetEstimate(&estimate);
  int top = 0;
  estimate.joints_mm.row(1).maxCoeff(&top);
  for (size_t c = 0; c < cameras_.size() && c < seen.boxes.size(); ++c) {
    const cv::Rect& box = seen.boxes[c];
    Eigen::Vector2d head;
    if (box.empty() || !cameras_[c].Project(estimate.joints_mm.col(top), &head)) continue;
    if (head.x() >= box.x && head.x() <= box.x + box.width &&
        std::abs(head.y() - box.y) <= options_.head_on_blob * box.height)
      return true;
  }
  return false;
}

bool Tracker::InView(const Eigen::Matrix3Xd& joints) const {
  for (const Camera& camera : cameras_) {
    if (ShareInView(camera, joints) >= options_.min_in_view) return true;
  }
  return false;
}

void Tracker::ApplyBuild() {
  const Build build = shape_.drawn();
  body_.SetRegionScales(build.widths);
  body_.SetGarment(build.garment);
  state_model_->SetProportions(build.lengths);
  state_model_->SetFloor(build.floor_mm);
  placer_.SetProportions(build.lengths);
  placer_.SetFloor(build.floor_mm);
  if (refiner_) {
    refiner_->SetProportions(build.lengths);
    refiner_->SetFloor(build.floor_mm);
  }
}

void Tracker::SetEstimate(TrackedFrame* out) const {
  ExactPose(out->state, &out->pose_deg, &out->joints_mm);
  out->prior_joints_mm = out->joints_mm;
  const PlacementIndex p = state_model_->placement();
  out->size = out->state[p.size];
  out->width = out->state[p.width];
  out->heading_rad = out->state[p.heading];
}

void Tracker::LookForShadowLight(const TrackedFrame& out, const std::vector<Capsule>& capsules,
                                 const std::vector<CameraObservation>& observations, int frame) {
  std::vector<Eigen::Vector3d> moves{Eigen::Vector3d::Zero()};
  int seeing = -1, views = 0;
  for (size_t c = 0; c < out.cameras.size(); ++c)
    if (out.cameras[c].observed_px > 0 && out.cameras[c].model_px > 0) seeing = static_cast<int>(c), ++views;
  if (views == 1 && seeing < static_cast<int>(cameras_.size())) {
    Eigen::Vector3d sight = out.joints_mm.col(0) - cameras_[seeing].CentreInWorld();
    sight.y() = 0;
    if (sight.norm() > 1) {
      sight.normalize();
      for (int k = 1; k <= 3; ++k) moves.push_back(k * options_.relocate_distance_mm * sight);
    }
  }
  std::vector<std::vector<Capsule>> placed(moves.size(), capsules);
  for (size_t m = 1; m < moves.size(); ++m)
    for (Capsule& part : placed[m]) part.from_mm += moves[m], part.to_mm += moves[m];
  std::vector<SilhouetteLikelihood::Workspace> spaces;
  for (int w = 0; w < pool_.size(); ++w) spaces.push_back(likelihood_.NewWorkspace());
  // Each light's cost at each place (light-major), on the pool's threads.
  const auto costs_at = [&](const std::vector<std::optional<Eigen::Vector3d>>& lights) {
    const int n = static_cast<int>(moves.size());
    std::vector<double> costs(lights.size() * n);
    pool_.For(static_cast<int>(costs.size()), [&](int begin, int end, int worker) {
      for (int i = begin; i < end; ++i) {
        const std::optional<Eigen::Vector3d>& light = lights[i / n];
        costs[i] = likelihood_.CostUnder(light ? &*light : nullptr, placed[i % n], observations, &spaces[worker]);
      }
    });
    return costs;
  };
  shadow_light_.Look([&](const std::vector<std::optional<Eigen::Vector3d>>& lights) {
    const std::vector<double> costs = costs_at(lights);
    std::vector<double> best(lights.size());
    for (size_t i = 0; i < lights.size(); ++i)
      best[i] = *std::min_element(costs.begin() + i * moves.size(), costs.begin() + (i + 1) * moves.size());
    return best;
  });
  if (!shadow_light_.light()) return;
  shadow_light_frame_ = frame;
  // The particles go to the place where the light found explains the masks best.
  const std::vector<double> costs = costs_at({shadow_light_.light()});
  const Eigen::Vector3d& move = moves[std::distance(costs.begin(), std::min_element(costs.begin(), costs.end()))];
  if (move.squaredNorm() > 0) {
    const PlacementIndex p = state_model_->placement();
    filter_->Shift(p.x, move.x());
    filter_->Shift(p.z, move.z());
  }
  // A trial's second tracker scores with the same shadows (its costs are compared).
  if (other_legs_) other_legs_->AdoptShadowLight(shadow_light_);
}

void Tracker::AlignViews(const std::vector<Capsule>& capsules, const std::vector<CameraObservation>& observations,
                         const TrackedFrame& out) {
  const int n = static_cast<int>(cameras_.size());
  std::vector<cv::Mat> silhouettes(n), masks(n);
  std::vector<cv::Rect> boxes(n);
  pool_.For(n, [&](int begin, int end, int) {
    for (int c = begin; c < end; ++c) {
      masks[c] = observations[c].mask();
      boxes[c] = observations[c].region();
      if (out.cameras[c].model_px == 0 || out.cameras[c].observed_px == 0) continue;  // no say
      BitMask canvas(cameras_[c].width, cameras_[c].height);
      likelihood_.renderer(c).Draw(capsules, &canvas);
      silhouettes[c] = canvas.ToMat();
    }
  });
  alignment_.Update(silhouettes, masks, boxes, out.joints_mm.col(0));
}

void Tracker::ExactPose(const Eigen::VectorXd& state, Eigen::VectorXd* pose_deg, Eigen::Matrix3Xd* joints_mm) const {
  *pose_deg = state_model_->Pose(state.data());
  const PlacementIndex p = state_model_->placement();
  placer_.Place(pose_deg->data(), state[p.x], state[p.z], state[p.heading], state[p.size], joints_mm);
}

void Tracker::DrawEstimate(const TrackedFrame& frame, std::vector<cv::Mat>* masks) const {
  if (frame.state.size() == 0 || frame.joints_mm.cols() == 0) return;
  std::vector<Capsule> capsules;
  body_.Place(frame.joints_mm, frame.size * frame.width, frame.build.widths, frame.build.garment, &capsules);
  for (size_t c = 0; c < cameras_.size() && c < masks->size(); ++c) {
    BitMask drawn(cameras_[c].width, cameras_[c].height);
    likelihood_.renderer(static_cast<int>(c)).Draw(capsules, &drawn);
    cv::Mat& mask = (*masks)[c];
    if (mask.empty()) mask = cv::Mat::zeros(cameras_[c].height, cameras_[c].width, CV_8UC1);
    cv::bitwise_or(mask, drawn.ToMat(), mask);
  }
}

void RunSource(FrameSource* source, int start_frames, const std::function<void(const std::vector<Frame>&)>& start,
               const std::function<void(const Frame&)>& step, const std::function<bool()>& stop) {
  const auto stopped = [&stop] { return stop && stop(); };
  std::vector<Frame> first;
  Frame frame;
  while (static_cast<int>(first.size()) < start_frames && !stopped() && source->Next(&frame)) first.push_back(frame);
  if (first.empty()) return;
  start(first);
  for (const Frame& f : first) step(f);
  while (!stopped() && source->Next(&frame)) step(frame);
}

StartBackOver::StartBackOver(const Tracker* tracker)
    : tracker_(tracker), armed_(tracker->options().start_backwards_s > 0) {}

void StartBackOver::Add(const Frame& frame, TrackedFrame estimate, std::vector<Estimate>* ready) {
  const double backwards_s = tracker_->options().start_backwards_s;
  if (estimate.status == TrackStatus::kLost) {
    // Lost before the start was gone over: the frames stand as tracked (or as gone back
    // over while the legs settled). The next start (a restart) is gone over in its turn,
    // and this frame waits for it as a lead-in.
    if (held_.size() > lead_) Flush(ready);
    armed_ = backwards_s > 0;
    held_.push_back({frame, std::move(estimate)});
    ++lead_;
    while (lead_ > 0 && !(held_.back().frame.time_s - held_.front().frame.time_s < backwards_s)) {
      ready->push_back(std::move(held_.front()));
      held_.erase(held_.begin());
      --lead_;
    }
    return;
  }
  held_.push_back({frame, std::move(estimate)});
  if (!armed_) return Flush(ready);
  if (!back_) {
    if (frame.time_s - held_[lead_].frame.time_s < backwards_s) return;
    back_epoch_ = tracker_->leg_order_epoch();
    back_ = GoBackOver();
  }
  if (!tracker_->LegsSettled()) return;
  if (tracker_->leg_order_epoch() != back_epoch_) {
    // The legs may have turned since it went back, and it carried back the order it
    // started from: its frames cost it, and it goes back again from here.
    back_->kept = false;
    Apply(std::move(*back_));
    back_ = GoBackOver();
  }
  armed_ = false;
  Flush(ready);
}

StartBackOver::SecondPass StartBackOver::GoBackOver() {
  std::vector<Frame> frames;
  std::vector<TrackedFrame> first;
  for (const Estimate& e : held_) frames.push_back(e.frame), first.push_back(e.estimate);
  back_end_ = held_.size();
  return GoBack(*tracker_, frames, first, lead_);
}

void StartBackOver::Apply(SecondPass back) {
  const size_t from = back_end_ - 1 - back.estimates.size();
  for (size_t i = 0; i < back.estimates.size(); ++i) {
    TrackedFrame& forward = held_[from + i].estimate;
    if (back.kept) {
      forward = std::move(back.estimates[i]);
    } else {  // each frame costs both passes, whichever is kept
      forward.seconds = back.estimates[i].seconds;
      forward.evaluations = back.estimates[i].evaluations;
    }
  }
}

StartBackOver::SecondPass StartBackOver::GoBack(const Tracker& tracker, const std::vector<Frame>& frames,
                                                const std::vector<TrackedFrame>& first, size_t lead) {
  SecondPass back;
  back.estimates = tracker.BackOver(frames, lead);
  // The frames before the last one, as far back as the second tracker went. The second
  // pass is kept unless it explains their masks worse (TrackerOptions::back_over_margin):
  // a track gone wrong by the frame it goes back from (legs swapped) carries that back.
  // Judged on the start's own frames: the lead-in's were lost the first time.
  const size_t from = first.size() - 1 - back.estimates.size();
  const std::span<const TrackedFrame> forward(first.data() + from, back.estimates.size());
  const size_t own = std::max(from, lead) - from;
  back.kept = KeepSecond(forward.subspan(own), std::span<const TrackedFrame>(back.estimates).subspan(own),
                         tracker.options().back_over_margin, tracker.options().lost_iou);
  for (size_t i = 0; i < back.estimates.size(); ++i) {
    back.estimates[i].seconds += forward[i].seconds;
    back.estimates[i].evaluations += forward[i].evaluations;
  }
  return back;
}

bool StartBackOver::KeepSecond(std::span<const TrackedFrame> first, std::span<const TrackedFrame> second,
                               double margin, double unseen_iou) {
  if (first.size() != second.size() || first.empty()) return false;
  // A frame where a pass is drawn nowhere and sees nobody near it (MeanIou's 1: no
  // evidence of loss) counts unseen_iou, neither a fit nor a loss. At 1, a pass that went
  // back behind a pillar outscored one on the walker beside it (the harsh webcam clip,
  // seed 4: frames 34-41 at IoU 0.67-0.71 replaced by a body on the pillar); at 0, one
  // that went behind the pillar with the walker lost to one predicted beside it (the same
  // clip's uncalibrated twin, seed 4: 232 -> 287 mm).
  double first_iou = 0, second_iou = 0;
  for (size_t i = 0; i < first.size(); ++i) {
    first_iou += first[i].MeanIou(unseen_iou);
    second_iou += second[i].MeanIou(unseen_iou);
  }
  return second_iou >= first_iou - margin * static_cast<double>(first.size());
}

void StartBackOver::Flush(std::vector<Estimate>* ready) {
  if (back_) Apply(std::move(*back_));
  back_.reset();
  for (Estimate& e : held_) ready->push_back(std::move(e));
  held_.clear();
  lead_ = 0;
}

std::vector<TrackedFrame> TrackSource(FrameSource* source, Tracker* tracker,
                                      const std::function<void(const Frame&, TrackedFrame&)>& on_frame,
                                      const std::function<bool()>& stop) {
  std::vector<TrackedFrame> tracked;
  StartBackOver hold(tracker);
  std::vector<StartBackOver::Estimate> ready;
  const auto give = [&] {
    for (StartBackOver::Estimate& e : ready) {
      tracked.push_back(std::move(e.estimate));
      if (on_frame) on_frame(e.frame, tracked.back());
    }
    ready.clear();
  };
  RunSource(
      source, tracker->options().start_frames, [tracker](const std::vector<Frame>& first) { tracker->StartFromFrames(first); },
      [&](const Frame& f) {
        hold.Add(f, tracker->Step(f), &ready);
        give();
      },
      stop);
  hold.Flush(&ready);  // the source ended before a start was gone over
  give();
  return tracked;
}

}  // namespace jgpm
