#include "calibration/cli/calibration_commands.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "calibration/camera.h"
#include "calibration/chessboard.h"
#include "calibration/rig_placement.h"
#include "io/base/error.h"
#include "io/cli/progress.h"
#include "io/video/image_list.h"

namespace jgpm::cli {
namespace {

namespace fs = std::filesystem;

struct CalibrateArguments {
  std::string images;
  std::string board;
  double square_mm = 0;
  std::string out;
  std::string name = "cam0";
  std::string floor_image;
  std::string floor_board;  // default: --board
  double floor_square_mm = 0;  // default: --square
  std::string pose;
  int distortion_coefficients = 5;
  bool fast_check = false;
  // --walkers
  std::vector<std::string> walkers;
  std::string background;
  std::string camera;  // intrinsics to keep
  double person_height_m = 1.70;
  double max_clock_offset_s = 2;
  int max_frames = 0;
  double fps = 0;
};

// "9x6" -> 9 and 6 (inner corners, each at least 3).
bool ParseBoard(const std::string& text, int* cols, int* rows) {
  const size_t x = text.find_first_of("xX");
  if (x == std::string::npos || x == 0 || x + 1 == text.size()) return false;
  const std::string a = text.substr(0, x), b = text.substr(x + 1);
  auto digits = [](const std::string& s) {
    return s.size() <= 4 && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
  };
  if (!digits(a) || !digits(b)) return false;
  *cols = std::stoi(a);
  *rows = std::stoi(b);
  return *cols >= 3 && *rows >= 3;
}

const CLI::Validator kBoardSize(
    [](std::string& text) {
      int cols, rows;
      return ParseBoard(text, &cols, &rows)
                 ? std::string()
                 : "expected COLSxROWS, the board's inner corners (e.g. 9x6 for 10 x 7 squares), each at least 3, got '" +
                       text + "'";
    },
    "COLSxROWS");

// The whole of `text` as a finite number, or nothing.
std::optional<double> ParseNumber(const std::string& text) {
  size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used != text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

// (CLI11's PositiveNumber would print its range up to DBL_MAX.)
const CLI::Validator kPositiveMm(
    [](std::string& text) {
      const std::optional<double> value = ParseNumber(text);
      return value && *value > 0
                 ? std::string()
                 : "expected a length in millimetres > 0, got '" + text + "'";
    },
    "MM");

std::string Distortion(const Camera& camera) {
  static const char* const names[] = {"k1", "k2", "p1", "p2", "k3", "k4", "k5", "k6"};
  std::string out;
  char value[64];
  for (size_t i = 0; i < camera.distortion.size(); ++i) {
    std::snprintf(value, sizeof(value), "%s%s %.6g", i ? ", " : "", names[i], camera.distortion[i]);
    out += value;
  }
  return out;
}

void PrintPlacement(const Camera& camera, const std::string& how) {
  const Eigen::Vector3d centre = camera.CentreInWorld();
  const Eigen::Vector3d forward = camera.cam_from_world_rotation.row(2).transpose();
  std::printf("placed %s: centre (%.1f, %.1f, %.1f) mm (%.1f mm above the floor), looking along (%.3f, %.3f, %.3f)\n",
              how.c_str(), centre.x(), centre.y(), centre.z(), centre.y(), forward.x(), forward.y(), forward.z());
}

void CheckOutFolder(const std::string& out) {
  const fs::path out_folder = fs::path(out).parent_path();
  if (!out_folder.empty() && !fs::is_directory(out_folder)) ThrowInputError("--out " + out, "no such folder");
}

}  // namespace

namespace {

// ", +- S with other walkers" (the jackknife's spread, WalkerCalibrationOptions), or nothing.
std::string WithOtherWalkers(const Estimate& e, int decimals) {
  if (e.walkers_sd <= 0) return "";
  char text[64];
  std::snprintf(text, sizeof text, ", +- %.*f with other walkers", decimals, e.walkers_sd);
  return text;
}

// One camera's calibration as found, with each number's uncertainty.

void PrintWalkerCalibration(const WalkerCalibration& found, int width, const std::string& intrinsics) {
  const double fov = 2 * std::atan(width / 2.0 / found.focal_px.value) * 180 / std::acos(-1.0);
  if (!intrinsics.empty()) {
    std::printf("focal length  %.1f px (kept from %s, with its lens distortion)\n", found.focal_px.value,
                intrinsics.c_str());
  } else {
    std::printf("focal length  %.1f +- %.1f px%s (horizontal field of view %.1f degrees; principal point at the image "
                "centre, no lens distortion assumed: give --camera for a chessboard's)\n",
                found.focal_px.value, found.focal_px.sd, WithOtherWalkers(found.focal_px, 1).c_str(), fov);
  }
  std::printf("height        %.0f +- %.0f mm above the floor%s\n", found.height_mm.value, found.height_mm.sd,
              WithOtherWalkers(found.height_mm, 0).c_str());
  std::printf("tilt          %.2f +- %.2f degrees down%s\n", found.tilt_deg.value, found.tilt_deg.sd,
              WithOtherWalkers(found.tilt_deg, 2).c_str());
  std::printf("roll          %.2f +- %.2f degrees%s\n", found.roll_deg.value, found.roll_deg.sd,
              WithOtherWalkers(found.roll_deg, 2).c_str());
  if (found.height_mm.walkers_sd > 0) {
    std::printf("(+- the fit's standard deviation, taking every walker for the model's upright person; with other "
                "walkers: how far the camera moves as groups of them are left out in turn, a jackknife)\n");
  }
  std::printf("fit: heads %.1f px RMS off their feet's vertical, %.0f mm RMS around their walker's height\n",
              found.rms_line_px, found.rms_height_mm);
  std::string heights;
  for (double h : found.walker_heights_mm) heights += (heights.empty() ? "" : " ") + std::to_string(std::lround(h));
  std::printf("the walkers' heights, mm: %s\n", heights.c_str());
}

}  // namespace

std::vector<Camera> CalibrateFromWalkerVideos(const WalkerRequest& request, const ReadWalkers& read_walkers) {
  JGPM_CHECK(!request.takes.empty() && !request.takes.front().empty());
  const size_t n = request.takes.front().size();
  for (const std::vector<std::string>& take : request.takes) {
    if (take.size() != n) {
      ThrowInputError("--walkers " + take.front(), "lists " + std::to_string(take.size()) + " cameras' videos, the "
                                                       "first --walkers " + std::to_string(n) +
                                                       " (each --walkers is one take: a video per camera)");
    }
  }
  for (const auto* list : {&request.backgrounds, &request.intrinsics}) {
    if (!list->empty() && list->size() != n) {
      ThrowInputError(list == &request.backgrounds ? "--background" : "--camera",
                      "give one per camera (" + std::to_string(n) + "), comma-separated, got " +
                          std::to_string(list->size()));
    }
  }
  auto per_camera = [](const std::vector<std::string>& list, size_t k) { return list.empty() ? "" : list[k]; };
  const size_t videos = request.takes.size() * n;
  std::printf("calibrating %s from the walkers in %zu video(s) (people %.2f m tall on average, +- %.2f m)\n",
              n == 1 ? "a camera" : (std::to_string(n) + " cameras").c_str(), videos, request.person_height_m,
              WalkerCalibrationOptions().person_height_sd_mm / 1000);
  std::fflush(stdout);
  // Every take's videos, each camera's walkers numbered apart across takes (they are
  // different people) and its frames on one clock (takes follow each other).
  std::vector<WalkerEvidence> evidence(n);
  std::vector<int> walkers(n, 0);
  int clock = 0;
  for (const std::vector<std::string>& take : request.takes) {
    int longest = 0;
    for (size_t k = 0; k < n; ++k) {
      const std::string& video = take[k];
      const WalkerEvidence one = read_walkers({video, per_camera(request.backgrounds, k), request.max_frames,
                                               request.fps, request.width, request.height});
      if (one.foreground_share > kMovingCameraShare) {
        ThrowInputError("--walkers " + video, "half its frames are more than " +
                                                  std::to_string(std::lround(100 * one.foreground_share)) +
                                                  "% foreground: a moving camera (or changing light)? calibration "
                                                  "from walkers needs a fixed camera");
      }
      WalkerEvidence& e = evidence[k];
      if (e.width == 0) {
        e.width = one.width;
        e.height = one.height;
        e.fps = one.fps;
      } else if (one.width != e.width || one.height != e.height) {
        ThrowInputError("--walkers " + video, "frames of " + std::to_string(one.width) + "x" +
                                                  std::to_string(one.height) + ", the camera's first video's are " +
                                                  std::to_string(e.width) + "x" + std::to_string(e.height) +
                                                  " (every video of a camera must come from that camera)");
      }
      int most = -1;
      for (HeadFoot point : one.points) {
        most = std::max(most, point.walker);
        point.walker += walkers[k];
        point.frame += clock;
        e.points.push_back(point);
      }
      walkers[k] += most + 1;
      e.frames += one.frames;
      longest = std::max(longest, one.frames);
      std::printf("  %s: %zu points of %d walkers in %d frames\n", video.c_str(), one.points.size(), most + 1,
                  one.frames);
    }
    clock += longest;
  }
  std::vector<RigCamera> rig(n);
  for (size_t k = 0; k < n; ++k) {
    const WalkerEvidence& e = evidence[k];
    WalkerCalibrationOptions options;
    options.person_height_mm = request.person_height_m * 1000;
    const std::string intrinsics = per_camera(request.intrinsics, k);
    if (!intrinsics.empty()) options.intrinsics = ReadCameraYaml(intrinsics).camera;
    // Frames within half a gait cycle (about half a second) share their errors.
    if (e.fps > 0) options.correlated_frames = std::max(1.0, 0.5 * e.fps);
    options.refuse_undetermined = n == 1;  // several: the others may pin it down
    const std::string name = "cam" + std::to_string(k);
    if (n > 1) std::printf("%s (%s ...):\n", name.c_str(), request.takes.front()[k].c_str());
    std::printf("%zu head-foot points of %d walkers wholly in view, in %d frames (%.1f s of video)\n",
                e.points.size(), walkers[k], e.frames, e.fps > 0 ? e.frames / e.fps : 0.0);
    try {
      rig[k].calibration = CalibrateFromWalkers(e.points, e.width, e.height, options);
    } catch (const InputError& error) {
      if (n == 1) throw;
      ThrowInputError(name + " (--walkers " + request.takes.front()[k] + ")", error.what());
    }
    rig[k].calibration.camera.name = name;
    rig[k].points = e.points;
    PrintWalkerCalibration(rig[k].calibration, e.width, intrinsics);
  }
  if (n == 1) {
    PrintPlacement(rig[0].calibration.camera,
                   "above the world origin, looking along +z (one camera cannot see its place on the floor)");
    return {rig[0].calibration.camera};
  }
  RigPlacementOptions options;
  options.person_height_mm = request.person_height_m * 1000;
  options.foot_height_mm = WalkerCalibrationOptions().foot_share * options.person_height_mm;
  const double fps = evidence[0].fps > 0 ? evidence[0].fps : 30;
  options.correlated_frames = std::max(1.0, 0.5 * fps);
  options.max_clock_offset_frames = static_cast<int>(std::lround(request.max_clock_offset_s * fps));
  options.offset_fit_frames = std::max(1, static_cast<int>(std::lround(options.match_mm / 1400 * fps)));
  const RigPlacement placed = PlaceRig(rig, options);
  std::printf("placed from the walkers they share, and refined together (cam0's floor point is the origin, its "
              "view +z):\n");
  std::vector<Camera> cameras;
  for (size_t k = 0; k < n; ++k) {
    const PlacedCamera& c = placed.cameras[k];
    std::printf("  cam%zu: floor point (%.0f, %.0f) +- %.0f mm, turned %.2f +- %.2f degrees; height %.0f +- %.0f mm, "
                "tilt %.2f +- %.2f, roll %.2f +- %.2f degrees, focal length %.1f +- %.1f px",
                k, c.x_mm.value, c.z_mm.value, std::max(c.x_mm.sd, c.z_mm.sd), c.yaw_deg.value, c.yaw_deg.sd,
                c.height_mm.value, c.height_mm.sd, c.tilt_deg.value, c.tilt_deg.sd, c.roll_deg.value, c.roll_deg.sd,
                c.focal_px.value, c.focal_px.sd);
    if (k > 0) {
      std::printf("; %d sightings matched with cam%d's, %.0f mm RMS apart", c.matches, c.placed_against, c.rms_mm);
      if (c.clock_offset_frames != 0) {
        std::printf("; its video started %.2f s (%d frames) %s cam0's", std::abs(c.clock_offset_frames) / fps,
                    std::abs(c.clock_offset_frames), c.clock_offset_frames > 0 ? "after" : "before");
      }
    }
    std::printf("\n");
    cameras.push_back(c.camera);
    cameras.back().clock_offset_s = c.clock_offset_frames / fps;
  }
  return cameras;
}

namespace {

// "a,b,c" -> {"a", "b", "c"}.
std::vector<std::string> SplitCommas(const std::string& text) {
  std::vector<std::string> parts;
  size_t from = 0;
  for (size_t comma; (comma = text.find(',', from)) != std::string::npos; from = comma + 1) {
    parts.push_back(text.substr(from, comma - from));
  }
  parts.push_back(text.substr(from));
  return parts;
}

// FILE[,FILE...]: every one an existing file.
CLI::Validator FileList(const std::string& what, const std::string& name) {
  return CLI::Validator(
      [what](std::string& text) {
        for (const std::string& part : SplitCommas(text)) {
          if (!fs::is_regular_file(part)) return "expected " + what + "; '" + part + "' is no file";
        }
        return std::string();
      },
      name + "[," + name + "...]");
}

void RunCalibrateFromWalkers(const CalibrateArguments& a, const ReadWalkers& read_walkers) {
  WalkerRequest request;
  for (const std::string& take : a.walkers) request.takes.push_back(SplitCommas(take));
  if (!a.background.empty()) request.backgrounds = SplitCommas(a.background);
  if (!a.camera.empty()) request.intrinsics = SplitCommas(a.camera);
  request.max_frames = a.max_frames;
  request.person_height_m = a.person_height_m;
  request.max_clock_offset_s = a.max_clock_offset_s;
  request.fps = a.fps;
  const size_t n = request.takes.front().size();
  // Several cameras: --out is a folder for their camK.yaml (made if missing).
  if (n == 1) {
    CheckOutFolder(a.out);
  } else if (fs::exists(a.out) && !fs::is_directory(a.out)) {
    ThrowInputError("--out " + a.out, "several cameras are written as camK.yaml into a folder; this is a file");
  } else if (!fs::is_directory(fs::absolute(a.out).parent_path())) {
    ThrowInputError("--out " + a.out, "no such folder to make it in");
  }
  const std::vector<Camera> found = CalibrateFromWalkerVideos(request, read_walkers);
  if (n > 1) fs::create_directories(a.out);
  for (size_t k = 0; k < found.size(); ++k) {
    CameraFile file;
    file.camera = found[k];
    if (n == 1) file.camera.name = a.name;
    file.has_extrinsics = true;
    const std::string path = n == 1 ? a.out : (fs::path(a.out) / (found[k].name + ".yaml")).string();
    WriteCameraYaml(file, path);
    std::printf("wrote %s\n", path.c_str());
  }
}

void RunCalibrate(const CalibrateArguments& a) {
  if (a.images.empty() || a.board.empty() || a.square_mm <= 0) {
    ThrowInputError("calibrate", "give --images, --board and --square (a chessboard), or --walkers VIDEO (people "
                                 "walking past a fixed camera)");
  }
  ChessboardOptions options;
  JGPM_CHECK(ParseBoard(a.board, &options.cols, &options.rows));  // validated by CLI11
  options.square_mm = a.square_mm;
  options.distortion_coefficients = a.distortion_coefficients;
  options.fast_check = a.fast_check;
  ChessboardOptions floor_options = options;
  if (!a.floor_board.empty()) JGPM_CHECK(ParseBoard(a.floor_board, &floor_options.cols, &floor_options.rows));
  if (a.floor_square_mm > 0) floor_options.square_mm = a.floor_square_mm;

  // Everything that can be checked before the slow part is.
  CheckOutFolder(a.out);
  std::vector<std::string> paths;
  for (const fs::path& image : ListImages(a.images)) paths.push_back(image.string());
  if (paths.empty()) ThrowInputError("--images " + a.images, "no .png, .jpg, .jpeg, .bmp or .tif images in the folder");
  std::optional<CameraPose> pose;
  if (!a.pose.empty()) pose = ReadCameraPoseYaml(a.pose);
  if (!a.floor_image.empty()) CheckFloorBoard(floor_options);

  std::printf("calibrating from %zu images in %s: board %dx%d inner corners, %g mm squares\n", paths.size(),
              a.images.c_str(), options.cols, options.rows, options.square_mm);
  std::fflush(stdout);
  ProgressLine line("calibrate", 0.2);
  options.progress = [&line](int done, int total) { line.Update(done, total, "images", "looking for the board"); };
  const CalibrationSummary summary = CalibrateFromImages(paths, options);
  line.Finish();
  for (const CalibrationImage& image : summary.images) {
    const std::string name = fs::path(image.path).filename().string();
    if (image.used) {
      std::printf("  %-28s used      RMS %.3f px\n", name.c_str(), image.reprojection_rms_px);
    } else {
      std::printf("  %-28s rejected  %s\n", name.c_str(), image.rejected_because.c_str());
    }
  }
  const Camera& c = summary.camera;
  std::printf("RMS reprojection error %.4f px over %d of %zu images (%.1f s)\n", summary.rms_px, summary.NumUsed(),
              summary.images.size(), summary.wall_seconds);
  std::printf("intrinsics: fx %.3f fy %.3f cx %.3f cy %.3f px, %dx%d\n", c.fx, c.fy, c.cx, c.cy, c.width, c.height);
  std::printf("distortion: %s\n", Distortion(c).c_str());

  CameraFile file;
  file.camera = c;
  file.camera.name = a.name;
  file.avg_reprojection_error_px = summary.rms_px;
  file.has_extrinsics = !a.floor_image.empty() || pose.has_value();
  if (!a.floor_image.empty()) {
    const FloorPlacement placement = PlaceCameraFromFloorBoard(file.camera, a.floor_image, floor_options);
    file.camera = placement.camera;
    char how[512];
    std::snprintf(how, sizeof(how), "by the %dx%d floor board in %s (RMS %.3f px)", floor_options.cols,
                  floor_options.rows, a.floor_image.c_str(), placement.reprojection_rms_px);
    PrintPlacement(file.camera, how);
  } else if (pose) {
    file.camera.cam_from_world_rotation = pose->cam_from_world_rotation;
    file.camera.cam_from_world_translation_mm = pose->cam_from_world_translation_mm;
    PrintPlacement(file.camera, "by " + a.pose);
  } else {
    std::printf("not placed (no --floor-image or --pose): the YAML has no extrinsics yet\n");
  }
  WriteCameraYaml(file, a.out);
  std::printf("wrote %s\n", a.out.c_str());
}

}  // namespace

void AddCalibrationCommands(CLI::App& app, ReadWalkers read_walkers) {
  auto a = std::make_shared<CalibrateArguments>();
  CLI::App* calibrate = app.add_subcommand(
      "calibrate", "Calibrate a camera from chessboard images (OpenCV) and write its YAML; optionally place it in the "
                   "world (y up, floor y = 0, mm) by a chessboard on the floor or a pose file. Or, with --walkers, "
                   "the whole camera from the people walking past it");
  CLI::Option* images =
      calibrate->add_option("--images", a->images, "folder of chessboard images (.png .jpg .jpeg .bmp .tif), all one size")
          ->check(CLI::ExistingDirectory);
  CLI::Option* board = calibrate->add_option("--board", a->board, "inner corners of the board, COLSxROWS (10 x 7 squares: 9x6)")
      ->check(kBoardSize);
  CLI::Option* square = calibrate->add_option("--square", a->square_mm, "side of a square as printed, mm")
      ->check(kPositiveMm);
  calibrate->add_option("--out", a->out,
                        "camera YAML to write (OpenCV's calibration keys plus the pose); several cameras from walkers: "
                        "a folder for their camK.yaml")
      ->required();
  calibrate->add_option("--name", a->name, "camera name written to the YAML")
      ->check(CLI::Validator(
          [](const std::string& name) {
            return ValidCameraName(name) ? std::string() : "expected 1-64 letters, digits, '_', '-' or '.'";
          },
          "NAME"))
      ->capture_default_str();
  CLI::Option* floor = calibrate->add_option(
      "--floor-image", a->floor_image,
      "image of a chessboard lying on the floor: world origin at its first inner corner, +x along its rows, +z "
      "along its columns (one count odd, one even, e.g. 9x6; see calibration/chessboard.h)");
  floor->check(CLI::ExistingFile);
  calibrate->add_option("--floor-board", a->floor_board, "the floor board's inner corners (default: --board)")
      ->check(kBoardSize)
      ->needs(floor);
  calibrate->add_option("--floor-square", a->floor_square_mm, "the floor board's square, mm (default: --square)")
      ->check(kPositiveMm)
      ->needs(floor);
  calibrate->add_option("--pose", a->pose,
                        "YAML with cam_from_world_rotation (3x3) and cam_from_world_translation_mm (3x1)")
      ->check(CLI::ExistingFile)
      ->excludes(floor);
  calibrate->add_option("--distortion", a->distortion_coefficients,
                        "distortion coefficients fitted: 4 (k1 k2 p1 p2), 5 (+k3) or 8 (rational model)")
      ->check(CLI::IsMember({4, 5, 8}))
      ->capture_default_str();
  CLI::Option* fast = calibrate->add_flag("--fast-check", a->fast_check,
                      "give up in milliseconds on images without a board (may miss a board in a poor image)");
  CLI::Option* walkers = calibrate->add_option(
      "--walkers", a->walkers,
      "video of a fixed camera with people walking by (repeat for several videos of the same camera): its focal "
      "length, height, tilt and roll from their heads and feet (no chessboard; calibration/walker_calibration.h); or a "
      "folder of its frames (jgpm capture; with --fps), a synthetic clip folder (jgpm render), its observed masks, or "
      "a live camera, /dev/videoN (fake:VIDEO plays a video as one), for --max-frames (default 900: 30 s at 30 fps). "
      "Several cameras that see the same people: their videos, comma-separated (A.avi,B.avi; "
      "repeat for more takes): each is calibrated, then all are placed in cam0's world from the walkers they share "
      "(calibration/rig_placement.h) and written to the folder --out as camK.yaml");
  walkers
      ->check(CLI::Validator(
          [](std::string& text) {
            for (const std::string& part : SplitCommas(text)) {
              std::error_code ec;
              if (part.rfind("fake:", 0) != 0 && !std::filesystem::exists(part, ec)) {
                return "expected a video, a folder of frames, a clip or a camera device; '" + part +
                       "' does not exist";
              }
            }
            return std::string();
          },
          "PATH[,PATH...]"))
      ->excludes(images)->excludes(board)->excludes(square)->excludes(floor)->excludes(fast);
  calibrate->add_option("--person-height", a->person_height_m, "the walkers' mean height, metres")
      ->check(CLI::Validator(
          [](std::string& text) {
            const std::optional<double> value = ParseNumber(text);
            return value && *value >= 1.0 && *value <= 2.5
                       ? std::string()
                       : "expected the walkers' mean height in metres, 1.0-2.5 (e.g. 1.70), got '" + text + "'";
          },
          "METRES"))
      ->needs(walkers)
      ->capture_default_str();
  calibrate->add_option("--max-clock-offset", a->max_clock_offset_s,
                        "several cameras: how far apart their videos may have started, seconds (0: together); each "
                        "camera's offset is found with its place and written to its YAML as clock_offset_s")
      ->check(CLI::Range(0.0, 60.0))
      ->needs(walkers)
      ->capture_default_str();
  calibrate->add_option("--camera", a->camera,
                        "camera YAML whose intrinsics and lens distortion to keep (a chessboard's); several cameras: "
                        "one per camera, comma-separated")
      ->check(FileList("a camera YAML", "YAML"))
      ->needs(walkers);
  calibrate->add_option("--background", a->background,
                        "picture of the empty scene (default: learnt from the video); several cameras: one per camera, "
                        "comma-separated")
      ->check(FileList("an image", "IMAGE"))
      ->needs(walkers);
  calibrate->add_option("--fps", a->fps, "the frame rate of --walkers folders of frames")
      ->check(CLI::PositiveNumber)
      ->needs(walkers);
  calibrate->add_option("--max-frames", a->max_frames, "use at most this many frames of the video (0: all)")
      ->check(CLI::NonNegativeNumber)
      ->needs(walkers);
  calibrate->callback([a, read_walkers] {
    if (a->walkers.empty()) {
      RunCalibrate(*a);
    } else {
      if (!a->pose.empty()) ThrowInputError("--pose", "places a chessboard-calibrated camera; --walkers places its own");
      RunCalibrateFromWalkers(*a, read_walkers);
    }
  });
}

}  // namespace jgpm::cli
