// A calibrated camera: OpenCV's pinhole model with lens distortion, placed in the world by
// `cam_from_world` (x_cam = R x_world + t, millimetres). The world is the motion data's:
// y up, the floor at y = 0, millimetres.
//
// Projection follows OpenCV's model exactly (cv::projectPoints is the test oracle) for the
// 4, 5 and 8 coefficient forms (k1 k2 p1 p2 [k3 [k4 k5 k6]]); it is written out here
// because the silhouette renderer projects a few dozen points per particle and
// cv::projectPoints costs microseconds of set-up per call.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace jgpm {

struct Camera {
  std::string name = "cam0";
  int width = 0;   // image size in pixels
  int height = 0;
  double fx = 0, fy = 0, cx = 0, cy = 0;  // camera_matrix, pixels
  // OpenCV's order k1 k2 p1 p2 k3 k4 k5 k6; unused ones zero.
  std::vector<double> distortion = std::vector<double>(5, 0.0);
  Eigen::Matrix3d cam_from_world_rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d cam_from_world_translation_mm = Eigen::Vector3d::Zero();
  // Seconds added to this camera's video times to put them on the rig's clock (cam0's): a
  // video started 0.4 s after cam0's has 0.4. Found with the placement from the walkers
  // (rig_placement.h); 0 for cameras recording together.
  double clock_offset_s = 0;

  // False, with the reason, unless every value is finite, the focal lengths and image size
  // are positive, there are 4, 5 or 8 distortion coefficients and the rotation is a
  // rotation (orthonormal, determinant +1, to 1e-6).
  bool Check(std::string* why) const;

  Eigen::Matrix3d CameraMatrix() const;
  // The camera's centre in the world, millimetres.
  Eigen::Vector3d CentreInWorld() const;
  Eigen::Vector3d ToCamera(const Eigen::Vector3d& point_in_world_mm) const {
    return cam_from_world_rotation * point_in_world_mm + cam_from_world_translation_mm;
  }
  // Normalised image coordinates (x/z, y/z) -> pixel, through the distortion.
  Eigen::Vector2d DistortToPixel(const Eigen::Vector2d& normalised) const;
  // Pixel of a world point; false (pixel untouched) when the point is not in front of the
  // camera (z <= 1 mm).
  bool Project(const Eigen::Vector3d& point_in_world_mm, Eigen::Vector2d* pixel) const;
  // Unit direction, in the world frame, of the ray through each pixel (u, v) given as the
  // columns of `pixels`: the exact inverse of the distortion (cv::undistortPoints iterated
  // to convergence).
  Eigen::Matrix3Xd PixelRaysInWorld(const Eigen::Matrix2Xd& pixels) const;
};

// A camera's name names files and folders (a clip's masks/NAME/, overlay_NAME.avi), so it
// is 1-64 letters, digits, '_', '-' or '.', starting with a letter or digit.
bool ValidCameraName(const std::string& name);

// A camera at `centre_mm` looking at `target_mm`, image rows pointing down and world +y
// up in the image (no roll). Distortion zero. The target must not be straight above or
// below the centre.
Camera LookAtCamera(const std::string& name, int width, int height, double focal_px,
                    const Eigen::Vector3d& centre_mm, const Eigen::Vector3d& target_mm);

// YAML as OpenCV's calibration sample writes it (`camera_matrix`, `distortion_coefficients`,
// `image_width`, `image_height`, other keys ignored), plus our optional `camera_name`,
// `cam_from_world_rotation` (3x3), `cam_from_world_translation_mm` (3x1) and
// `clock_offset_s` (written when not 0). A file
// without the extrinsics gives a camera at the world origin (has_extrinsics false).
// InputError naming the file and the missing or wrong key.
struct CameraFile {
  Camera camera;
  bool has_extrinsics = false;
  double avg_reprojection_error_px = -1;  // OpenCV's `avg_reprojection_error`; < 0: none
};
CameraFile ReadCameraYaml(const std::string& path);
// Parses YAML text; `source` names it in errors.
CameraFile ParseCameraYaml(const std::string& text, const std::string& source);
// Writes the extrinsics only when has_extrinsics: an unplaced camera stays recognisably
// unplaced.
std::string FormatCameraYaml(const CameraFile& file);
// Written atomically (never a half-written file).
void WriteCameraYaml(const CameraFile& file, const std::string& path);

// Only cam_from_world, from a YAML file holding `cam_from_world_rotation` and
// `cam_from_world_translation_mm` (a camera file, or a file with just those two keys):
// a pose measured some other way for a calibrated camera. InputError naming the file and
// the key when either is missing or wrong.
struct CameraPose {
  Eigen::Matrix3d cam_from_world_rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d cam_from_world_translation_mm = Eigen::Vector3d::Zero();
};
CameraPose ReadCameraPoseYaml(const std::string& path);
// Parses YAML text; `source` names it in errors.
CameraPose ParseCameraPoseYaml(const std::string& text, const std::string& source);

}  // namespace jgpm
