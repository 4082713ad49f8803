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

json JointsJson(const Eigen::Matrix3Xd& joints_mm) {
  json joints = json::array();
  for (int b = 0; b < joints_mm.cols(); ++b) {  // to 0.01 mm
    joints.push_back({std::round(joints_mm(0, b) * 100) / 100, std::round(joints_mm(1, b) * 100) / 100,
                      std::round(joints_mm(2, b) * 100) / 100});
  }
  return joints;
}

Eigen::Matrix3Xd ReadJoints(const JsonReader& in, const json& j, const std::string& where, int count) {
  const auto positions = in.Get<std::vector<std::vector<double>>>(j, "joints_mm", where);
  if (static_cast<int>(positions.size()) != count) {
    in.Fail(where + "joints_mm", "expected " + std::to_string(count) + " joints (joint_names), found " +
                                     std::to_string(positions.size()));
  }
  Eigen::Matrix3Xd joints(3, count);
  for (int b = 0; b < count; ++b) {
    if (positions[b].size() != 3) in.Fail(where + "joints_mm", "expected x, y, z for each joint");
    for (int i = 0; i < 3; ++i) joints(i, b) = positions[b][i];
  }
  return joints;
}

json BodyPartsJson(const std::vector<ClipBodyPart>& body_parts) {
  json parts = json::array();
  for (const ClipBodyPart& p : body_parts) {
    parts.push_back({{"name", p.name}, {"from", p.from}, {"to", p.to}, {"radius_from_mm", p.radius_from_mm},
                     {"radius_to_mm", p.radius_to_mm}});
  }
  return parts;
}

json BodyJson(const ClipBodyOptions& body, const std::vector<ClipBodyPart>& parts) {
  json r = {{"width_scale", body.width_scale}, {"parts", BodyPartsJson(parts)}};
  if (!body.TrackersBody()) {
    r["body_seed"] = body.body_seed;
    r["clothing"] = std::string(ClothingName(body.clothing));
    r["bag"] = body.bag;
  }
  return r;
}

void ReadBody(const JsonReader& in, const json& body, const std::string& where, ClipBodyOptions* options,
              std::vector<ClipBodyPart>* body_parts) {
  options->width_scale = in.Get<double>(body, "width_scale", where);
  if (body.contains("body_seed")) {  // not today's body
    options->body_seed = in.Get<uint64_t>(body, "body_seed", where);
    if (!ParseClothing(in.Get<std::string>(body, "clothing", where), &options->clothing)) {
      in.Fail(where + "clothing", "expected none, trousers, coat or skirt");
    }
    options->bag = in.Get<bool>(body, "bag", where);
  }
  std::string why;
  if (!options->Check(&why)) in.Fail(where.substr(0, where.size() - 1), why);
  const json& parts = in.Field(body, "parts", where);
  if (!parts.is_array()) in.Fail(where + "parts", "expected an array");
  for (size_t i = 0; i < parts.size(); ++i) {
    const std::string at = where + "parts[" + std::to_string(i) + "].";
    ClipBodyPart p;
    p.name = in.Get<std::string>(parts[i], "name", at);
    p.from = in.Get<std::string>(parts[i], "from", at);
    p.to = in.Get<std::string>(parts[i], "to", at);
    p.radius_from_mm = in.Get<double>(parts[i], "radius_from_mm", at);
    p.radius_to_mm = in.Get<double>(parts[i], "radius_to_mm", at);
    body_parts->push_back(p);
  }
}

json PeopleJson(const std::vector<ClipPerson>& people) {
  json r = json::array();
  for (const ClipPerson& p : people) {
    json frames = json::array();
    for (const ClipPersonFrame& f : p.frames) {
      frames.push_back({{"frame", f.frame}, {"source_frame", f.source_frame}, {"joints_mm", JointsJson(f.joints_mm)},
                        {"visible_px", f.visible_px}});
    }
    json placement = {{"placed", p.placement.placed}};
    if (p.placement.placed) {
      placement["at_mm"] = {p.placement.at_x_mm, p.placement.at_z_mm};
      placement["heading_deg"] = p.placement.heading_deg;
      placement["delay_s"] = p.placement.delay_s;
    }
    r.push_back({{"id", p.id}, {"source", {{"asf", p.source_asf}, {"amc", p.source_amc}}},
                 {"body_model", BodyJson(p.body, p.body_parts)}, {"joint_names", p.joint_names},
                 {"placement", placement}, {"start_s", p.start_s}, {"frames", frames}});
  }
  return r;
}

std::vector<ClipPerson> ReadPeople(const JsonReader& in, const json& people, int clip_frames, int cameras) {
  if (!people.is_array() || people.size() < 2) in.Fail("people", "expected an array of 2 or more walkers");
  std::vector<ClipPerson> r;
  for (size_t i = 0; i < people.size(); ++i) {
    const std::string where = "people[" + std::to_string(i) + "].";
    const json& j = people[i];
    ClipPerson p;
    p.id = in.Get<int>(j, "id", where);
    if (p.id != static_cast<int>(i) + 1) in.Fail(where + "id", "expected " + std::to_string(i + 1));
    const json& s = in.Field(j, "source", where);
    p.source_asf = in.Get<std::string>(s, "asf", where + "source.");
    p.source_amc = in.Get<std::string>(s, "amc", where + "source.");
    ReadBody(in, in.Field(j, "body_model", where), where + "body_model.", &p.body, &p.body_parts);
    p.joint_names = in.Get<std::vector<std::string>>(j, "joint_names", where);
    if (p.joint_names.empty()) in.Fail(where + "joint_names", "is empty");
    const json& placement = in.Field(j, "placement", where);
    p.placement.placed = in.Get<bool>(placement, "placed", where + "placement.");
    if (p.placement.placed) {
      const auto at = in.Get<std::vector<double>>(placement, "at_mm", where + "placement.");
      if (at.size() != 2) in.Fail(where + "placement.at_mm", "expected x and z");
      p.placement.at_x_mm = at[0];
      p.placement.at_z_mm = at[1];
      p.placement.heading_deg = in.Get<double>(placement, "heading_deg", where + "placement.");
      p.placement.delay_s = in.Get<double>(placement, "delay_s", where + "placement.");
    }
    p.start_s = in.Get<double>(j, "start_s", where);
    const json& frames = in.Field(j, "frames", where);
    if (!frames.is_array()) in.Fail(where + "frames", "expected an array");
    for (size_t k = 0; k < frames.size(); ++k) {
      const std::string at = where + "frames[" + std::to_string(k) + "].";
      ClipPersonFrame f;
      f.frame = in.Get<int>(frames[k], "frame", at);
      if (f.frame < 0 || f.frame >= clip_frames || (!p.frames.empty() && f.frame <= p.frames.back().frame)) {
        in.Fail(at + "frame", "expected a clip frame (0 to " + std::to_string(clip_frames - 1) +
                                  ") after the one before");
      }
      f.source_frame = in.Get<int>(frames[k], "source_frame", at);
      f.joints_mm = ReadJoints(in, frames[k], at, static_cast<int>(p.joint_names.size()));
      f.visible_px = in.Get<std::vector<int>>(frames[k], "visible_px", at);
      if (static_cast<int>(f.visible_px.size()) != cameras) {
        in.Fail(at + "visible_px", "expected one count per camera (" + std::to_string(cameras) + ")");
      }
      p.frames.push_back(std::move(f));
    }
    r.push_back(std::move(p));
  }
  return r;
}

}  // namespace

bool ParsePlacement(const std::string& text, ClipPlacement* placement) {
  ClipPlacement p;
  p.placed = true;
  char end = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf,%lf,%lf%c", &p.at_x_mm, &p.at_z_mm, &p.heading_deg, &p.delay_s, &end) != 4 ||
      !std::isfinite(p.at_x_mm) || !std::isfinite(p.at_z_mm) || !std::isfinite(p.heading_deg) ||
      !std::isfinite(p.delay_s))
    return false;
  *placement = p;
  return true;
}

bool ParsePause(const std::string& text, ClipPause* pause) {
  ClipPause p;
  char end = 0;
  if (std::sscanf(text.c_str(), "%lf,%lf%c", &p.at_s, &p.for_s, &end) != 2 || !p.Valid()) return false;
  *pause = p;
  return true;
}

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
  truth["body_model"] = BodyJson(t.body, t.body_parts);
  if (t.rig != RigKind::kRing || t.calibration_error > 0 || t.shadow || t.reflection > 0 || !t.occluders.empty()) {
    truth["scene"] = {{"rig", std::string(RigKindName(t.rig))}, {"calibration_error", t.calibration_error},
                      {"shadow", t.shadow}, {"occluders", t.occluders}};
    if (t.reflection > 0) truth["scene"]["reflection"] = t.reflection;
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
    frames.push_back({{"frame", k}, {"time_s", f.time_s}, {"source_frame", f.source_frame}, {"dropped", f.dropped},
                      {"video_frame", f.dropped ? json(nullptr) : json(f.video_frame)},
                      {"joints_mm", JointsJson(f.joints_mm)}});
  }
  truth["frames"] = frames;
  if (!t.people.empty()) truth["people"] = PeopleJson(t.people);
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
  ReadBody(in, in.Field(root, "body_model", ""), "body_model.", &t.body, &t.body_parts);
  if (root.contains("scene")) {  // not today's lab
    const json& scene = in.Field(root, "scene", "");
    if (!ParseRigKind(in.Get<std::string>(scene, "rig", "scene."), &t.rig)) {
      in.Fail("scene.rig", "expected ring, surveillance or webcam");
    }
    t.calibration_error = in.Get<double>(scene, "calibration_error", "scene.");
    if (!(t.calibration_error >= 0 && t.calibration_error <= 10)) in.Fail("scene.calibration_error", "expected 0 to 10");
    t.shadow = in.Get<bool>(scene, "shadow", "scene.");
    if (scene.contains("reflection")) {  // clips before glossy floors have none
      t.reflection = in.Get<double>(scene, "reflection", "scene.");
      if (!(t.reflection >= 0 && t.reflection <= 0.5)) in.Fail("scene.reflection", "expected 0 to 0.5");
    }
    t.occluders = in.Get<std::vector<std::string>>(scene, "occluders", "scene.");
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
    f.joints_mm = ReadJoints(in, j, where, joints);
    t.frames.push_back(std::move(f));
  }
  if (root.contains("people")) {
    t.people = ReadPeople(in, in.Field(root, "people", ""), static_cast<int>(t.frames.size()),
                          static_cast<int>(t.cameras.size()));
  }
  return t;
}

ClipGroundTruth ReadGroundTruth(const std::filesystem::path& path) {
  return ParseGroundTruth(ReadTextFile(path, "a synthetic clip's ground_truth.json"), path.string());
}

}  // namespace jgpm
