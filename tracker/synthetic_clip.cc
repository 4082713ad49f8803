#include "tracker/synthetic_clip.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "io/error.h"
#include "io/json_file.h"
#include "io/kinematics.h"
#include "io/text_reader.h"
#include "tracker/contact_sheet.h"
#include "tracker/ray_caster.h"
#include "tracker/synthetic_background.h"

namespace jgpm {
namespace fs = std::filesystem;

bool RigOptions::Check(std::string* why) const {
  auto fail = [&](const std::string& what) { if (why) *why = what; return false; };
  if (num_cameras < 1 || num_cameras > 4) return fail("cameras: expected 1 to 4");
  if (width < 32 || height < 32 || width > 4096 || height > 4096)
    return fail("image size: expected 32 to 4096 pixels a side");
  if (!(ring_radius_mm >= 1000 && ring_radius_mm <= 50000)) return fail("ring radius: expected 1000 to 50000 mm");
  if (!(camera_height_mm > 0 && camera_height_mm < 10000)) return fail("camera height: expected 0 to 10000 mm");
  return true;
}

bool ClipDegradations::Check(std::string* why) const {
  auto fail = [&](const std::string& what) { if (why) *why = what; return false; };
  if (!(sensor_noise >= 0 && sensor_noise <= 100)) return fail("sensor noise: expected 0 to 100 grey levels");
  if (!(mask_noise_px >= 0 && mask_noise_px <= 20)) return fail("mask noise: expected 0 to 20 px");
  if (holes < 0 || holes > 100) return fail("holes: expected 0 to 100 per frame");
  if (clutter_blobs < 0 || clutter_blobs > 50) return fail("clutter: expected 0 to 50 blobs");
  if (!(lighting_gain >= 0.1 && lighting_gain <= 3)) return fail("lighting gain: expected 0.1 to 3");
  if (!(drop_rate >= 0 && drop_rate < 1)) return fail("drop rate: expected 0 <= rate < 1");
  return true;
}

bool ClipDegradations::Any() const {
  return mask_noise_px > 0 || holes > 0 || clutter_blobs > 0 || lighting_gain != 1 || drop_rate > 0;
}

bool ClipOptions::Check(std::string* why) const {
  if (!(fps > 0 && fps <= 1000)) {
    if (why) *why = "fps: expected a positive rate";
    return false;
  }
  if (max_frames < 0) {
    if (why) *why = "max frames: expected >= 0";
    return false;
  }
  return rig.Check(why) && degradations.Check(why) && body.Check(why);
}

std::vector<Camera> DefaultRig(const std::vector<Eigen::Matrix3Xd>& joints, const RigOptions& options) {
  JGPM_CHECK(!joints.empty() && options.Check(nullptr));
  // The walk's centre and direction on the floor, from the root's path.
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const Eigen::Matrix3Xd& j : joints) {
    const Eigen::Vector2d root(j(0, 0), j(2, 0));
    lo = lo.cwiseMin(root);
    hi = hi.cwiseMax(root);
  }
  const Eigen::Vector2d centre = 0.5 * (lo + hi);
  Eigen::Vector2d walk(joints.back()(0, 0) - joints.front()(0, 0), joints.back()(2, 0) - joints.front()(2, 0));
  walk = walk.norm() > 300 ? walk.normalized() : Eigen::Vector2d(0, 1);
  const Eigen::Vector2d side(walk.y(), -walk.x());
  // A camera in line with the walk must stay ~2 m clear of the walker's nearest point.
  double reach = 0;
  for (const Eigen::Matrix3Xd& j : joints)
    for (int c = 0; c < j.cols(); ++c) reach = std::max(reach, (Eigen::Vector2d(j(0, c), j(2, c)) - centre).norm());
  const double radius = std::max(options.ring_radius_mm, reach + 2000);
  static const std::vector<std::vector<double>> kAzimuthsDeg = {
      {90}, {90, 0}, {90, 210, 330}, {90, 0, 270, 180}};
  std::vector<Camera> cameras;
  for (double azimuth : kAzimuthsDeg[options.num_cameras - 1]) {
    const double a = azimuth * M_PI / 180;
    const Eigen::Vector2d at = centre + radius * (std::cos(a) * walk + std::sin(a) * side);
    Camera camera = LookAtCamera("cam" + std::to_string(cameras.size()), options.width, options.height,
                                 1.0, {at.x(), options.camera_height_mm, at.y()},
                                 {centre.x(), 1000, centre.y()});
    // Largest focal length with every joint, padded by 250 mm (half a body's width) and a
    // 3 px border, in view.
    constexpr double kPadMm = 250, kBorderPx = 3;
    double tan_x = 1e-6, tan_y = 1e-6;
    for (const Eigen::Matrix3Xd& j : joints)
      for (int c = 0; c < j.cols(); ++c) {
        const Eigen::Vector3d p = camera.ToCamera(j.col(c));
        const double z = std::max(p.z() - kPadMm, 100.0);
        tan_x = std::max(tan_x, (std::abs(p.x()) + kPadMm) / z);
        tan_y = std::max(tan_y, (std::abs(p.y()) + kPadMm) / z);
      }
    const double f = std::min((options.width / 2.0 - kBorderPx) / tan_x, (options.height / 2.0 - kBorderPx) / tan_y);
    camera.fx = camera.fy = f;
    cameras.push_back(camera);
  }
  return cameras;
}

std::string ClipSummary::BriefReport() const {
  char line[256];
  std::snprintf(line, sizeof line, "%d frames (%d dropped) x %zu camera(s) at %dx%d in %.1f s", frames,
                dropped, cameras.size(), cameras.empty() ? 0 : cameras[0].width,
                cameras.empty() ? 0 : cameras[0].height, seconds);
  return line;
}

namespace {

// BGR colour of each material.
cv::Vec3f MaterialColour(BodyMaterial material) {
  switch (material) {
    case BodyMaterial::kSkin: return {120, 150, 210};
    case BodyMaterial::kShirt: return {170, 90, 50};
    case BodyMaterial::kTrousers: return {60, 55, 60};
    case BodyMaterial::kShoes: return {35, 35, 40};
  }
  return {128, 128, 128};
}

// A coloured ellipse drifting across the image, bouncing at the borders.
struct Blob {
  cv::Point2d at, velocity;
  cv::Size2d axes;
  double angle_deg;
  cv::Scalar colour;
};

// Brightness gain at clip time fraction s in [0, 1]: 1, then a ramp over the middle third.
double Gain(double s, double final_gain) {
  const double r = std::clamp((s - 1.0 / 3) * 3, 0.0, 1.0);
  return 1 + (final_gain - 1) * r;
}

void CheckOutputFolder(const fs::path& out) {
  std::error_code ec;
  if (fs::exists(out, ec)) {
    if (!fs::is_directory(out, ec)) ThrowInputError(out.string(), "exists and is not a folder");
    if (!fs::is_empty(out, ec))
      ThrowInputError(out.string(), "exists and is not empty (choose a new --out, or remove it)");
  }
}

void WriteImage(const fs::path& path, const cv::Mat& image) {
  if (!cv::imwrite(path.string(), image)) ThrowInputError(path.string(), "cannot write the image");
}

std::string FrameName(int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "%06d.png", frame);
  return name;
}

nlohmann::json CameraJson(const Camera& c) {
  nlohmann::json r = nlohmann::json::array();
  for (int i = 0; i < 3; ++i) r.push_back({c.cam_from_world_rotation(i, 0), c.cam_from_world_rotation(i, 1), c.cam_from_world_rotation(i, 2)});
  return {{"name", c.name}, {"yaml", c.name + ".yaml"}, {"video", c.name + ".avi"},
          {"masks", "masks/" + c.name}, {"observed_masks", "observed/" + c.name},
          {"image_width", c.width}, {"image_height", c.height},
          {"fx", c.fx}, {"fy", c.fy}, {"cx", c.cx}, {"cy", c.cy}, {"distortion", c.distortion},
          {"cam_from_world_rotation", r},
          {"cam_from_world_translation_mm", {c.cam_from_world_translation_mm.x(), c.cam_from_world_translation_mm.y(), c.cam_from_world_translation_mm.z()}}};
}

// The walker's silhouette with the skeleton over it, cropped about him and enlarged to
// 160 x 240 (at 320 x 240 he is often under 100 px tall). The crop is an affine map of
// the image, so the camera of the tile is the same camera with scaled intrinsics.
cv::Mat SheetTile(const Skeleton& skeleton, const Camera& camera, const cv::Mat& mask,
                  const Eigen::Matrix3Xd& joints) {
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
  DrawSkeleton(skeleton, zoomed, joints, &tile);
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

// The colour frame: the room, clutter blobs behind the walker (`clutter`: 1 + blob index,
// 0 for none), the Lambert-shaded body.
void ComposeFrame(const cv::Mat& background, const BodyImage& body, const std::vector<cv::Vec3f>& colours,
                  const cv::Mat& clutter, const std::vector<Blob>& blobs, cv::Mat* colour) {
  static const Eigen::Vector3d kLight = Eigen::Vector3d(0.4, 1.0, -0.3).normalized();
  background.convertTo(*colour, CV_32FC3);
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
        const cv::Scalar& s = blobs[blob[u] - 1].colour;
        out[u] = cv::Vec3f(s[0], s[1], s[2]);
      }
    }
  }
}

// The mask as a segmentation would deliver it: eroded or dilated, holed, with the clutter.
cv::Mat DegradeMask(const cv::Mat& mask, const cv::Mat& clutter, const ClipDegradations& deg,
                    std::mt19937_64* rng) {
  std::uniform_real_distribution<double> uniform(0, 1);
  cv::Mat observed = mask.clone();
  if (deg.mask_noise_px > 0) {
    const int r = static_cast<int>(std::lround(deg.mask_noise_px * uniform(*rng)));
    if (r > 0) {
      const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * r + 1, 2 * r + 1));
      if (uniform(*rng) < 0.5) cv::erode(observed, observed, kernel);
      else cv::dilate(observed, observed, kernel);
    }
  }
  if (deg.holes > 0) {
    std::vector<cv::Point> inside;
    cv::findNonZero(mask, inside);
    for (int h = 0; h < deg.holes && !inside.empty(); ++h) {
      const cv::Point at = inside[static_cast<size_t>(uniform(*rng) * inside.size()) % inside.size()];
      cv::circle(observed, at, 2 + static_cast<int>(4 * uniform(*rng)), cv::Scalar(0), -1);
    }
  }
  observed.setTo(255, clutter);
  return observed;
}

// The clip's frames: which source frame each shows, its joints, whether it was dropped.
struct Sampling {
  std::vector<int> source_frame;
  std::vector<Eigen::Matrix3Xd> joints;
  std::vector<bool> dropped;
  int size() const { return static_cast<int>(joints.size()); }
};

nlohmann::json GroundTruth(const Skeleton& skeleton, const Motion& motion, const ClipSource& source,
                           const std::vector<Camera>& cameras, const ClipOptions& options,
                           const BodyModel& body, const Sampling& sampling) {
  const ClipDegradations& deg = options.degradations;
  nlohmann::json truth;
  truth["format"] = "jgpm synthetic clip";
  truth["version"] = 1;
  truth["source"] = {{"asf", source.asf}, {"amc", source.amc}, {"fps", motion.frames_per_second}};
  truth["fps"] = options.fps;
  truth["image_width"] = cameras[0].width;
  truth["image_height"] = cameras[0].height;
  truth["seed"] = options.seed;
  truth["degradations"] = {{"sensor_noise", deg.sensor_noise}, {"mask_noise_px", deg.mask_noise_px},
                           {"holes", deg.holes}, {"clutter_blobs", deg.clutter_blobs},
                           {"lighting_gain", deg.lighting_gain}, {"drop_rate", deg.drop_rate}};
  nlohmann::json parts = nlohmann::json::array();
  for (const BodyPart& p : body.parts())
    parts.push_back({{"name", p.name}, {"from", skeleton.bones[p.from_joint].name},
                     {"to", skeleton.bones[p.to_joint].name}, {"radius_from_mm", p.radius_from_mm},
                     {"radius_to_mm", p.radius_to_mm}});
  truth["body_model"] = {{"width_scale", options.body.width_scale}, {"parts", parts}};
  nlohmann::json joint_names = nlohmann::json::array();
  for (const Bone& bone : skeleton.bones) joint_names.push_back(bone.name);
  truth["joint_names"] = joint_names;
  truth["joints_note"] = "joints_mm[j] is the end of bone j (the root: its position), world y up, mm";
  nlohmann::json cams = nlohmann::json::array();
  for (const Camera& c : cameras) cams.push_back(CameraJson(c));
  truth["cameras"] = cams;
  nlohmann::json frame_list = nlohmann::json::array();
  int video_frame = 0;
  for (int k = 0; k < sampling.size(); ++k) {
    const Eigen::Matrix3Xd& joints = sampling.joints[k];
    nlohmann::json j = nlohmann::json::array();
    for (int b = 0; b < joints.cols(); ++b)  // to 0.01 mm
      j.push_back({std::round(joints(0, b) * 100) / 100, std::round(joints(1, b) * 100) / 100,
                   std::round(joints(2, b) * 100) / 100});
    const bool dropped = sampling.dropped[k];
    frame_list.push_back({{"frame", k}, {"time_s", k / options.fps}, {"source_frame", sampling.source_frame[k]},
                          {"dropped", dropped},
                          {"video_frame", dropped ? nlohmann::json(nullptr) : nlohmann::json(video_frame++)},
                          {"joints_mm", j}});
  }
  truth["frames"] = frame_list;
  return truth;
}

}  // namespace

ClipSummary RenderClip(const Skeleton& skeleton, const Motion& motion, const ClipSource& source,
                       std::vector<Camera> cameras, const ClipOptions& options,
                       const std::string& out_dir, const std::function<void(int, int)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  std::string why;
  if (!options.Check(&why)) ThrowInputError("render options", why);
  if (options.fps > motion.frames_per_second)
    ThrowInputError("render options", "fps " + FormatShortest(options.fps) + " exceeds the motion's " +
                                          FormatShortest(motion.frames_per_second));
  if (motion.NumFrames() == 0) ThrowInputError(source.amc, "the motion has no frames");
  fs::path out = fs::path(out_dir).lexically_normal();
  if (!out.has_filename()) out = out.parent_path();  // "DIR/"
  CheckOutputFolder(out);
  CheckCameras(cameras);

  // Clip frame k shows the source frame nearest to time k / fps.
  const double step = motion.frames_per_second / options.fps;
  int frames = static_cast<int>(std::floor((motion.NumFrames() - 1) / step + 1e-9)) + 1;
  if (options.max_frames > 0) frames = std::min(frames, options.max_frames);
  const Kinematics kinematics(skeleton);
  Sampling sampling;
  sampling.source_frame.resize(frames);
  sampling.joints.resize(frames);
  for (int k = 0; k < frames; ++k) {
    sampling.source_frame[k] = std::min(motion.NumFrames() - 1, static_cast<int>(std::lround(k * step)));
    kinematics.Compute(motion.Frame(sampling.source_frame[k]), &sampling.joints[k]);
  }
  const std::vector<Eigen::Matrix3Xd>& joints = sampling.joints;
  if (cameras.empty()) cameras = DefaultRig(joints, options.rig);
  const BodyModel body(skeleton, options.body, source.asf);

  std::mt19937_64 random(options.seed);
  const ClipDegradations& deg = options.degradations;
  sampling.dropped.assign(frames, false);
  std::bernoulli_distribution drop(deg.drop_rate);
  for (int k = 1; k < frames; ++k) sampling.dropped[k] = drop(random);
  const std::vector<bool>& dropped = sampling.dropped;

  const fs::path partial = out.string() + ".partial";
  std::error_code ec;
  fs::remove_all(partial, ec);
  fs::create_directories(partial, ec);
  if (ec) ThrowInputError(partial.string(), "cannot create the folder (" + ec.message() + ")");
  // Whatever goes wrong from here on (disk full, a codec missing), no half clip is left.
  struct RemoveUnlessDone {
    fs::path path;
    bool done = false;
    ~RemoveUnlessDone() {
      std::error_code ignored;
      if (!done) fs::remove_all(path, ignored);
    }
  } cleanup{partial};

  // The room's centre: the walk's middle.
  Eigen::Vector3d room = Eigen::Vector3d::Zero();
  for (const Eigen::Matrix3Xd& j : joints) room += j.col(0);
  room /= frames;
  room.y() = 0;

  ClipSummary summary;
  summary.frames = frames;
  summary.dropped = static_cast<int>(std::count(dropped.begin(), dropped.end(), true));
  summary.cameras = cameras;
  std::vector<std::vector<cv::Mat>> sheet_tiles(cameras.size());
  std::vector<int> sheet_frames;
  {
    std::vector<int> kept;
    for (int k = 0; k < frames; ++k) if (!dropped[k]) kept.push_back(k);
    const int n = std::min<int>(8, kept.size());
    for (int i = 0; i < n; ++i) sheet_frames.push_back(kept[(kept.size() - 1) * i / std::max(1, n - 1)]);
  }
  std::vector<cv::Vec3f> colours;
  for (const BodyPart& part : body.parts()) colours.push_back(MaterialColour(part.material));
  std::vector<Capsule> capsules;
  const int total = frames * static_cast<int>(cameras.size());
  int done = 0;
  for (size_t c = 0; c < cameras.size(); ++c) {
    const Camera& camera = cameras[c];
    WriteCameraYaml({camera, true, -1}, (partial / (camera.name + ".yaml")).string());
    fs::create_directories(partial / "masks" / camera.name);
    fs::create_directories(partial / "observed" / camera.name);
    const fs::path video_path = partial / (camera.name + ".avi");
    cv::VideoWriter video(video_path.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), options.fps,
                          cv::Size(camera.width, camera.height));
    if (!video.isOpened())
      ThrowInputError(video_path.string(), "OpenCV cannot write an MJPG video here");
    const RayCaster caster(camera);
    const cv::Mat background = RenderBackground(camera, room);
    // Each camera's own random stream, so adding a camera does not change the others.
    std::mt19937_64 rng(options.seed * 1000003 + c);
    std::uniform_real_distribution<double> uniform(0, 1);
    std::vector<Blob> blobs;
    for (int b = 0; b < deg.clutter_blobs; ++b) {
      const double speed = 0.5 + 2 * uniform(rng), heading = 2 * M_PI * uniform(rng);
      blobs.push_back({{camera.width * uniform(rng), camera.height * (0.2 + 0.7 * uniform(rng))},
                       {speed * std::cos(heading), speed * std::sin(heading)},
                       {camera.width * (0.02 + 0.04 * uniform(rng)), camera.height * (0.03 + 0.05 * uniform(rng))},
                       180 * uniform(rng),
                       cv::Scalar(255 * uniform(rng), 255 * uniform(rng), 255 * uniform(rng))});
    }
    BodyImage image;
    cv::Mat colour(camera.height, camera.width, CV_32FC3), noise(camera.height, camera.width, CV_32FC3);
    cv::Mat frame8, clutter_mask(camera.height, camera.width, CV_8UC1);
    cv::RNG cv_rng(options.seed * 7919 + c);
    for (int k = 0; k < frames; ++k) {
      for (Blob& blob : blobs) {  // blobs move on through dropped frames
        blob.at += blob.velocity;
        if (blob.at.x < 0 || blob.at.x > camera.width) blob.velocity.x = -blob.velocity.x;
        if (blob.at.y < 0 || blob.at.y > camera.height) blob.velocity.y = -blob.velocity.y;
      }
      if (dropped[k]) {
        if (progress) progress(++done, total);
        continue;
      }
      body.Place(joints[k], &capsules);
      caster.Render(capsules, &image);
      const cv::Mat mask = image.Mask();
      // Colour: room, clutter, shaded body, then the light and the sensor's noise.
      clutter_mask.setTo(0);
      for (const Blob& blob : blobs)
        cv::ellipse(clutter_mask, blob.at, blob.axes, blob.angle_deg, 0, 360, cv::Scalar(1 + (&blob - blobs.data())), -1);
      ComposeFrame(background, image, colours, clutter_mask, blobs, &colour);
      colour *= Gain(frames > 1 ? static_cast<double>(k) / (frames - 1) : 0, deg.lighting_gain);
      if (deg.sensor_noise > 0) {
        cv_rng.fill(noise, cv::RNG::NORMAL, cv::Scalar::all(0), cv::Scalar::all(deg.sensor_noise));
        colour += noise;
      }
      colour.convertTo(frame8, CV_8UC3);
      video.write(frame8);
      WriteImage(partial / "masks" / camera.name / FrameName(k), mask);
      WriteImage(partial / "observed" / camera.name / FrameName(k), DegradeMask(mask, clutter_mask, deg, &rng));
      if (options.contact_sheet && std::find(sheet_frames.begin(), sheet_frames.end(), k) != sheet_frames.end()) {
        sheet_tiles[c].push_back(SheetTile(skeleton, camera, mask, joints[k]));
      }
      if (progress) progress(++done, total);
    }
    video.release();
  }
  if (options.contact_sheet && !sheet_frames.empty()) {
    std::vector<cv::Mat> tiles;
    std::vector<std::string> labels;
    for (size_t c = 0; c < cameras.size(); ++c)
      for (size_t i = 0; i < sheet_tiles[c].size(); ++i) {
        tiles.push_back(sheet_tiles[c][i]);
        labels.push_back(cameras[c].name + " frame " + std::to_string(sheet_frames[i]));
      }
    WriteImage(partial / "contact_sheet.png", TileImages(tiles, labels, static_cast<int>(sheet_frames.size())));
  }

  WriteFileAtomic(partial / "ground_truth.json",
                  FormatJson(GroundTruth(skeleton, motion, source, cameras, options, body, sampling)));

  fs::remove(out, ec);  // an empty folder, checked above
  fs::rename(partial, out, ec);
  if (ec) ThrowInputError(out.string(), "cannot move the finished clip into place (" + ec.message() + ")");
  cleanup.done = true;
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace jgpm
