// Pictures a person checks a clip or a track with: the skeleton drawn over a silhouette,
// and a grid of such frames in one PNG.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "calibration/camera.h"
#include "io/mocap/skeleton.h"

namespace jgpm {

// Draws the skeleton's bones (left side red, right side blue, spine and head green) and
// joints, projected through the camera, over `image` (BGR). Joints behind the camera are
// skipped.
void DrawSkeleton(const Skeleton& skeleton, const Camera& camera,
                  const Eigen::Matrix3Xd& joint_in_world_mm, cv::Mat* image);

// A grid of equally sized BGR tiles, `columns` per row, each with its label in the corner.
cv::Mat TileImages(const std::vector<cv::Mat>& tiles, const std::vector<std::string>& labels,
                   int columns);

}  // namespace jgpm
