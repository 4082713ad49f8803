// The synthetic clip folder: where each file is, and `ground_truth.json`, written by the
// renderer and read by the tracker's tests and benchmarks.
//
//   ground_truth.json        frame rate, cameras, per frame the time, source frame and
//                            3-D joint positions (mm), and which frames were dropped; with
//                            several walkers, also `people`: each walker's source, body,
//                            placement and, per frame it is in the scene, its joints and
//                            how many pixels of it each camera sees (the top-level frames
//                            are the first walker's, so one-person readers still work)
//   camK.yaml                each camera (calibration/camera.h YAML), as calibrated: with
//                            calibration error, not the camera that rendered the images
//   camK.avi                 colour video (MJPG): shaded body over a textured room, noise
//   background/camK.png      the empty room, as a lab records it before the take
//   masks/camK/NNNNNN.png    exact silhouettes (ray cast), one per kept frame
//   observed/camK/NNNNNN.png the silhouettes after the mask degradations (the tracker's
//                            input when it skips background subtraction)
//   contact_sheet.png        frames per camera with the skeleton over the silhouette
// NNNNNN is the clip frame number; dropped frames have no image and no video frame.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "calibration/camera.h"
#include "tracker/clip/clip_body.h"
#include "tracker/clip/clip_degradations.h"
#include "tracker/clip/clip_rig.h"

namespace jgpm {

// Files of a clip in `folder`.
struct ClipPaths {
  std::filesystem::path folder;

  std::filesystem::path GroundTruth() const { return folder / "ground_truth.json"; }
  std::filesystem::path CameraYaml(const std::string& camera) const { return folder / (camera + ".yaml"); }
  std::filesystem::path Video(const std::string& camera) const { return folder / (camera + ".avi"); }
  std::filesystem::path Background(const std::string& camera) const { return folder / "background" / (camera + ".png"); }
  // The static occluders in front of the walkers, as a user would paint them (255 where
  // one is); written when the scene has occluders.
  std::filesystem::path Occluders(const std::string& camera) const { return folder / "occluders" / (camera + ".png"); }
  std::filesystem::path MaskFolder(const std::string& camera) const { return folder / "masks" / camera; }
  std::filesystem::path ObservedFolder(const std::string& camera) const { return folder / "observed" / camera; }
  std::filesystem::path Mask(const std::string& camera, int frame) const;
  std::filesystem::path ObservedMask(const std::string& camera, int frame) const;
  std::filesystem::path ContactSheet() const { return folder / "contact_sheet.png"; }
};

// "000042.png".
std::string ClipFrameName(int frame);

struct ClipBodyPart {
  std::string name, from, to;  // from and to: bone names
  double radius_from_mm = 0, radius_to_mm = 0;
};

struct ClipFrame {
  double time_s = 0;
  int source_frame = 0;  // index into the motion's frames
  bool dropped = false;
  int video_frame = -1;  // index in each camK.avi; -1 when dropped
  // 3 x bones: the end of bone j (the root: its position), world y up, mm; written to
  // 0.01 mm.
  Eigen::Matrix3Xd joints_mm;
};

// One walker of a several-walker clip, in a clip frame where it is in the scene.
struct ClipPersonFrame {
  int frame = 0;         // clip frame
  int source_frame = 0;  // index into its motion's frames
  Eigen::Matrix3Xd joints_mm;       // as ClipFrame::joints_mm
  std::vector<int> visible_px;      // per camera: its pixels no one and nothing hides
};

// Where and when a walker of a several-walker clip walks (tracker/clip/synthetic_clip.h).
struct ClipPlacement {
  bool placed = false;             // false: as recorded, from the clip's start
  double at_x_mm = 0, at_z_mm = 0;  // its middle frame's root on the floor
  double heading_deg = 0;          // its walk's direction, degrees from +x towards +z
  double delay_s = 0;              // its middle frame, after the first walker's
};

// "X,Z,HEADING,DELAY" (jgpm render --walk): four finite numbers.
bool ParsePlacement(const std::string& text, ClipPlacement* placement);

// A stop: a walker stands still, holding the pose it has `at_s` seconds into its trial,
// for `for_s` seconds, then walks on from there (tracker/clip/synthetic_clip.h).
struct ClipPause {
  double at_s = 0, for_s = 0;
  bool Valid() const { return at_s >= 0 && at_s < 1e6 && for_s > 0 && for_s <= 60; }  // NaN is not
};

// "AT,FOR" (jgpm render --pause): two numbers, AT >= 0, 0 < FOR <= 60.
bool ParsePause(const std::string& text, ClipPause* pause);

struct ClipPerson {
  int id = 0;  // 1, 2, ... in the order given
  std::string source_asf, source_amc;
  ClipBodyOptions body;
  std::vector<ClipBodyPart> body_parts;
  std::vector<std::string> joint_names;
  ClipPlacement placement;
  double start_s = 0;                  // clip time of its motion's first frame
  std::vector<ClipPersonFrame> frames;  // the clip frames it is in the scene, in order
};

struct ClipGroundTruth {
  static constexpr int kVersion = 1;
  std::string source_asf, source_amc;
  double source_fps = 0;
  double fps = 0;
  int image_width = 0, image_height = 0;
  uint64_t seed = 0;
  ClipDegradations degradations;
  ClipBodyOptions body;                  // the person rendered (width scale, seed, clothing, bag)
  std::vector<ClipBodyPart> body_parts;  // its shapes (ends: bone names, or weighted sums)
  std::vector<std::string> joint_names;  // bone names, joints_mm's columns
  // The scene: the rig's kind, the calibration error's scale, the shadow, the occluders'
  // kinds. Written only when not today's defaults (ring, 0, none, none).
  RigKind rig = RigKind::kRing;
  double calibration_error = 0;
  bool shadow = false;
  double reflection = 0;  // the floor's (written when not 0)
  std::vector<std::string> occluders;
  std::vector<Camera> cameras;         // as calibrated (camK.yaml): the tracker's cameras
  std::vector<Camera> render_cameras;  // the cameras that rendered the images, when they
                                       // differ (calibration error); empty otherwise
  std::vector<ClipFrame> frames;
  std::vector<ClipPerson> people;  // every walker (the first included) when there are
                                   // several; empty for one
};

std::string FormatGroundTruth(const ClipGroundTruth& truth);
// InputError naming `source` and the field for anything malformed: another format or
// version, missing or mistyped fields, non-finite numbers, an invalid camera, frames whose
// joints do not match the joint names, video frames out of order.
ClipGroundTruth ParseGroundTruth(const std::string& text, const std::string& source);
ClipGroundTruth ReadGroundTruth(const std::filesystem::path& path);

}  // namespace jgpm
