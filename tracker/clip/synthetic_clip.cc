#include "tracker/clip/synthetic_clip.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <limits>
#include <numbers>
#include <random>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "io/base/error.h"
#include "io/base/output_folder.h"
#include "io/base/text_reader.h"
#include "io/mocap/kinematics.h"
#include "tracker/body/ray_caster.h"
#include "tracker/clip/contact_sheet.h"
#include "tracker/clip/synthetic_background.h"

namespace jgpm {
namespace fs = std::filesystem;

bool ClipOptions::Check(std::string* why) const {
  if (!(fps > 0 && fps <= 1000)) {
    if (why) *why = "fps: expected a positive rate";
    return false;
  }
  if (max_frames < 0) {
    if (why) *why = "max frames: expected >= 0";
    return false;
  }
  if (!(calibration_error >= 0 && calibration_error <= 10)) {
    if (why) *why = "calibration error: expected a scale of 0 to 10";
    return false;
  }
  for (const ClipPause& p : pauses) {
    if (!p.Valid()) {
      if (why) *why = "pause: expected AT >= 0 s and 0 < FOR <= 60 s";
      return false;
    }
  }
  return rig.Check(why) && degradations.Check(why) && body.Check(why) && scene.Check(why);
}

std::string ClipSummary::BriefReport() const {
  char line[256];
  std::snprintf(line, sizeof line, "%d frames (%d dropped) x %zu camera(s) at %dx%d in %.1f s", frames,
                dropped, cameras.size(), cameras.empty() ? 0 : cameras[0].width,
                cameras.empty() ? 0 : cameras[0].height, seconds);
  return line;
}

namespace {

// The clip frames' poses of one walker: the source frame and joints (placed) of every
// clip frame it is in the scene.
struct WalkerTrack {
  double start_s = 0;                     // clip time of its motion's first frame
  std::vector<int> clip_frames, source_frames;
  std::vector<Eigen::Matrix3Xd> joints;
  int Find(int clip_frame) const {        // index into the above, -1 when not in the scene
    const auto it = std::lower_bound(clip_frames.begin(), clip_frames.end(), clip_frame);
    return it != clip_frames.end() && *it == clip_frame ? static_cast<int>(it - clip_frames.begin()) : -1;
  }
};

// BGR colour of each material; the first walker wears today's, the others other colours
// so that a viewer tells them apart.
cv::Vec3f MaterialColour(ClipMaterial material, int walker) {
  static const cv::Vec3f kTops[] = {{60, 140, 60}, {50, 60, 160}, {150, 150, 150}, {40, 160, 190},
                                    {130, 60, 120}, {200, 170, 90}, {60, 60, 60}};
  static const cv::Vec3f kBottoms[] = {{120, 80, 40}, {80, 90, 100}, {40, 40, 90}, {150, 140, 130}};
  if (walker > 0) {
    switch (material) {
      case ClipMaterial::kShirt:
      case ClipMaterial::kCoat:
      case ClipMaterial::kSkirt: return kTops[(walker - 1) % std::size(kTops)];
      case ClipMaterial::kTrousers: return kBottoms[(walker - 1) % std::size(kBottoms)];
      default: break;
    }
  }
  switch (material) {
    case ClipMaterial::kSkin: return {120, 150, 210};
    case ClipMaterial::kShirt: return {170, 90, 50};
    case ClipMaterial::kTrousers: return {60, 55, 60};
    case ClipMaterial::kShoes: return {35, 35, 40};
    case ClipMaterial::kCoat: return {70, 110, 150};
    case ClipMaterial::kSkirt: return {90, 60, 140};
    case ClipMaterial::kBag: return {40, 70, 90};
  }
  return {128, 128, 128};
}

void WriteImage(const fs::path& path, const cv::Mat& image) {
  if (!cv::imwrite(path.string(), image)) ThrowInputError(path.string(), "cannot write the image");
}

// What a user would paint as occluders in front of the walk: each object in the image
// (a connected region of objects_depth) that hid some walker in some frame, whole. Objects
// seen only behind the walkers (another camera's pillar) are left out, as a user would.
cv::Mat PaintedOccluders(const cv::Mat& objects_depth, const cv::Mat& hid_by_objects) {
  const cv::Mat objects = objects_depth < std::numeric_limits<float>::infinity();
  cv::Mat labels;
  const int count = cv::connectedComponents(objects, labels, 8, CV_32S);
  std::vector<uint8_t> keep(count, 0);
  for (int v = 0; v < labels.rows; ++v)
    for (int u = 0; u < labels.cols; ++u)
      if (hid_by_objects.at<uint8_t>(v, u)) keep[labels.at<int>(v, u)] = 255;
  keep[0] = 0;
  cv::Mat painted(objects.size(), CV_8UC1);
  for (int v = 0; v < labels.rows; ++v)
    for (int u = 0; u < labels.cols; ++u) painted.at<uint8_t>(v, u) = keep[labels.at<int>(v, u)];
  return painted;
}

// The walker's silhouette with the skeleton over it, cropped about him and enlarged to
// 160 x 240 (at 320 x 240 he is often under 100 px tall). The crop is an affine map of
// the image, so the camera of the tile is the same camera with scaled intrinsics.
// Each walker in the scene gets its skeleton drawn.
cv::Mat SheetTile(const std::vector<const Skeleton*>& skeletons, const Camera& camera, const cv::Mat& mask,
                  const std::vector<Eigen::Matrix3Xd>& joints) {
  constexpr int kWidth = 160, kHeight = 240;
  cv::Rect box = cv::boundingRect(mask);
  if (box.empty()) box = cv::Rect(0, 0, mask.cols, mask.rows);
  double h = std::max(40.0, 1.25 * box.height);
  h = std::max(h, 1.25 * box.width * kHeight / kWidth);
  const double scale = kHeight / h;
  const double x0 = box.x + 0.5 * (box.width - 1) - 0.5 * (kWidth - 1) / scale;
  const double y0 = box.y + 0.5 * (box.height - 1) - 0.5 * (kHeight - 1) / scale;
  const cv::Matx23d to_tile(scale, 0, -x0 * scale, 0, scale, -y0 * scale);
  cv::Mat grey, tile;
  cv::warpAffine(mask / 255 * 170 + 40, grey, to_tile, cv::Size(kWidth, kHeight), cv::INTER_NEAREST,
                 cv::BORDER_CONSTANT, cv::Scalar(25));
  cv::cvtColor(grey, tile, cv::COLOR_GRAY2BGR);
  Camera zoomed = camera;
  zoomed.fx *= scale;
  zoomed.fy *= scale;
  zoomed.cx = (camera.cx - x0) * scale;
  zoomed.cy = (camera.cy - y0) * scale;
  zoomed.width = kWidth;
  zoomed.height = kHeight;
  for (size_t w = 0; w < joints.size(); ++w) DrawSkeleton(*skeletons[w], zoomed, joints[w], &tile);
  return tile;
}

void CheckCameras(const std::vector<Camera>& cameras) {
  if (cameras.size() > 8) ThrowInputError("cameras", "at most 8");
  std::string why;
  for (size_t i = 0; i < cameras.size(); ++i) {
    const std::string& name = cameras[i].name;  // it names the clip's files
    if (!cameras[i].Check(&why)) ThrowInputError("camera " + name, why);
    if (name.empty() || name[0] == '.' ||
        name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-.") != std::string::npos)
      ThrowInputError("camera '" + name + "'", "a camera name may hold only letters, digits, '_', '-' and '.'");
    for (size_t k = 0; k < i; ++k)
      if (cameras[k].name == name) ThrowInputError("camera " + name, "two cameras share this name");
  }
}

// The colour frame: the room (CV_32FC3), clutter blobs behind the walker (`clutter`: 1 +
// blob index, 0 for none), the Lambert-shaded body.
void ComposeFrame(const cv::Mat& background, const BodyImage& body, const std::vector<cv::Vec3f>& colours,
                  const cv::Mat& clutter, const MovingClutter& blobs, cv::Mat* colour) {
  static const Eigen::Vector3d kLight = Eigen::Vector3d(0.4, 1.0, -0.3).normalized();
  background.copyTo(*colour);
  for (int v = 0; v < colour->rows; ++v) {
    cv::Vec3f* out = colour->ptr<cv::Vec3f>(v);
    const uint8_t* part = body.part.ptr<uint8_t>(v);
    const uint8_t* blob = clutter.ptr<uint8_t>(v);
    const cv::Vec3f* normal = body.normal.ptr<cv::Vec3f>(v);
    for (int u = 0; u < colour->cols; ++u) {
      if (part[u] != BodyImage::kNoPart) {
        const double lambert = std::max(0.0, kLight.dot(Eigen::Vector3d(normal[u][0], normal[u][1], normal[u][2])));
        out[u] = colours[part[u]] * static_cast<float>(0.35 + 0.65 * lambert);
      } else if (blob[u]) {
        const cv::Scalar& s = blobs.Colour(blob[u]);
        out[u] = cv::Vec3f(s[0], s[1], s[2]);
      }
    }
  }
}

std::vector<ClipBodyPart> BodyParts(const ClipBody& body) {
  std::vector<ClipBodyPart> parts;
  for (const ClipShape& s : body.shapes()) {
    parts.push_back({s.name, body.EndText(s.from, s.from_offset_mm), body.EndText(s.to, s.to_offset_mm),
                     s.radius_from_mm, s.radius_to_mm});
  }
  return parts;
}

std::vector<std::string> JointNames(const Skeleton& skeleton) {
  std::vector<std::string> names;
  for (const Bone& bone : skeleton.bones) names.push_back(bone.name);
  return names;
}

// The walker's poses in the clip's `frames` frames at `fps`; `first` is the first walker
// (nullptr for it), whose middle frame the delay counts from. InputError for a placed first
// walker with a delay.
WalkerTrack PlaceWalker(const ClipWalker& walker, int frames, double fps, const std::vector<ClipPause>& pauses,
                        const ClipWalker* first) {
  const Motion& motion = walker.motion;
  const ClipPlacement& place = walker.placement;
  const double source_fps = motion.frames_per_second;
  const auto middle_s = [](const Motion& m) { return 0.5 * (m.NumFrames() - 1) / m.frames_per_second; };
  WalkerTrack track;
  if (first == nullptr && place.placed && place.delay_s != 0)
    ThrowInputError(walker.source.amc, "the first walker's delay must be 0: the clip starts with its trial");
  if (first != nullptr && place.placed) track.start_s = middle_s(first->motion) + place.delay_s - middle_s(motion);
  const Kinematics kinematics(walker.skeleton);
  // Placed: the rotation about the vertical and the shift that take the middle frame's root
  // to `at`, heading `heading_deg`.
  Eigen::Matrix2d turn = Eigen::Matrix2d::Identity();
  Eigen::Vector2d from = Eigen::Vector2d::Zero(), to = Eigen::Vector2d::Zero();
  if (place.placed) {
    const auto root = [&](int f) {
      const Eigen::Matrix3Xd j = kinematics.Compute(motion.Frame(f));
      return Eigen::Vector2d(j(0, 0), j(2, 0));
    };
    const Eigen::Vector2d walk = root(motion.NumFrames() - 1) - root(0);
    const double along = walk.norm() > 300 ? std::atan2(walk.y(), walk.x()) : 0;
    const double angle = place.heading_deg * std::numbers::pi / 180 - along;
    turn << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
    from = root((motion.NumFrames() - 1) / 2);
    to = Eigen::Vector2d(place.at_x_mm, place.at_z_mm);
  }
  Eigen::Matrix3Xd joints;
  for (int k = 0; k < frames; ++k) {
    // Clip frame k shows the source frame nearest to its time.
    const long source = std::lround(TrialTime(k / fps - track.start_s, pauses) * source_fps);
    if (source < 0 || source >= motion.NumFrames()) continue;
    kinematics.Compute(motion.Frame(static_cast<int>(source)), &joints);
    if (place.placed) {
      for (int b = 0; b < joints.cols(); ++b) {
        const Eigen::Vector2d p = turn * (Eigen::Vector2d(joints(0, b), joints(2, b)) - from) + to;
        joints(0, b) = p.x();
        joints(2, b) = p.y();
      }
    }
    track.clip_frames.push_back(k);
    track.source_frames.push_back(static_cast<int>(source));
    track.joints.push_back(joints);
  }
  return track;
}

// The ground truth of the clip's frames (joints, times, drops) and what made them: the
// top level is the first walker's; `people` every walker's when there are several.
ClipGroundTruth GroundTruth(const std::vector<ClipWalker>& walkers, const std::vector<WalkerTrack>& tracks,
                            const std::vector<ClipBody>& bodies, const std::vector<Camera>& cameras,
                            const ClipOptions& options, const std::vector<bool>& dropped,
                            const std::vector<std::vector<std::vector<int>>>& visible_px) {
  const ClipWalker& first = walkers[0];
  ClipGroundTruth t;
  t.source_asf = first.source.asf;
  t.source_amc = first.source.amc;
  t.source_fps = first.motion.frames_per_second;
  t.fps = options.fps;
  t.image_width = cameras[0].width;
  t.image_height = cameras[0].height;
  t.seed = options.seed;
  t.degradations = options.degradations;
  t.body = first.body;
  t.body_parts = BodyParts(bodies[0]);
  t.joint_names = JointNames(first.skeleton);
  t.cameras = cameras;
  int video_frame = 0;
  for (size_t k = 0; k < dropped.size(); ++k) {
    ClipFrame f;
    f.time_s = k / options.fps;
    f.source_frame = tracks[0].source_frames[k];
    f.dropped = dropped[k];
    f.video_frame = dropped[k] ? -1 : video_frame++;
    f.joints_mm = tracks[0].joints[k];
    t.frames.push_back(std::move(f));
  }
  if (walkers.size() < 2) return t;
  for (size_t w = 0; w < walkers.size(); ++w) {
    ClipPerson p;
    p.id = static_cast<int>(w) + 1;
    p.source_asf = walkers[w].source.asf;
    p.source_amc = walkers[w].source.amc;
    p.body = walkers[w].body;
    p.body_parts = BodyParts(bodies[w]);
    p.joint_names = JointNames(walkers[w].skeleton);
    p.placement = walkers[w].placement;
    p.start_s = tracks[w].start_s;
    for (size_t i = 0; i < tracks[w].clip_frames.size(); ++i) {
      const int k = tracks[w].clip_frames[i];
      std::vector<int> seen(cameras.size(), 0);
      for (size_t c = 0; c < cameras.size(); ++c) seen[c] = visible_px[c][k][w];
      p.frames.push_back({k, tracks[w].source_frames[i], tracks[w].joints[i], seen});
    }
    t.people.push_back(std::move(p));
  }
  return t;
}

// The scene's walks for the rig and the occluders: every walker's poses, with the first
// walker's last pose last so that the walk's direction (first to last root) stays the
// first walker's.
std::vector<Eigen::Matrix3Xd> SceneJoints(const std::vector<WalkerTrack>& tracks) {
  std::vector<Eigen::Matrix3Xd> joints = tracks[0].joints;
  const Eigen::Matrix3Xd last = joints.back();
  for (size_t w = 1; w < tracks.size(); ++w) joints.insert(joints.end(), tracks[w].joints.begin(), tracks[w].joints.end());
  if (tracks.size() > 1) joints.push_back(last);
  return joints;
}

void CheckWalkers(const std::vector<ClipWalker>& walkers, const ClipOptions& options) {
  if (walkers.empty() || walkers.size() > 8) ThrowInputError("render options", "expected 1 to 8 walkers");
  for (const ClipWalker& w : walkers) {
    if (options.fps > w.motion.frames_per_second)
      ThrowInputError(w.source.amc, "the clip's fps " + FormatShortest(options.fps) + " exceeds the motion's " +
                                        FormatShortest(w.motion.frames_per_second));
    if (w.motion.NumFrames() == 0) ThrowInputError(w.source.amc, "the motion has no frames");
    const ClipPlacement& p = w.placement;
    if (p.placed && !(std::isfinite(p.at_x_mm) && std::isfinite(p.at_z_mm) && std::isfinite(p.heading_deg) &&
                      std::isfinite(p.delay_s)))
      ThrowInputError(w.source.amc, "its placement has a value that is not a finite number");
  }
  // The clip is the first walker's trial: its stops must fall within it.
  const Motion& first = walkers[0].motion;
  const double trial_s = (first.NumFrames() - 1) / first.frames_per_second;
  for (const ClipPause& p : options.pauses)
    if (p.at_s >= trial_s)
      ThrowInputError("--pause " + FormatShortest(p.at_s) + "," + FormatShortest(p.for_s),
                      "the trial lasts " + cv::format("%.2f", trial_s) + " s: a stop must begin within it");
}

}  // namespace

double TrialTime(double walker_s, const std::vector<ClipPause>& pauses) {
  std::vector<ClipPause> sorted = pauses;
  std::sort(sorted.begin(), sorted.end(), [](const ClipPause& a, const ClipPause& b) { return a.at_s < b.at_s; });
  double paused = 0;  // paused before walker_s
  for (const ClipPause& p : sorted) {
    if (walker_s - paused < p.at_s) break;
    if (walker_s - paused < p.at_s + p.for_s) return p.at_s;
    paused += p.for_s;
  }
  return walker_s - paused;
}

ClipBodyOptions WalkerBody(const ClipBodyOptions& first, int index) {
  ClipBodyOptions body = first;
  body.body_seed += static_cast<uint64_t>(index);
  return body;
}

ClipSummary RenderClip(const Skeleton& skeleton, const Motion& motion, const ClipSource& source,
                       std::vector<Camera> cameras, const ClipOptions& options,
                       const std::string& out_dir, const std::function<void(int, int)>& progress) {
  return RenderClip({ClipWalker{skeleton, motion, source, options.body, {}}}, std::move(cameras), options, out_dir,
                    progress);
}

ClipSummary RenderClip(const std::vector<ClipWalker>& walkers, std::vector<Camera> cameras,
                       const ClipOptions& options, const std::string& out_dir,
                       const std::function<void(int, int)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  std::string why;
  if (!options.Check(&why)) ThrowInputError("render options", why);
  CheckWalkers(walkers, options);
  CheckCameras(cameras);
  const size_t people = walkers.size();
  std::vector<ClipBody> bodies;
  size_t shapes = 0;
  for (const ClipWalker& w : walkers) {
    bodies.emplace_back(w.skeleton, w.body, w.source.asf);
    shapes += bodies.back().shapes().size();
  }
  if (shapes >= BodyImage::kNoPart)
    ThrowInputError("render options", "the walkers' bodies have " + std::to_string(shapes) +
                                          " shapes; the ray caster draws at most " +
                                          std::to_string(BodyImage::kNoPart - 1) + ": fewer walkers");

  // The clip is the first walker's trial: clip frame k is at time k / fps.
  const Motion& motion = walkers[0].motion;
  const double step = motion.frames_per_second / options.fps;
  double paused_s = 0;
  for (const ClipPause& p : options.pauses) paused_s += p.for_s;
  int frames = static_cast<int>(std::floor((motion.NumFrames() - 1) / step + paused_s * options.fps + 1e-9)) + 1;
  if (options.max_frames > 0) frames = std::min(frames, options.max_frames);
  std::vector<WalkerTrack> tracks;
  for (size_t w = 0; w < people; ++w)
    tracks.push_back(PlaceWalker(walkers[w], frames, options.fps, options.pauses, w == 0 ? nullptr : &walkers[0]));
  const std::vector<Eigen::Matrix3Xd> scene_joints = SceneJoints(tracks);
  if (cameras.empty()) cameras = MakeRig(scene_joints, options.rig, options.seed);
  // The cameras as a calibration would give them: written to the clip, used by the tracker.
  std::vector<Camera> calibrated = cameras;
  if (options.calibration_error > 0) {
    std::mt19937_64 calibration_rng(options.seed * 0xD1B54A32D192ED03ull + 7);
    for (Camera& c : calibrated) c = Miscalibrate(c, options.calibration_error, &calibration_rng);
  }
  const ClipScene scene(options.scene, cameras, scene_joints, options.seed);

  std::mt19937_64 random(options.seed);
  const ClipDegradations& deg = options.degradations;
  std::vector<bool> dropped(frames, false);
  std::bernoulli_distribution drop(deg.drop_rate);
  for (int k = 1; k < frames; ++k) dropped[k] = drop(random);

  // The clip is made in DIR.partial and moved into place when complete; whatever goes wrong
  // on the way (disk full, a codec missing), no half clip is left.
  OutputFolder folder(out_dir);
  const fs::path& partial = folder.partial();
  const ClipPaths files{partial};

  // The room's centre: the walks' middle. It holds every camera, 3 m high unless one is
  // higher.
  Eigen::Vector3d room = Eigen::Vector3d::Zero();
  int poses = 0;
  for (const WalkerTrack& track : tracks) {
    for (const Eigen::Matrix3Xd& j : track.joints) room += j.col(0);
    poses += static_cast<int>(track.joints.size());
  }
  room /= poses;
  room.y() = 0;
  double room_radius = 12000, wall_height = 3000;
  for (const Camera& c : cameras) {
    const Eigen::Vector3d at = c.CentreInWorld();
    room_radius = std::max(room_radius, std::hypot(at.x() - room.x(), at.z() - room.z()) + 3000);
    wall_height = std::max(wall_height, at.y() + 1000);
  }

  ClipSummary summary;
  summary.frames = frames;
  summary.dropped = static_cast<int>(std::count(dropped.begin(), dropped.end(), true));
  summary.cameras = calibrated;
  std::vector<std::vector<cv::Mat>> sheet_tiles(cameras.size());
  std::vector<int> sheet_frames;
  {
    std::vector<int> kept;
    for (int k = 0; k < frames; ++k) if (!dropped[k]) kept.push_back(k);
    const int n = std::min<int>(8, kept.size());
    for (int i = 0; i < n; ++i) sheet_frames.push_back(kept[(kept.size() - 1) * i / std::max(1, n - 1)]);
  }
  // visible_px[camera][frame][walker]: its pixels that nothing hides.
  std::vector<std::vector<std::vector<int>>> visible_px(
      cameras.size(), std::vector<std::vector<int>>(frames, std::vector<int>(people, 0)));
  std::vector<Capsule> capsules, placed;
  std::vector<cv::Vec3f> colours;  // per capsule drawn
  std::vector<uint8_t> owner;      // per capsule drawn: its walker
  std::vector<const Skeleton*> sheet_skeletons;
  std::vector<Eigen::Matrix3Xd> sheet_joints;
  const int total = frames * static_cast<int>(cameras.size());
  int done = 0;
  for (size_t c = 0; c < cameras.size(); ++c) {
    const Camera& camera = cameras[c];
    WriteCameraYaml({calibrated[c], true, -1}, files.CameraYaml(camera.name).string());
    fs::create_directories(files.MaskFolder(camera.name));
    fs::create_directories(files.ObservedFolder(camera.name));
    const fs::path video_path = files.Video(camera.name);
    cv::VideoWriter video(video_path.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), options.fps,
                          cv::Size(camera.width, camera.height));
    if (!video.isOpened())
      ThrowInputError(video_path.string(), "OpenCV cannot write an MJPG video here");
    const RayCaster caster(camera);
    // The room with the occluders in it, and how far away they are.
    cv::Mat room8 = RenderBackground(camera, room, room_radius, wall_height), objects_depth, objects_colour;
    scene.RenderObjects(caster, &objects_depth, &objects_colour);
    if (!scene.objects().empty()) {
      cv::Mat objects8;
      objects_colour.convertTo(objects8, CV_8UC3);
      objects8.copyTo(room8, objects_depth < std::numeric_limits<float>::infinity());
    }
    cv::Mat background;
    room8.convertTo(background, CV_32FC3);
    const double reflectance = options.scene.reflection;
    cv::Mat floor;  // where the walkers' shadow falls and a glossy floor shows their reflection
    if (options.scene.shadow || reflectance > 0) ClipScene::VisibleFloor(caster, objects_depth, room, room_radius, &floor);
    {
      // The empty room as the camera saw it before anyone walked in, as a lab records it.
      cv::Mat plate = room8.clone(), plate_noise(camera.height, camera.width, CV_32FC3), plate8;
      cv::RNG plate_rng(options.seed * 104729 + c);
      plate_rng.fill(plate_noise, cv::RNG::NORMAL, cv::Scalar::all(0), cv::Scalar::all(deg.sensor_noise));
      plate += plate_noise;
      plate.convertTo(plate8, CV_8UC3);
      fs::create_directories(files.Background(camera.name).parent_path());
      WriteImage(files.Background(camera.name), plate8);
    }
    // Each camera's own random stream, so adding a camera does not change the others.
    std::mt19937_64 rng(options.seed * 1000003 + c);
    MovingClutter clutter(deg.clutter_blobs, camera.width, camera.height, &rng);
    // With occluders, things also pass in front of the walker (as many as the occluders,
    // from their own random stream).
    std::mt19937_64 passer_rng(options.seed * 0x94D049BB133111EBull + c);
    MovingClutter passers(options.scene.occluders, camera.width, camera.height, &passer_rng);
    BodyImage image;
    cv::Mat colour(camera.height, camera.width, CV_32FC3), noise(camera.height, camera.width, CV_32FC3);
    cv::Mat frame8, clutter_mask(camera.height, camera.width, CV_8UC1), passer_mask(camera.height, camera.width, CV_8UC1);
    cv::Mat shadow, shadowed, reflected, reflection_seen, mirror_colour;
    BodyImage mirror;
    const cv::Mat no_clutter = cv::Mat::zeros(camera.height, camera.width, CV_8UC1);
    cv::Mat hid_by_objects = cv::Mat::zeros(camera.height, camera.width, CV_8UC1);
    cv::RNG cv_rng(options.seed * 7919 + c);
    for (int k = 0; k < frames; ++k) {
      clutter.Step();  // blobs move on through dropped frames
      passers.Step();
      if (dropped[k]) {
        if (progress) progress(++done, total);
        continue;
      }
      // Everyone in the scene, drawn together so that they hide one another.
      capsules.clear();
      colours.clear();
      owner.clear();
      sheet_skeletons.clear();
      sheet_joints.clear();
      for (size_t w = 0; w < people; ++w) {
        const int at = tracks[w].Find(k);
        if (at < 0) continue;
        bodies[w].Place(tracks[w].joints[at], &placed);
        capsules.insert(capsules.end(), placed.begin(), placed.end());
        for (const ClipShape& shape : bodies[w].shapes()) {
          colours.push_back(MaterialColour(shape.material, static_cast<int>(w)));
          owner.push_back(static_cast<uint8_t>(w));
        }
        sheet_skeletons.push_back(&walkers[w].skeleton);
        sheet_joints.push_back(tracks[w].joints[at]);
      }
      caster.Render(capsules, &image);
      // What can be seen of the walkers: not what an occluder or a passer hides.
      passers.Draw(&passer_mask);
      const cv::Mat behind_objects = image.depth_mm > objects_depth;  // no body: depth 0, never behind
      if (!scene.objects().empty()) hid_by_objects |= behind_objects;
      const cv::Mat hidden = behind_objects | (passer_mask != 0);
      image.part.setTo(BodyImage::kNoPart, hidden);
      const cv::Mat mask = image.Mask();
      for (int v = 0; v < image.part.rows; ++v) {
        const uint8_t* part = image.part.ptr<uint8_t>(v);
        for (int u = 0; u < image.part.cols; ++u)
          if (part[u] != BodyImage::kNoPart) ++visible_px[c][k][owner[part[u]]];
      }
      // Colour: room (with the walkers' shadows), clutter, shaded bodies, passers, then the
      // light and the sensor's noise.
      clutter.Draw(&clutter_mask);
      scene.RenderShadow(caster, capsules, floor, &shadow);
      const cv::Mat* room_now = &background;
      if (options.scene.shadow) {
        background.copyTo(shadowed);
        cv::multiply(shadowed, cv::Scalar::all(scene.shadow_gain()), shadowed);
        background.copyTo(shadowed, shadow == 0);
        room_now = &shadowed;
      }
      if (reflectance > 0) {
        // The walkers mirrored in the floor, seen where the floor is, blended into it.
        caster.Render(MirroredInFloor(capsules), &mirror);
        mirror.part.setTo(BodyImage::kNoPart, floor == 0);
        ComposeFrame(*room_now, mirror, colours, no_clutter, clutter, &mirror_colour);
        cv::addWeighted(*room_now, 1 - reflectance, mirror_colour, reflectance, 0, reflected);
        cv::Mat change, channels[3];
        cv::absdiff(reflected, *room_now, change);
        cv::split(change, channels);
        reflection_seen = cv::max(cv::max(channels[0], channels[1]), channels[2]) > kReflectionSeenLevels;
        room_now = &reflected;
      }
      ComposeFrame(*room_now, image, colours, clutter_mask, clutter, &colour);
      for (int v = 0; v < colour.rows; ++v) {
        const uint8_t* passer = passer_mask.ptr<uint8_t>(v);
        cv::Vec3f* out = colour.ptr<cv::Vec3f>(v);
        for (int u = 0; u < colour.cols; ++u) {
          if (!passer[u]) continue;
          const cv::Scalar& s = passers.Colour(passer[u]);
          out[u] = cv::Vec3f(s[0], s[1], s[2]);
        }
      }
      colour *= LightingGain(frames > 1 ? static_cast<double>(k) / (frames - 1) : 0, deg.lighting_gain);
      if (deg.sensor_noise > 0) {
        cv_rng.fill(noise, cv::RNG::NORMAL, cv::Scalar::all(0), cv::Scalar::all(deg.sensor_noise));
        colour += noise;
      }
      colour.convertTo(frame8, CV_8UC3);
      video.write(frame8);
      WriteImage(files.Mask(camera.name, k), mask);
      // The observed mask: degraded, with the clutter and passers, and the shadow that a
      // segmentation without shadow removal keeps.
      cv::Mat observed = DegradeMask(mask, options.scene.occluders > 0 ? (clutter_mask | passer_mask) : clutter_mask,
                                     deg, &rng);
      if (options.scene.shadow) observed.setTo(255, shadow);
      if (reflectance > 0) observed.setTo(255, reflection_seen);
      WriteImage(files.ObservedMask(camera.name, k), observed);
      if (options.contact_sheet && std::find(sheet_frames.begin(), sheet_frames.end(), k) != sheet_frames.end()) {
        sheet_tiles[c].push_back(SheetTile(sheet_skeletons, camera, mask, sheet_joints));
      }
      if (progress) progress(++done, total);
    }
    video.release();
    if (!scene.objects().empty()) {
      fs::create_directories(files.Occluders(camera.name).parent_path());
      WriteImage(files.Occluders(camera.name), PaintedOccluders(objects_depth, hid_by_objects));
    }
  }
  if (options.contact_sheet && !sheet_frames.empty()) {
    std::vector<cv::Mat> tiles;
    std::vector<std::string> labels;
    for (size_t c = 0; c < cameras.size(); ++c)
      for (size_t i = 0; i < sheet_tiles[c].size(); ++i) {
        tiles.push_back(sheet_tiles[c][i]);
        labels.push_back(cameras[c].name + " frame " + std::to_string(sheet_frames[i]));
      }
    WriteImage(files.ContactSheet(), TileImages(tiles, labels, static_cast<int>(sheet_frames.size())));
  }

  ClipGroundTruth truth = GroundTruth(walkers, tracks, bodies, calibrated, options, dropped, visible_px);
  truth.rig = options.rig.kind;
  truth.calibration_error = options.calibration_error;
  truth.shadow = options.scene.shadow;
  truth.reflection = options.scene.reflection;
  for (const SceneObject& o : scene.objects()) truth.occluders.push_back(o.kind);
  if (options.calibration_error > 0) truth.render_cameras = cameras;
  WriteFileAtomic(files.GroundTruth(), FormatGroundTruth(truth));

  folder.Commit();
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace jgpm
