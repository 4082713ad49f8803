#include "tracker/run/track_job.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <future>
#include <map>
#include <numbers>

#include <Eigen/Geometry>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "io/base/error.h"
#include "io/base/json_file.h"
#include "io/base/output_batch.h"
#include "io/base/output_folder.h"
#include "io/base/png_file.h"
#include "io/base/text_reader.h"
#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/bvh.h"
#include "io/mocap/bvh_conversion.h"
#include "prior/model/inference.h"
#include "prior/model/model_file.h"
#include "tracker/frames/clip_source.h"
#include "tracker/frames/floor_reflection.h"
#include "tracker/frames/foreground.h"
#include "tracker/frames/occluder_masks.h"
#include "tracker/frames/prefetch_source.h"
#include "tracker/frames/video_frame_source.h"
#include "tracker/run/overlay_videos.h"
#include "tracker/run/pose_table_cache.h"

namespace jgpm {
namespace fs = std::filesystem;
namespace {

// Counts the frames the tracker has taken from its source. A start's frames are given only
// once the tracker has read on (StartBackOver), so a progress counted in frames given ran
// ahead: the line said 101 frames/s on a clip tracked at 22.
class CountingSource : public FrameSource {
 public:
  explicit CountingSource(FrameSource* inner) : inner_(inner) {}
  const std::vector<Camera>& cameras() const override { return inner_->cameras(); }
  double fps() const override { return inner_->fps(); }
  int NumFrames() const override { return inner_->NumFrames(); }
  double mask_scale(size_t camera) const override { return inner_->mask_scale(camera); }
  bool Next(Frame* frame) override { return inner_->Next(frame) && (++read_, true); }
  int read() const { return read_; }

 private:
  FrameSource* const inner_;
  int read_ = 0;
};

int BoneIndex(const std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

// Thigh plus shin, mm, of bone ends named by `names`.
double LegLength(const Eigen::Matrix3Xd& joints, const std::vector<std::string>& names) {
  const int hip = BoneIndex(names, "lhipjoint"), knee = BoneIndex(names, "lfemur"), ankle = BoneIndex(names, "ltibia");
  if (hip < 0 || knee < 0 || ankle < 0) return 0;
  return (joints.col(knee) - joints.col(hip)).norm() + (joints.col(ankle) - joints.col(knee)).norm();
}

// The truth's joints of walker `id` in clip frame `frame` (a one-walker clip's: id 1);
// empty when that walker is not in the scene then.
Eigen::Matrix3Xd WalkerJoints(const ClipGroundTruth& truth, int id, int frame) {
  if (truth.people.empty()) return id == 1 ? truth.frames.at(frame).joints_mm : Eigen::Matrix3Xd();
  for (const ClipPersonFrame& f : truth.people.at(id - 1).frames)
    if (f.frame == frame) return f.joints_mm;
  return Eigen::Matrix3Xd();
}

// --people all: CLEAR MOT and the paired people's pose error against a clip's walkers, and
// the results folder (poses.json with each frame's people, tracked_ID.bvh per person, the
// cameras, the overlays).
void FinishPeople(const TrackJobOptions& o, const ClipFrameSource* clip, const GaitModel& model, OutputFolder* folder,
                  std::optional<OverlayVideos>* overlays, TrackJobResult* result) {
  const TrackRun& run = result->run;
  const std::vector<PeopleFrame>& people = result->people;
  if (clip) {
    const ClipGroundTruth& truth = clip->truth();
    const std::vector<std::vector<MotPoint>> walkers = TruePeople(truth, people.back().index + 1);
    std::vector<MotFrame> frames(people.size());
    for (size_t k = 0; k < people.size(); ++k) {
      if (people[k].index < static_cast<int>(walkers.size())) frames[k].truth = walkers[people[k].index];
      for (const PersonFrame& p : people[k].people) {
        if (p.frame.status == TrackStatus::kLost || p.frame.joints_mm.cols() == 0) continue;
        frames[k].tracked.push_back({p.id, Eigen::Vector2d(p.frame.joints_mm(0, 0), p.frame.joints_mm(2, 0))});
      }
    }
    result->mot = ClearMot(frames);
    std::vector<Eigen::Matrix3Xd> estimates, true_joints;
    for (const MotPair& pair : result->mot->paired) {
      const PeopleFrame& f = people[pair.frame];
      for (const PersonFrame& p : f.people)
        if (p.id == pair.tracked_id) estimates.push_back(p.frame.joints_mm);
      true_joints.push_back(WalkerJoints(truth, pair.truth_id, f.index));
    }
    if (!estimates.empty()) {
      const std::vector<std::string>& names = truth.people.empty() ? truth.joint_names : truth.people[0].joint_names;
      result->matched_bodytrack14 =
          CompareTracks(estimates, model.skeleton().BoneNames(), true_joints, names, Bodytrack14());
    }
  }
  if (!folder) return;
  const fs::path dir = folder->partial();
  OutputBatch batch;
  batch.Add(dir / "poses.json", FormatJson(PeoplePosesJson(run, model.skeleton(), people, result->mot)));
  std::map<int, TrackRun> runs;  // each person's frames, for their BVH
  for (const PeopleFrame& f : people) {
    for (const PersonFrame& p : f.people) {
      auto [it, fresh] = runs.try_emplace(p.id, run);
      it->second.frames.push_back(p.frame);
    }
  }
  std::vector<std::string> names = {"poses.json"};
  for (const auto& [id, person] : runs) {
    const TrackedMotion motion = MakeTrackedMotion(person, model);
    const std::string name = "tracked_" + std::to_string(id) + ".bvh";
    batch.Add(dir / name, FormatBvh(AcclaimToBvh(motion.skeleton, motion.motion)));
    names.push_back(name);
  }
  for (const Camera& c : run.cameras) {
    batch.Add(dir / (c.name + ".yaml"), FormatCameraYaml({c, true}));
    names.push_back(c.name + ".yaml");
  }
  batch.Commit();
  if (*overlays) (*overlays)->Close();
  folder->Commit();
  for (const std::string& name : names) result->written.push_back(fs::path(o.out) / name);
  if (o.overlays)
    for (const Camera& c : run.cameras) result->written.push_back(fs::path(o.out) / ("overlay_" + c.name + ".avi"));
}

}  // namespace

InitialGuess TruthGuess(const ClipGroundTruth& truth, const GaitModel& model, const StateModel& state_model) {
  InitialGuess guess;
  const Eigen::Matrix3Xd& joints = truth.frames.at(0).joints_mm;
  const int root = BoneIndex(truth.joint_names, "root");
  const int left = BoneIndex(truth.joint_names, "lhipjoint"), right = BoneIndex(truth.joint_names, "rhipjoint");
  if (root < 0 || left < 0 || right < 0) ThrowInputError("ground truth", "has no root, lhipjoint and rhipjoint to start from");
  guess.floor_mm = Eigen::Vector2d(joints(0, root), joints(2, root));
  guess.floor_std_mm = 20;
  // Facing: the left hip's side crossed with up.
  const Eigen::Vector3d to_left = joints.col(left) - joints.col(right);
  const Eigen::Vector3d forward = to_left.cross(Eigen::Vector3d::UnitY());
  guess.heading_rad = std::atan2(forward.x(), forward.z());
  guess.heading_std_rad = 3 * std::numbers::pi / 180;
  // Size: the truth's leg against the model's.
  const std::vector<std::string> model_bones = model.skeleton().BoneNames();
  Eigen::Matrix3Xd rest;
  const Eigen::VectorXd zero_pose = Eigen::VectorXd::Zero(model.NumChannels());
  PosePlacer(model.skeleton()).Place(zero_pose.data(), 0, 0, 0, 1, &rest);
  const double model_leg = LegLength(rest, model_bones), true_leg = LegLength(joints, truth.joint_names);
  if (model_leg > 0 && true_leg > 0) guess.size = true_leg / model_leg;
  guess.size_std = 0.01;
  // The pose: the source trial's frame as gait channels, on the model.
  std::error_code ec;
  if (!fs::exists(truth.source_asf, ec) || !fs::exists(truth.source_amc, ec)) return guess;
  const Skeleton skeleton = ReadAsf(truth.source_asf);
  const Motion motion = ReadAmc(truth.source_amc, skeleton);
  const GaitPoseLayout layout(skeleton, truth.source_asf);
  if (layout.channel_names() != model.data().set.channel_names) return guess;
  const double* frame = motion.Frame(std::min(truth.frames[0].source_frame, motion.NumFrames() - 1));
  PoseObservations observed;
  observed.poses_deg.resize(1, layout.NumChannels());
  layout.FromFrame(frame, HeadingOf(layout.RootRotation(frame)), observed.poses_deg.data());
  if (state_model.Name() == "joint-space") {
    guess.coordinates = observed.poses_deg.row(0).transpose();
    return guess;
  }
  const Eigen::Vector3d x = InferLatentSequence(model, observed).latent.row(0).transpose();
  if (state_model.Name() == "manifold") {
    const ManifoldPoint m = model.LatentToManifold(x);
    guess.coordinates = Eigen::Vector3d(m.phase, m.gait, m.scale);
  } else {
    guess.coordinates = x;
  }
  return guess;
}

std::unique_ptr<GaitModel> ModelOnSkeleton(const GaitModel& model, const std::string& asf) {
  GaitModelData data = model.data();
  data.skeleton_asf = ReadTextFile(asf, "the subject's skeleton (ASF)");
  ParseAsf(data.skeleton_asf, asf);  // errors name the file itself
  data.skeleton_trial = fs::path(asf).stem().string();
  // Create parses the ASF and checks that the model's channels fit its bones and dofs.
  return GaitModel::Create(std::move(data), asf);
}

TrackJobResult RunTrackJob(const TrackJobOptions& o, const TrackProgress& progress) {
  const auto job_started = std::chrono::steady_clock::now();
  const auto finished = [&job_started](TrackJobResult* r) {
    r->wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - job_started).count();
  };
  // Everything that can be refused is, before the long part. The model and its pose table
  // are read while the sources open (given backgrounds read or learnt ones learnt, the
  // first frames read ahead): on a 4-camera clip each took about a quarter of a second on
  // one core while the other waited. A source's error is named first, then the model's.
  TrackerOptions tracker_options = o.tracker;
  if (!o.asf.empty()) tracker_options.known_size = true;
  PoseTableOptions table_options = tracker_options.table;
  table_options.threads = tracker_options.threads;
  const bool with_table = tracker_options.space == StateSpace::kModel;
  struct Prior {
    std::unique_ptr<GaitModel> model;
    std::shared_ptr<const PoseTable> table;
  };
  // The kept pose table is read on a thread of its own while the model is parsed: one after
  // the other they took 1.2 s before a 4-camera clip's first frame (0.45 s parsing the
  // model, 0.75 s reading the 68 MB table into a string and copying it out).
  std::future<std::unique_ptr<PoseTable>> kept_table;
  if (with_table) {
    kept_table = std::async(std::launch::async, [&o, table_options] {
      return ReadKeptPoseTable(o.model, o.asf, table_options, o.source.note);
    });
  }
  std::future<Prior> reading = std::async(std::launch::async, [&o, table_options, with_table, &kept_table] {
    Prior prior{ReadModelFile(o.model), nullptr};
    if (!o.asf.empty()) prior.model = ModelOnSkeleton(*prior.model, o.asf);
    if (with_table)
      prior.table = CachedPoseTable(*prior.model, o.model, o.asf, table_options, o.source.note, kept_table.get());
    return prior;
  });
  FrameSourceSpec spec = o.source;
  // A clip's overlays are drawn as the frames go by, its videos decoded on the reading
  // thread with the masks (after the run, decoding and encoding them took a tenth of its
  // wall time on a 4-camera clip).
  spec.clip_images = o.overlays && !o.out.empty();
  // A learnt background's masks are made at the working resolution, not brought to it.
  if (o.working.enabled) spec.mask_person_px = o.working.person_px;
  std::unique_ptr<FrameSource> made = MakeFrameSource(spec);
  const auto* clip = dynamic_cast<const ClipFrameSource*>(made.get());
  const auto* video = dynamic_cast<const VideoFrameSource*>(made.get());
  if (o.truth_start && !clip) ThrowInputError("--init truth", "needs a clip's ground truth (--clip)");
  if (o.truth_start && o.people) ThrowInputError("--init truth", "starts one person; --people all finds everyone");
  std::vector<cv::Mat> paintings = OccluderPaintings(o.source, made->cameras());
  if (!paintings.empty()) made = std::make_unique<OccludedSource>(std::move(made), std::move(paintings));
  // Reflections are cut at the input's size, before the working resolution is chosen from
  // the blobs' heights (a reflection doubles them). Not through a guessed camera: the cut
  // rests on the camera's height and tilt.
  const FloorReflectionSource* reflections = nullptr;
  if (o.source.cut_reflections && !o.source.camera_guess) {
    auto cut = std::make_unique<FloorReflectionSource>(std::move(made), video && video->live());
    reflections = cut.get();
    made = std::move(cut);
  }
  const auto source = std::make_unique<WorkingResolutionSource>(std::move(made), o.working, video && video->live());
  std::optional<OutputFolder> folder;
  if (!o.out.empty()) folder.emplace(o.out);

  // A chosen pixel is the full-size image's; the tracker sees the working resolution.
  if (tracker_options.person.kind == PersonPreference::Kind::kNearPixel) {
    const int c = tracker_options.person.camera;
    if (c >= static_cast<int>(source->scales().size()))
      ThrowInputError("--person", "camera " + std::to_string(c) + " of " + std::to_string(source->scales().size()));
    const Camera& full = source->full_cameras()[c];
    const Eigen::Vector2d& p = tracker_options.person.pixel;
    if (!(p.x() < full.width && p.y() < full.height)) {
      ThrowInputError("--person", "pixel " + std::to_string(static_cast<int>(p.x())) + "," +
                                      std::to_string(static_cast<int>(p.y())) + " is outside the first camera's " +
                                      std::to_string(full.width) + "x" + std::to_string(full.height) + " image");
    }
    tracker_options.person.pixel = (p.array() + 0.5) * source->scales()[c] - 0.5;
  }
  const Prior prior = reading.get();
  const std::unique_ptr<GaitModel>& model = prior.model;
  const std::shared_ptr<const PoseTable>& table = prior.table;
  // A live camera's estimates are given as they come, and a start from the truth is sure.
  if ((video && video->live()) || o.truth_start) tracker_options.start_backwards_s = 0;
  Tracker tracker(*model, source->cameras(), tracker_options, table);
  TrackJobResult result;
  TrackRun& run = result.run;
  run.model_path = o.model;
  for (const std::string* s : {&o.source.clip, &o.source.images}) {
    if (!s->empty()) run.source = *s;
  }
  for (const auto* list : {&o.source.videos, &o.source.devices})
    for (const std::string& v : *list) run.source += (run.source.empty() ? "" : ", ") + v;
  run.init = o.truth_start ? "truth" : "auto";
  run.coordinate_names = tracker.state_model().CoordinateNames();
  run.state_space = tracker.state_model().Name();
  run.cameras = source->full_cameras();
  result.working_cameras = source->cameras();
  run.fps = source->fps();
  run.options = tracker_options;
  result.live = video && video->live();
  // Frames that wait before they are tracked: the start's, and a live camera's learning
  // frames (tracked once the background is learnt from them).
  result.held_frames = tracker_options.start_frames +
                       (result.live && o.source.backgrounds.empty() ? o.source.foreground.learning_frames : 0);

  // Overlays are written as the frames go by.
  const fs::path dir = folder ? folder->partial() : fs::path();
  std::optional<OverlayVideos> overlays;
  if (folder && o.overlays) overlays.emplace(dir, run.cameras, run.fps, tracker.body(), model->skeleton());
  std::optional<MultiTracker> multi;
  if (o.people) multi.emplace(*model, source->cameras(), tracker_options, o.multi, table);
  const auto body_of = [&multi](int id) -> const BodyModel& { return multi->body(id); };
  // Files and folders are read ahead while the frame before is tracked; a live camera's
  // newest frame is taken when the tracker is ready for it.
  std::optional<PrefetchSource> ahead;
  if (!result.live) {
    ahead.emplace(source.get(), 2,
                  video ? std::function<int()>([video] { return video->skipped(); }) : std::function<int()>());
  }
  CountingSource frames_read(ahead ? static_cast<FrameSource*>(&*ahead) : source.get());
  FrameSource* frames = &frames_read;
  const auto skipped_so_far = [&] { return ahead ? ahead->lost() : video ? video->skipped() : 0; };
  const auto started = std::chrono::steady_clock::now();
  double latency_sum = 0;
  int latency_count = 0, frames_seen = 0;
  std::vector<ForegroundShare> shares(run.cameras.size());
  const auto on_frame = [&](const Frame& frame, TrackedFrame& f) {
    for (size_t c = 0; c < shares.size() && c < frame.masks.size() && !frame.dropped; ++c)
      if (!frame.masks[c].empty()) shares[c].Add(frame.masks[c]);
    if (result.live && !frame.dropped) {
      f.latency_ms = frame.latency_ms +
                     std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frame.ready).count();
      // The summary is of the steady state: the frames held for the start wait for it.
      if (++frames_seen > result.held_frames) {
        latency_sum += f.latency_ms;
        ++latency_count;
        result.max_latency_ms = std::max(result.max_latency_ms, f.latency_ms);
      }
    }
    if (progress) progress(f, frames_read.read(), frames->NumFrames(), skipped_so_far());
    if (folder && o.save_masks && !frame.dropped) {
      for (size_t c = 0; c < run.cameras.size(); ++c) {
        const fs::path path = dir / "masks" / run.cameras[c].name / ClipFrameName(frame.index);
        fs::create_directories(path.parent_path());
        if (!cv::imwrite(path.string(), frame.masks[c])) ThrowInputError(path.string(), "cannot write the mask");
      }
    }
    if (overlays && !o.people) {
      if (o.show) {
        o.show(overlays->AddAndDraw(frame, f));
      } else {
        overlays->Add(frame, f);
      }
    }
  };
  const auto stop = [&] {
    if (o.stop && o.stop->load()) return result.stopped = "interrupted", true;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (o.max_seconds > 0 && elapsed >= o.max_seconds) return result.stopped = "time limit reached", true;
    return false;
  };
  if (o.people) {
    struct HeldFrame {
      Frame frame;
      std::vector<std::pair<int, TrackedFrame>> people;
    };
    std::deque<HeldFrame> held;  // overlays not yet written, oldest first
    const auto write_held = [&] {
      overlays->AddPeople(held.front().frame, held.front().people, body_of);
      held.pop_front();
    };
    const auto on_people = [&](const Frame& frame, PeopleFrame& f) {
      // The progress line shows the frame as tracked when anyone in it is.
      TrackedFrame summary;
      summary.index = f.index;
      summary.time_s = f.time_s;
      summary.seconds = f.seconds;
      for (const PersonFrame& p : f.people)
        if (p.frame.status == TrackStatus::kTracked) summary.status = TrackStatus::kTracked;
      on_frame(frame, summary);
      if (!overlays) return;
      std::vector<std::pair<int, TrackedFrame>> people;
      for (const PersonFrame& p : f.people) people.emplace_back(p.id, p.frame);
      if (o.show) {  // live: shown now, without the frames before a confirmation
        o.show(overlays->AddPeople(frame, people, body_of, true));
        return;
      }
      // Written birth_window frames and start_backwards_s late, so that a person confirmed
      // now is drawn in the frames they were followed in before, and a birth's start as
      // gone back over (PeopleFrame::earlier), as poses.json has them: with the lead-in
      // before the birth, birth_window frames before a frame start_backwards_s old.
      for (const auto& [index, person] : f.earlier) {
        const int wanted = index, id = person.id;  // (clang 14 cannot capture a structured binding)
        const auto at = std::find_if(held.begin(), held.end(), [&](const HeldFrame& h) { return h.frame.index == wanted; });
        if (at == held.end()) continue;
        const auto same = std::find_if(at->people.begin(), at->people.end(), [&](const auto& p) { return p.first == id; });
        if (same != at->people.end()) {
          same->second = person.frame;
        } else {
          at->people.emplace_back(person.id, person.frame);
        }
        std::sort(at->people.begin(), at->people.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      }
      held.push_back({frame, std::move(people)});
      const size_t window = static_cast<size_t>(o.multi.birth_window);
      while (held.size() > window && frame.time_s - held[window].frame.time_s >= multi->tracker_options().start_backwards_s)
        write_held();
    };
    result.people = TrackPeople(frames, &*multi, on_people, stop);
    while (!held.empty()) write_held();
  } else if (o.truth_start) {
    tracker.StartAt(TruthGuess(clip->truth(), *model, tracker.state_model()));
    Frame frame;
    while (!stop() && frames->Next(&frame)) {
      run.frames.push_back(tracker.Step(frame));
      on_frame(frame, run.frames.back());
    }
  } else {
    run.frames = TrackSource(frames, &tracker, on_frame, stop);
  }
  if (ahead) ahead->Stop();  // the sources' counts below are the reading thread's
  if (reflections) result.reflection_frames = reflections->frames_cut();
  if (tracker.shadow_light().light()) {
    result.shadow_light_deg = tracker.shadow_light().Angles();
    result.shadow_light_frame = tracker.shadow_light_frame();
  } else if (multi && multi->shadow_light()) {
    result.shadow_light_deg = multi->shadow_light()->Angles();
    result.shadow_light_frame = multi->shadow_light_frame();
  }
  // Measured when every camera gave masks.
  if (std::none_of(shares.begin(), shares.end(), [](const ForegroundShare& s) { return s.empty(); }))
    for (ForegroundShare& s : shares) run.foreground_share.push_back(s.Median());
  for (const TrackedFrame& f : run.frames) run.tracking_seconds += f.seconds;
  for (const PeopleFrame& f : result.people) run.tracking_seconds += f.seconds;
  result.loop_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  if (video) {
    if (result.stopped.empty()) result.stopped = video->end_reason();
    result.skipped = video->skipped();
    result.unpaired = video->unpaired();
  }
  result.latency_frames = latency_count;
  if (latency_count) result.mean_latency_ms = latency_sum / latency_count;
  if (run.frames.empty() && result.people.empty()) {
    ThrowInputError(run.source, "no frame was tracked" + (result.stopped.empty() ? "" : " (" + result.stopped + ")"));
  }
  if (o.people) {
    FinishPeople(o, clip, *model, folder ? &*folder : nullptr, &overlays, &result);
    finished(&result);
    return result;
  }

  if (clip) {
    std::vector<Eigen::Matrix3Xd> truth;
    for (const TrackedFrame& f : run.frames) truth.push_back(clip->truth().frames[f.index].joints_mm);
    result.errors = EvaluateRun(run, model->skeleton(), truth, clip->truth().joint_names);
  }
  if (!folder) return finished(&result), result;

  // The results, all or none.
  OutputBatch batch;
  batch.Add(dir / "poses.json", FormatJson(PosesJson(run, model->skeleton(), result.errors)));
  const TrackedMotion motion = MakeTrackedMotion(run, *model);
  batch.Add(dir / "tracked.amc", FormatAmc(motion.motion, motion.skeleton));
  batch.Add(dir / "tracked.asf", motion.asf);
  batch.Add(dir / "tracked.bvh", FormatBvh(AcclaimToBvh(motion.skeleton, motion.motion)));
  if (result.errors) batch.Add(dir / "track.png", EncodePng(ErrorPlot(*result.errors, run), "track.png"));
  // The cameras as the run used them (given, guessed or calibrated from the walkers), so
  // that anyone can project poses.json into the images.
  for (const Camera& c : run.cameras) batch.Add(dir / (c.name + ".yaml"), FormatCameraYaml({c, true}));
  batch.Commit();
  if (overlays) overlays->Close();  // the videos written and closed before the folder moves
  folder->Commit();
  for (const char* name : {"poses.json", "tracked.amc", "tracked.asf", "tracked.bvh"}) {
    result.written.push_back(fs::path(o.out) / name);
  }
  if (result.errors) result.written.push_back(fs::path(o.out) / "track.png");
  for (const Camera& c : run.cameras) result.written.push_back(fs::path(o.out) / (c.name + ".yaml"));
  if (o.overlays)
    for (const Camera& c : run.cameras) result.written.push_back(fs::path(o.out) / ("overlay_" + c.name + ".avi"));
  if (o.save_masks) result.written.push_back(fs::path(o.out) / "masks");
  finished(&result);
  return result;
}

}  // namespace jgpm
