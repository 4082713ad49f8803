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

// (CLI11's PositiveNumber would print its range up to DBL_MAX.)
const CLI::Validator kPositiveMm(
    [](std::string& text) {
      size_t used = 0;
      double value = 0;
      try {
        value = std::stod(text, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      return used == text.size() && std::isfinite(value) && value > 0
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

void RunCalibrate(const CalibrateArguments& a) {
  ChessboardOptions options;
  JGPM_CHECK(ParseBoard(a.board, &options.cols, &options.rows));  // validated by CLI11
  options.square_mm = a.square_mm;
  options.distortion_coefficients = a.distortion_coefficients;
  options.fast_check = a.fast_check;
  ChessboardOptions floor_options = options;
  if (!a.floor_board.empty()) JGPM_CHECK(ParseBoard(a.floor_board, &floor_options.cols, &floor_options.rows));
  if (a.floor_square_mm > 0) floor_options.square_mm = a.floor_square_mm;

  // Everything that can be checked before the slow part is.
  const fs::path out_folder = fs::path(a.out).parent_path();
  if (!out_folder.empty() && !fs::is_directory(out_folder)) ThrowInputError("--out " + a.out, "no such folder");
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

void AddCalibrationCommands(CLI::App& app) {
  auto a = std::make_shared<CalibrateArguments>();
  CLI::App* calibrate = app.add_subcommand(
      "calibrate", "Calibrate a camera from chessboard images (OpenCV) and write its YAML; optionally place it in the "
                   "world (y up, floor y = 0, mm) by a chessboard on the floor or a pose file");
  calibrate->add_option("--images", a->images, "folder of chessboard images (.png .jpg .jpeg .bmp .tif), all one size")
      ->required()
      ->check(CLI::ExistingDirectory);
  calibrate->add_option("--board", a->board, "inner corners of the board, COLSxROWS (10 x 7 squares: 9x6)")
      ->required()
      ->check(kBoardSize);
  calibrate->add_option("--square", a->square_mm, "side of a square as printed, mm")
      ->required()
      ->check(kPositiveMm);
  calibrate->add_option("--out", a->out, "camera YAML to write (OpenCV's calibration keys plus the pose)")->required();
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
  calibrate->add_flag("--fast-check", a->fast_check,
                      "give up in milliseconds on images without a board (may miss a board in a poor image)");
  calibrate->callback([a] { RunCalibrate(*a); });
}

}  // namespace jgpm::cli
