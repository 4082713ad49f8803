#include "tracker/cli/render_commands.h"

#include <cstdio>
#include <numbers>

#include "calibration/camera.h"
#include "io/base/error.h"
#include "io/cli/progress.h"
#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/motion_file.h"
#include "tracker/clip/synthetic_clip.h"

namespace jgpm::cli {
namespace {

struct RenderArguments {
  std::vector<std::string> asf;
  std::vector<std::string> amc;
  std::vector<std::string> walks;
  std::vector<std::string> pauses;
  std::string rig = "ring";
  bool cameras_given = false;  // --cameras (else the webcam rig has its one)
  std::string clothing = "none";
  std::vector<std::string> cameras;
  std::string out;
  double amc_fps = 120;
  ClipOptions clip;
};

std::vector<ClipWalker> ReadWalkers(const RenderArguments& a, const ClipBodyOptions& body) {
  if (!a.asf.empty() && a.asf.size() != a.amc.size())
    ThrowInputError("--asf", "give one per --amc (" + std::to_string(a.amc.size()) + ") or none");
  if (!a.walks.empty() && a.walks.size() != a.amc.size())
    ThrowInputError("--walk", "give one per --amc (" + std::to_string(a.amc.size()) + ") or none");
  std::vector<ClipWalker> walkers;
  for (size_t i = 0; i < a.amc.size(); ++i) {
    MotionFileOptions files;
    if (!a.asf.empty()) files.asf = a.asf[i];
    const std::filesystem::path asf = SkeletonForAmc(a.amc[i], files);
    ClipWalker w;
    w.skeleton = ReadAsf(asf);
    w.motion = ReadAmc(a.amc[i], w.skeleton);
    w.motion.frames_per_second = a.amc_fps;
    w.source = {asf.string(), a.amc[i]};
    w.body = WalkerBody(body, static_cast<int>(i));
    if (!a.walks.empty() && !ParsePlacement(a.walks[i], &w.placement))
      ThrowInputError("--walk " + a.walks[i], "expected X_MM,Z_MM,HEADING_DEG,DELAY_S (four numbers, e.g. 0,0,90,0.5)");
    walkers.push_back(std::move(w));
  }
  return walkers;
}

void RunRender(const RenderArguments& a) {
  ClipOptions clip = a.clip;
  JGPM_CHECK(ParseRigKind(a.rig, &clip.rig.kind) && ParseClothing(a.clothing, &clip.body.clothing));  // CLI11 checked
  if (clip.rig.kind == RigKind::kWebcam && !a.cameras_given) clip.rig.num_cameras = 1;
  for (const std::string& text : a.pauses) {
    ClipPause pause;
    if (!ParsePause(text, &pause)) ThrowInputError("--pause " + text, "expected AT_S,FOR_S (AT >= 0, 0 < FOR <= 60)");
    clip.pauses.push_back(pause);
  }
  std::string why;
  if (!clip.Check(&why)) ThrowInputError("jgpm render", why);
  std::vector<Camera> cameras;
  for (const std::string& path : a.cameras) {
    const CameraFile file = ReadCameraYaml(path);
    if (!file.has_extrinsics)
      ThrowInputError(path, "has no cam_from_world_rotation / cam_from_world_translation_mm: place "
                            "the camera first (jgpm calibrate --floor-image or --pose)");
    cameras.push_back(file.camera);
  }
  const std::vector<ClipWalker> walkers = ReadWalkers(a, clip.body);
  ProgressLine line("render");
  const ClipSummary summary = RenderClip(walkers, cameras, clip, a.out,
                                         [&line](int done, int total) { line.Update(done, total, "images"); });
  line.Finish();
  std::printf("rendered %s -> %s\n", summary.BriefReport().c_str(), a.out.c_str());
  for (const Camera& c : summary.cameras) {
    const Eigen::Vector3d at = c.CentreInWorld();
    std::printf("  %s: f %.1f px (%.0f deg across), at (%.0f, %.0f, %.0f) mm\n", c.name.c_str(), c.fx,
                2 * std::atan(c.width / (2 * c.fx)) * 180 / std::numbers::pi, at.x(), at.y(), at.z());
  }
}

}  // namespace

void AddRenderCommands(CLI::App& app) {
  auto a = std::make_shared<RenderArguments>();
  CLI::App* render = app.add_subcommand(
      "render", "render a synthetic clip from a mocap trial: video, masks and ground truth per camera");
  render->add_option("--amc", a->amc,
                     "motion to render; repeat for several walkers (at most 8), the clip lasting the first's "
                     "trial, each next walker another person (--body-seed + 1, + 2, ...)")
      ->required()->check(CLI::ExistingFile);
  render->add_option("--asf", a->asf, "its skeleton (default: NN.asf next to NN_TT.amc); one per --amc")
      ->check(CLI::ExistingFile);
  render->add_option("--walk", a->walks,
                     "X,Z,HEADING,DELAY, one per --amc: turn and move the trial so that its middle frame's root "
                     "is at (X, Z) mm on the floor walking towards HEADING degrees (from +x towards +z), and show "
                     "its middle frame DELAY s after the first walker's (the first's delay: 0). Same X, Z and "
                     "delay: they cross. Default: each trial as recorded, all from the clip's start");
  CLI::Option* camera = render->add_option("--camera", a->cameras,
      "camera YAML with extrinsics (repeat for several); default: a ring rig, see --cameras");
  render->add_option("--out", a->out, "new (or empty) folder for the clip")->required();
  render->add_option("--fps", a->clip.fps, "clip frame rate")->capture_default_str()->check(CLI::PositiveNumber);
  render->add_option("--amc-fps", a->amc_fps, "frame rate of the AMC (AMC stores none; CMU: 120)")
      ->capture_default_str()->check(CLI::PositiveNumber);
  render->add_option("--max-frames", a->clip.max_frames, "render at most this many clip frames (0: all)")
      ->capture_default_str()->check(CLI::NonNegativeNumber);
  render->add_option("--rig", a->rig,
                     "cameras when none are given: ring (the lab's, at 1.5 m), surveillance (4-8 m up, 8-19 m "
                     "away, people 60-150 px tall) or webcam (one, 1-1.5 m up, 60-90 degrees across, near the walk)")
      ->check(CLI::IsMember({"ring", "surveillance", "webcam"}))->capture_default_str()->excludes(camera);
  render->add_option("--cameras", a->clip.rig.num_cameras, "rig: how many cameras (1-4; the webcam rig has one)")
      ->capture_default_str()->check(CLI::Range(1, 4))->excludes(camera);
  render->add_option("--width", a->clip.rig.width, "rig: image width (default: ring 320, others 640)")
      ->check(CLI::Range(32, 4096))->excludes(camera);
  render->add_option("--height", a->clip.rig.height, "rig: image height (default: ring 240, others 480)")
      ->check(CLI::Range(32, 4096))->excludes(camera);
  render->add_option("--ring-radius", a->clip.rig.ring_radius_mm, "default rig: distance from the walk's centre, mm")
      ->capture_default_str()->check(CLI::Range(1000.0, 50000.0))->excludes(camera);
  render->add_option("--ring-height", a->clip.rig.camera_height_mm, "default rig: the cameras' height above the floor, mm")
      ->capture_default_str()->check(CLI::Range(100.0, 9999.0))->excludes(camera);
  render->add_option("--sensor-noise", a->clip.degradations.sensor_noise, "video noise std, grey levels")
      ->capture_default_str()->check(CLI::Range(0.0, 100.0));
  render->add_option("--mask-noise", a->clip.degradations.mask_noise_px,
                     "observed masks: erode or dilate each frame by up to this many px")
      ->capture_default_str()->check(CLI::Range(0.0, 20.0));
  render->add_option("--holes", a->clip.degradations.holes, "observed masks: holes per frame")
      ->capture_default_str()->check(CLI::Range(0, 100));
  render->add_option("--clutter", a->clip.degradations.clutter_blobs, "moving background blobs")
      ->capture_default_str()->check(CLI::Range(0, 50));
  render->add_option("--lighting", a->clip.degradations.lighting_gain,
                     "brightness at the end of the clip (ramps from 1 over the middle third)")
      ->capture_default_str()->check(CLI::Range(0.1, 3.0));
  render->add_option("--drop-rate", a->clip.degradations.drop_rate, "probability of dropping a frame")
      ->capture_default_str()->check(CLI::Range(0.0, 0.99));
  render->add_option("--width-scale", a->clip.body.width_scale, "body widths times this")
      ->capture_default_str()->check(CLI::Range(0.25, 4.0));
  render->add_option("--body-seed", a->clip.body.body_seed,
                     "another person for each N > 0: widths drawn around the adult mean (+-25%), head, hands and "
                     "shoulders of other sizes, bone lengths the subject's (0: the tracker's own body)")
      ->capture_default_str();
  render->add_option("--clothing", a->clothing,
                     "none, trousers (loose, filling the crotch), coat (to mid-thigh) or skirt (swinging with the "
                     "thighs): volumes the tracker's body cannot represent")
      ->check(CLI::IsMember({"none", "trousers", "coat", "skirt"}))->capture_default_str();
  render->add_flag("--bag", a->clip.body.bag, "a shoulder bag at the right hip");
  render->add_flag("--shadow", a->clip.scene.shadow,
                   "the walker's shadow on the floor from a random light (in the video and the observed masks, "
                   "not the exact ones)");
  render->add_option("--reflection", a->clip.scene.reflection,
                     "a glossy floor reflecting the walkers with this reflectance, 0-0.5 (in the video, and in the "
                     "observed masks where it shows, not the exact ones)")
      ->capture_default_str()->check(CLI::Range(0.0, 0.5));
  render->add_option("--occluders", a->clip.scene.occluders,
                     "static objects between the cameras and the walk (pillar, table, bicycle) and as many things "
                     "passing in front of the walker")
      ->capture_default_str()->check(CLI::Range(0, 8));
  render->add_option("--calibration-error", a->clip.calibration_error,
                     "the written cameras differ from the rendering ones by this times a real calibration's error "
                     "(1: focal 1.5%, principal point 4 px, rotation 0.7 deg, centre 30 mm)")
      ->capture_default_str()->check(CLI::Range(0.0, 10.0));
  render->add_option("--pause", a->pauses,
                     "AT,FOR: the walkers stand still AT s into their trials for FOR s, then walk on (repeat for "
                     "several stops; the clip lasts that much longer)");
  render->add_option("--seed", a->clip.seed, "random seed of the degradations, rig, scene and calibration error")
      ->capture_default_str();
  render->add_flag("!--no-contact-sheet", a->clip.contact_sheet, "skip contact_sheet.png");
  render->callback([a, render] {
    a->cameras_given = render->get_option("--cameras")->count() > 0;
    RunRender(*a);
  });
}

}  // namespace jgpm::cli
