#include "tracker/frames/frame_source_factory.h"

#include <algorithm>
#include <filesystem>
#include <future>

#include "io/base/error.h"
#include "io/video/image_folder.h"
#include "io/video/v4l2_camera.h"
#include "io/video/video_file.h"
#include "tracker/frames/clip_source.h"
#include "tracker/frames/occluder_masks.h"
#include "tracker/frames/video_frame_source.h"

namespace jgpm {
namespace {

// The camera of source k: given, its YAML, or the guess.
Camera SourceCamera(const FrameSourceSpec& spec, const ImageSource& source, size_t k, size_t count) {
  if (!spec.cameras.empty()) return spec.cameras[k];
  if (spec.camera_guess) {
    return GuessCamera(count == 1 ? "cam0" : "cam" + std::to_string(k), source.width(), source.height(), spec.guess);
  }
  const CameraFile file = ReadCameraYaml(spec.camera_yamls[k]);
  if (!file.has_extrinsics) {
    ThrowInputError(spec.camera_yamls[k], "has no cam_from_world_rotation / cam_from_world_translation_mm: the "
                                          "tracker needs to know where the camera stands (place it with `jgpm "
                                          "calibrate ... --floor-image FLOOR.png`, or use --camera-guess)");
  }
  return file.camera;
}

// A live camera (a V4L2 device, or the software one playing a video), its negotiation
// told.
std::unique_ptr<ImageSource> OpenCamera(const FrameSourceSpec& spec, const std::string& device) {
  V4l2Options options;
  options.width = spec.device_width;
  options.height = spec.device_height;
  options.fps = spec.device_fps;
  options.format = spec.device_format;
  auto camera = OpenV4l2Camera(device, options);
  if (spec.note) spec.note(camera->negotiation());
  return camera;
}

}  // namespace

std::unique_ptr<FrameSource> MakeFrameSource(const FrameSourceSpec& spec) {
  const int kinds = !spec.clip.empty() + !spec.videos.empty() + !spec.images.empty() + !spec.devices.empty();
  if (kinds != 1) ThrowInputError("--clip/--video/--images/--device", "give exactly one source of frames");
  if (!spec.clip.empty()) {
    if (!spec.camera_yamls.empty() || !spec.cameras.empty() || spec.camera_guess) {
      ThrowInputError("--camera", "a clip brings its own cameras (choose among them with --cameras)");
    }
    if (!spec.backgrounds.empty()) ThrowInputError("--background", "a clip's background is learnt from its videos");
    ClipFrameSourceOptions options;
    options.cameras = spec.clip_cameras;
    options.exact_masks = spec.exact_masks;
    options.max_frames = spec.max_frames;
    options.with_images = spec.clip_images;
    if (spec.clip_foreground) options.foreground = spec.foreground;
    return std::make_unique<ClipFrameSource>(spec.clip, options);
  }
  if (!spec.clip_cameras.empty()) ThrowInputError("--cameras", "chooses among a clip's cameras; give --camera YAMLs");
  if (spec.exact_masks) ThrowInputError("--exact-masks", "only a clip has exact masks");
  if (spec.images.empty() && spec.images_fps > 0) ThrowInputError("--fps", "is the frame rate of an --images folder");
  const size_t wanted = std::max<size_t>({1, spec.videos.size(), spec.devices.size()});
  if (spec.camera_guess + !spec.camera_yamls.empty() + !spec.cameras.empty() > 1) {
    ThrowInputError("--camera-guess", "give --camera YAMLs, the guess or a calibration from the walkers, one of them");
  }
  if (!spec.cameras.empty() && spec.cameras.size() != wanted) {
    ThrowInputError("--calibrate-from-walkers", "one camera per video source (" + std::to_string(wanted) + ", got " +
                                                    std::to_string(spec.cameras.size()) + ")");
  }
  if (!spec.camera_guess && spec.cameras.empty() && spec.camera_yamls.size() != wanted) {
    ThrowInputError("--camera", "give one calibrated camera YAML per video source (" + std::to_string(wanted) +
                                    ", got " + std::to_string(spec.camera_yamls.size()) +
                                    "): make one with `jgpm calibrate --images CHESSBOARD_DIR --board COLSxROWS "
                                    "--square MM --floor-image FLOOR.png --out CAM.yaml` or, with people walking in "
                                    "the video, `jgpm calibrate --walkers VIDEO --out CAM.yaml` (or track with "
                                    "--calibrate-from-walkers), or ask for a rough guess with --camera-guess");
  }
  std::vector<std::unique_ptr<ImageSource>> sources;
  // The background is learnt from a sample of each video unless given: taken during the
  // video's damage check. Given, nothing needs a first pass: each video is decoded once,
  // and checked as it is read.
  const int sample = spec.backgrounds.empty() ? spec.foreground.learning_frames : 0;
  const VideoCheck check = spec.backgrounds.empty() ? VideoCheck::kFirst : VideoCheck::kAsItGoes;
  // The videos' first passes side by side (each decodes its whole file); the first
  // camera's error is the one named.
  std::vector<std::future<std::unique_ptr<ImageSource>>> opening;
  for (const std::string& video : spec.videos) {
    opening.push_back(std::async(std::launch::async, [&video, sample, check]() -> std::unique_ptr<ImageSource> {
      return std::make_unique<VideoFileSource>(video, sample, check);
    }));
  }
  for (auto& video : opening) sources.push_back(video.get());
  if (!spec.images.empty()) sources.push_back(std::make_unique<ImageFolderSource>(spec.images, spec.images_fps));
  for (const std::string& device : spec.devices) sources.push_back(OpenCamera(spec, device));
  std::vector<Camera> cameras;
  for (size_t k = 0; k < sources.size(); ++k) cameras.push_back(SourceCamera(spec, *sources[k], k, sources.size()));
  for (size_t a = 0; a < cameras.size(); ++a)
    for (size_t b = 0; b < a; ++b)
      if (cameras[a].name == cameras[b].name) {
        ThrowInputError("--camera", "two cameras are named " + cameras[a].name + " (set camera_name in the YAMLs)");
      }
  if (spec.note && !sources.empty() && sources[0]->live() && spec.backgrounds.empty()) {
    spec.note("learning the background from the first " + std::to_string(spec.foreground.learning_frames) +
              " frames: keep out of view until tracking starts");
  }
  VideoFrameSourceOptions options;
  options.foreground = spec.foreground;
  options.backgrounds = spec.backgrounds;
  options.max_frames = spec.max_frames;
  options.person_px = spec.mask_person_px;
  return std::make_unique<VideoFrameSource>(std::move(sources), std::move(cameras), options);
}

std::vector<cv::Mat> OccluderPaintings(const FrameSourceSpec& spec, const std::vector<Camera>& cameras) {
  std::vector<cv::Mat> paintings;
  if (!spec.clip.empty()) {
    if (!spec.occluders.empty()) {
      ThrowInputError("--occluders", "a clip brings its own paintings (occluders/); --no-occluders leaves them out");
    }
    if (!spec.clip_occluders) return paintings;
    const ClipPaths paths{spec.clip};
    bool any = false;
    for (const Camera& camera : cameras) {
      const std::filesystem::path path = paths.Occluders(camera.name);
      const bool has = std::filesystem::exists(path);
      paintings.push_back(has ? ReadOccluderMask(path.string(), camera) : cv::Mat());
      any = any || has;
    }
    if (!any) paintings.clear();
    return paintings;
  }
  if (spec.occluders.empty()) return paintings;
  if (spec.occluders.size() != cameras.size()) {
    ThrowInputError("--occluders", std::to_string(spec.occluders.size()) + " paintings for " +
                                       std::to_string(cameras.size()) + " cameras: give one per camera, in order");
  }
  for (size_t c = 0; c < cameras.size(); ++c) paintings.push_back(ReadOccluderMask(spec.occluders[c], cameras[c]));
  return paintings;
}

}  // namespace jgpm
