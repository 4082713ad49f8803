#include "tracker/clip/clip_format.h"

#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "io/base/error.h"
#include "io/base/json_file.h"
#include "io/base/text_reader.h"

namespace jgpm {
namespace {

using nlohmann::json;

constexpr char kFormat[] = "jgpm synthetic clip";

json CameraJson(const Camera& c) {
  json r = json::array();
  for (int i = 0; i < 3; ++i) r.push_back({c.cam_from_world_rotation(i, 0), c.cam_from_world_rotation(i, 1), c.cam_from_world_rotation(i, 2)});
  return {{"name", c.name}, {"yaml", c.name + ".yaml"}, {"video", c.name + ".avi"},
          {"masks", "masks/" + c.name}, {"observed_masks", "observed/" + c.name},
          {"image_width", c.width}, {"image_height", c.height},
          {"fx", c.fx}, {"fy", c.fy}, {"cx", c.cx}, {"cy", c.cy}, {"distortion", c.distortion},
          {"cam_from_world_rotation", r},
          {"cam_from_world_translation_mm", {c.cam_from_world_translation_mm.x(), c.cam_from_world_translation_mm.y(), c.cam_from_world_translation_mm.z()}}};
}

Camera ReadCamera(const JsonReader& in, const json& c, const std::string& where) {
  Camera camera;
  camera.name = in.Get<std::string>(c, "name", where);
  camera.width = in.Get<int>(c, "image_width", where);
  camera.height = in.Get<int>(c, "image_height", where);
  camera.fx = in.Get<double>(c, "fx", where);
  camera.fy = in.Get<double>(c, "fy", where);
  camera.cx = in.Get<double>(c, "cx", where);
  camera.cy = in.Get<double>(c, "cy", where);
  camera.distortion = in.Get<std::vector<double>>(c, "distortion", where);
  const auto rotation = in.Get<std::vector<std::vector<double>>>(c, "cam_from_world_rotation", where);
  if (rotation.size() != 3) in.Fail(where + "cam_from_world_rotation", "expected 3 rows");
  for (int i = 0; i < 3; ++i) {
    if (rotation[i].size() != 3) in.Fail(where + "cam_from_world_rotation", "expected 3 values a row");
    for (int j = 0; j < 3; ++j) camera.cam_from_world_rotation(i, j) = rotation[i][j];
  }
  const auto translation = in.Get<std::vector<double>>(c, "cam_from_world_translation_mm", where);
  if (translation.size() != 3) in.Fail(where + "cam_from_world_translation_mm", "expected 3 values");
  camera.cam_from_world_translation_mm = Eigen::Vector3d(translation[0], translation[1], translation[2]);
  std::string why;
  if (!camera.Check(&why)) in.Fail(where + "name", "is an invalid camera: " + why);
  return camera;
}

}  // namespace

std::string ClipFrameName(int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "%06d.png", frame);
  return name;
}

std::filesystem::path ClipPaths::Mask(const std::string& camera, int frame) const {
  return MaskFolder(camera) / ClipFrameName(frame);
}

std::filesystem::path ClipPaths::ObservedMask(const std::string& camera, int frame) const {
  return ObservedFolder(camera) / ClipFrameName(frame);
}

std::string FormatGroundTruth(const ClipGroundTruth& t) {
  const ClipDegradations& deg = t.degradations;
  json truth;
  truth["format"] = kFormat;
  truth["version"] = ClipGroundTruth::kVersion;
  truth["source"] = {{"asf", t.source_asf}, {"amc", t.source_amc}, {"fps", t.source_fps}};
  truth["fps"] = t.fps;
  truth["image_width"] = t.image_width;
  truth["image_height"] = t.image_height;
  truth["seed"] = t.seed;
  truth["degradations"] = {{"sensor_noise", deg.sensor_noise}, {"mask_noise_px", deg.mask_noise_px},
                           {"holes", deg.holes}, {"clutter_blobs", deg.clutter_blobs},
                           {"lighting_gain", deg.lighting_gain}, {"drop_rate", deg.drop_rate}};
  json parts = json::array();
  for (const ClipBodyPart& p : t.body_parts) {
    parts.push_back({{"name", p.name}, {"from", p.from}, {"to", p.to}, {"radius_from_mm", p.radius_from_mm},
                     {"radius_to_mm", p.radius_to_mm}});
  }
  truth["body_model"] = {{"width_scale", t.body.width_scale}, {"parts", parts}};
  if (!t.body.TrackersBody()) {
    truth["body_model"]["body_seed"] = t.body.body_seed;
    truth["body_model"]["clothing"] = std::string(ClothingName(t.body.clothing));
    truth["body_model"]["bag"] = t.body.bag;
  }
  if (t.rig != RigKind::kRing || t.calibration_error > 0 || t.shadow || !t.occluders.empty()) {
    truth["scene"] = {{"rig", std::string(RigKindName(t.rig))}, {"calibration_error", t.calibration_error},
                      {"shadow", t.shadow}, {"occluders", t.occluders}};
  }
  truth["joint_names"] = t.joint_names;
  truth["joints_note"] = "joints_mm[j] is the end of bone j (the root: its position), world y up, mm";
  json cameras = json::array();
  for (const Camera& c : t.cameras) cameras.push_back(CameraJson(c));
  truth["cameras"] = cameras;
  if (!t.render_cameras.empty()) {
    json rendered = json::array();
    for (const Camera& c : t.render_cameras) rendered.push_back(CameraJson(c));
    truth["render_cameras"] = rendered;
  }
  json frames = json::array();
  for (size_t k = 0; k < t.frames.size(); ++k) {
    const ClipFrame& f = t.frames[k];
    json joints = json::array();
    for (int b = 0; b < f.joints_mm.cols(); ++b) {  // to 0.01 mm
      joints.push_back({std::round(f.joints_mm(0, b) * 100) / 100, std::round(f.joints_mm(1, b) * 100) / 100,
                        std::round(f.joints_mm(2, b) * 100) / 100});
    }
    frames.push_back({{"frame", k}, {"time_s", f.time_s}, {"source_frame", f.source_frame}, {"dropped", f.dropped},
                      {"video_frame", f.dropped ? json(nullptr) : json(f.video_frame)}, {"joints_mm", joints}});
  }
  truth["frames"] = frames;
  return FormatJson(truth);
}

ClipGroundTruth ParseGroundTruth(const std::string& text, const std::string& source) {
  const json root = ParseJson(text, source);
  const JsonReader in(source);
  if (!root.is_object() || in.Get<std::string>(root, "format", "") != kFormat) {
    ThrowInputError(source, std::string("not a synthetic clip's ground truth (expected \"format\": \"") + kFormat + "\")");
  }
  const int version = in.Get<int>(root, "version", "");
  if (version != ClipGroundTruth::kVersion) {
    ThrowInputError(source, "ground truth version " + std::to_string(version) + " is not supported (expected " +
                                std::to_string(ClipGroundTruth::kVersion) + ")");
  }
  ClipGroundTruth t;
  const json& s = in.Field(root, "source", "");
  t.source_asf = in.Get<std::string>(s, "asf", "source.");
  t.source_amc = in.Get<std::string>(s, "amc", "source.");
  t.source_fps = in.Get<double>(s, "fps", "source.");
  t.fps = in.Get<double>(root, "fps", "");
  if (!(t.fps > 0)) in.Fail("fps", "must be > 0");
  t.image_width = in.Get<int>(root, "image_width", "");
  t.image_height = in.Get<int>(root, "image_height", "");
  t.seed = in.Get<uint64_t>(root, "seed", "");
  const json& d = in.Field(root, "degradations", "");
  ClipDegradations& deg = t.degradations;
  deg.sensor_noise = in.Get<double>(d, "sensor_noise", "degradations.");
  deg.mask_noise_px = in.Get<double>(d, "mask_noise_px", "degradations.");
  deg.holes = in.Get<int>(d, "holes", "degradations.");
  deg.clutter_blobs = in.Get<int>(d, "clutter_blobs", "degradations.");
  deg.lighting_gain = in.Get<double>(d, "lighting_gain", "degradations.");
  deg.drop_rate = in.Get<double>(d, "drop_rate", "degradations.");
  std::string why;
  if (!deg.Check(&why)) in.Fail("degradations", why);
  const json& body = in.Field(root, "body_model", "");
  t.body.width_scale = in.Get<double>(body, "width_scale", "body_model.");
  if (body.contains("body_seed")) {  // not today's body
    t.body.body_seed = in.Get<uint64_t>(body, "body_seed", "body_model.");
    if (!ParseClothing(in.Get<std::string>(body, "clothing", "body_model."), &t.body.clothing)) {
      in.Fail("body_model.clothing", "expected none, trousers, coat or skirt");
    }
    t.body.bag = in.Get<bool>(body, "bag", "body_model.");
  }
  if (!t.body.Check(&why)) in.Fail("body_model", why);
  if (root.contains("scene")) {  // not today's lab
    const json& scene = in.Field(root, "scene", "");
    if (!ParseRigKind(in.Get<std::string>(scene, "rig", "scene."), &t.rig)) {
      in.Fail("scene.rig", "expected ring, surveillance or webcam");
    }
    t.calibration_error = in.Get<double>(scene, "calibration_error", "scene.");
    if (!(t.calibration_error >= 0 && t.calibration_error <= 10)) in.Fail("scene.calibration_error", "expected 0 to 10");
    t.shadow = in.Get<bool>(scene, "shadow", "scene.");
    t.occluders = in.Get<std::vector<std::string>>(scene, "occluders", "scene.");
  }
  const json& parts = in.Field(body, "parts", "body_model.");
  if (!parts.is_array()) in.Fail("body_model.parts", "expected an array");
  for (size_t i = 0; i < parts.size(); ++i) {
    const std::string where = "body_model.parts[" + std::to_string(i) + "].";
    ClipBodyPart p;
    p.name = in.Get<std::string>(parts[i], "name", where);
    p.from = in.Get<std::string>(parts[i], "from", where);
    p.to = in.Get<std::string>(parts[i], "to", where);
    p.radius_from_mm = in.Get<double>(parts[i], "radius_from_mm", where);
    p.radius_to_mm = in.Get<double>(parts[i], "radius_to_mm", where);
    t.body_parts.push_back(p);
  }
  t.joint_names = in.Get<std::vector<std::string>>(root, "joint_names", "");
  if (t.joint_names.empty()) in.Fail("joint_names", "is empty");
  const json& cameras = in.Field(root, "cameras", "");
  if (!cameras.is_array() || cameras.empty()) in.Fail("cameras", "expected a non-empty array");
  for (size_t c = 0; c < cameras.size(); ++c) {
    t.cameras.push_back(ReadCamera(in, cameras[c], "cameras[" + std::to_string(c) + "]."));
  }
  if (root.contains("render_cameras")) {
    const json& rendered = in.Field(root, "render_cameras", "");
    if (!rendered.is_array() || rendered.size() != cameras.size()) {
      in.Fail("render_cameras", "expected one per camera (" + std::to_string(cameras.size()) + ")");
    }
    for (size_t c = 0; c < rendered.size(); ++c) {
      t.render_cameras.push_back(ReadCamera(in, rendered[c], "render_cameras[" + std::to_string(c) + "]."));
      if (t.render_cameras.back().name != t.cameras[c].name) {
        in.Fail("render_cameras[" + std::to_string(c) + "].name", "expected " + t.cameras[c].name);
      }
    }
  }
  const json& frames = in.Field(root, "frames", "");
  if (!frames.is_array()) in.Fail("frames", "expected an array");
  const int joints = static_cast<int>(t.joint_names.size());
  int video_frames = 0;
  for (size_t k = 0; k < frames.size(); ++k) {
    const std::string where = "frames[" + std::to_string(k) + "].";
    const json& j = frames[k];
    if (in.Get<size_t>(j, "frame", where) != k) in.Fail(where + "frame", "expected " + std::to_string(k));
    ClipFrame f;
    f.time_s = in.Get<double>(j, "time_s", where);
    f.source_frame = in.Get<int>(j, "source_frame", where);
    f.dropped = in.Get<bool>(j, "dropped", where);
    if (f.dropped) {
      if (!in.Field(j, "video_frame", where).is_null()) in.Fail(where + "video_frame", "must be null for a dropped frame");
    } else {
      f.video_frame = in.Get<int>(j, "video_frame", where);
      if (f.video_frame != video_frames) in.Fail(where + "video_frame", "expected " + std::to_string(video_frames));
      ++video_frames;
    }
    const auto positions = in.Get<std::vector<std::vector<double>>>(j, "joints_mm", where);
    if (static_cast<int>(positions.size()) != joints) {
      in.Fail(where + "joints_mm", "expected " + std::to_string(joints) + " joints (joint_names), found " +
                                       std::to_string(positions.size()));
    }
    f.joints_mm.resize(3, joints);
    for (int b = 0; b < joints; ++b) {
      if (positions[b].size() != 3) in.Fail(where + "joints_mm", "expected x, y, z for each joint");
      for (int i = 0; i < 3; ++i) f.joints_mm(i, b) = positions[b][i];
    }
    t.frames.push_back(std::move(f));
  }
  return t;
}

ClipGroundTruth ReadGroundTruth(const std::filesystem::path& path) {
  return ParseGroundTruth(ReadTextFile(path, "a synthetic clip's ground_truth.json"), path.string());
}

}  // namespace jgpm
