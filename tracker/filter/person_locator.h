// Where the person is, from foreground masks alone: the tracker's automatic start and its
// recovery after a loss. In each camera the largest foreground blob is the person; the
// bottom of the blob is where the feet touch the floor (y = 0), so its ray meets the floor
// at the person's place; the ray through the blob's top, at that place, gives the height.
// Blobs that cannot be a person standing on the floor (under 1 m or over 2.3 m tall, as
// clutter in the air is) are passed over; with several cameras the place that most cameras'
// blobs agree on (within 1 m) is taken, and the answer is the median of those blobs.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "calibration/camera.h"

namespace jgpm {

struct PersonSighting {
  bool found = false;
  Eigen::Vector2d floor_mm = Eigen::Vector2d::Zero();  // (x, z)
  double height_mm = 0;                                // floor to the top of the head
  int cameras = 0;                                     // cameras that saw a blob
  std::vector<cv::Rect> boxes;                         // per camera: the blob's box (empty if none)
};

// Blobs smaller than `min_blob_px` are not a person.
PersonSighting LocatePerson(const std::vector<Camera>& cameras, const std::vector<cv::Mat>& masks,
                            int min_blob_px = 60);

}  // namespace jgpm
