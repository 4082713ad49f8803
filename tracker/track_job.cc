#include "tracker/track_job.h"

#include <cmath>

#include <Eigen/Geometry>
#include <opencv2/videoio.hpp>

#include "io/amc.h"
#include "io/asf.h"
#include "io/bvh.h"
#include "io/bvh_conversion.h"
#include "io/error.h"
#include "io/json_file.h"
#include "io/output_batch.h"
#include "io/output_folder.h"
#include "io/text_reader.h"
#include "prior/inference.h"
#include "prior/model_file.h"
#include "prior/png_file.h"
#include "tracker/clip_source.h"

namespace jgpm {
namespace fs = std::filesystem;
namespace {

constexpr double kPi = 3.14159265358979323846;

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
  guess.heading_std_rad = 3 * kPi / 180;
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

TrackJobResult RunTrackJob(const TrackJobOptions& o, const std::function<void(const TrackedFrame&, int total)>& progress) {
  // Everything that can be refused is, before the long part.
  std::unique_ptr<GaitModel> model = ReadModelFile(o.model);
  TrackerOptions tracker_options = o.tracker;
  if (!o.asf.empty()) {
    model = ModelOnSkeleton(*model, o.asf);
    tracker_options.known_size = true;
  }
  ClipFrameSourceOptions source_options;
  source_options.cameras = o.cameras;
  source_options.exact_masks = o.exact_masks;
  source_options.max_frames = o.max_frames;
  ClipFrameSource source(o.clip, source_options);
  std::optional<OutputFolder> folder;
  if (!o.out.empty()) folder.emplace(o.out);

  Tracker tracker(*model, source.cameras(), tracker_options);
  TrackJobResult result;
  TrackRun& run = result.run;
  run.model_path = o.model;
  run.source = o.clip;
  run.init = o.truth_start ? "truth" : "auto";
  run.coordinate_names = tracker.state_model().CoordinateNames();
  run.state_space = tracker.state_model().Name();
  run.cameras = source.cameras();
  run.fps = source.fps();
  run.options = tracker_options;

  if (o.truth_start) {
    tracker.StartAt(TruthGuess(source.truth(), *model, tracker.state_model()));
    Frame frame;
    while (source.Next(&frame)) {
      run.frames.push_back(tracker.Step(frame));
      if (progress) progress(run.frames.back(), source.NumFrames());
    }
  } else {
    run.frames = TrackSource(&source, &tracker, progress);
  }
  for (const TrackedFrame& f : run.frames) run.tracking_seconds += f.seconds;

  std::vector<Eigen::Matrix3Xd> truth;
  for (const TrackedFrame& f : run.frames) truth.push_back(source.truth().frames[f.index].joints_mm);
  result.errors = EvaluateRun(run, model->skeleton(), truth, source.truth().joint_names);
  if (!folder) return result;

  // The results, all or none.
  const fs::path& dir = folder->partial();
  OutputBatch batch;
  batch.Add(dir / "poses.json", FormatJson(PosesJson(run, model->skeleton(), result.errors)));
  const TrackedMotion motion = MakeTrackedMotion(run, *model);
  batch.Add(dir / "tracked.amc", FormatAmc(motion.motion, motion.skeleton));
  batch.Add(dir / "tracked.asf", motion.asf);
  batch.Add(dir / "tracked.bvh", FormatBvh(AcclaimToBvh(motion.skeleton, motion.motion)));
  batch.Add(dir / "track.png", EncodePng(ErrorPlot(*result.errors, run), "track.png"));
  batch.Commit();
  if (o.overlays) {
    // A second pass over the clip for its video frames (kept out of the tracking time).
    source_options.with_images = true;
    ClipFrameSource images(o.clip, source_options);
    std::vector<cv::VideoWriter> videos;
    for (const Camera& camera : run.cameras) {
      const fs::path path = dir / ("overlay_" + camera.name + ".avi");
      videos.emplace_back(path.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), run.fps,
                          cv::Size(camera.width, camera.height));
      if (!videos.back().isOpened()) ThrowInputError(path.string(), "OpenCV cannot write an MJPG video here");
    }
    Frame frame;
    std::vector<cv::Mat> last(run.cameras.size());
    Eigen::Matrix3Xd joints;
    std::vector<Capsule> capsules;
    for (const TrackedFrame& f : run.frames) {
      if (!images.Next(&frame)) break;
      capsules.clear();
      if (f.state.size()) {
        tracker.body().Place(f.joints_mm, &capsules);
        for (Capsule& c : capsules) c.radius_from_mm *= f.size, c.radius_to_mm *= f.size;
      }
      for (size_t c = 0; c < run.cameras.size(); ++c) {
        if (!frame.dropped) last[c] = frame.images[c];
        cv::Mat shown = frame.dropped && !last[c].empty() ? cv::Mat(last[c] * 0.5) : last[c];
        videos[c].write(OverlayFrame(shown, run.cameras[c], f, capsules, model->skeleton()));
      }
    }
  }
  folder->Commit();
  for (const char* name : {"poses.json", "tracked.amc", "tracked.asf", "tracked.bvh", "track.png"}) {
    result.written.push_back(fs::path(o.out) / name);
  }
  if (o.overlays)
    for (const Camera& c : run.cameras) result.written.push_back(fs::path(o.out) / ("overlay_" + c.name + ".avi"));
  return result;
}

}  // namespace jgpm
