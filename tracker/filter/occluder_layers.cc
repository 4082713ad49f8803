#include "tracker/filter/occluder_layers.h"

#include <cmath>

#include <opencv2/imgproc.hpp>

namespace jgpm {

std::vector<PaintedObject> SplitPainting(const cv::Mat& painting, const Camera& camera) {
  std::vector<PaintedObject> objects;
  if (painting.empty()) return objects;
  CV_Assert(painting.type() == CV_8UC1);
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(painting != 0, labels, stats, centroids, 8, CV_32S);
  const Eigen::Vector3d eye = camera.CentreInWorld();
  for (int l = 1; l < n; ++l) {
    PaintedObject object;
    object.pixels = labels == l;
    // The middle of the object's lowest row, at the row's lower edge.
    const int bottom = stats.at<int>(l, cv::CC_STAT_TOP) + stats.at<int>(l, cv::CC_STAT_HEIGHT) - 1;
    const int* row = labels.ptr<int>(bottom);
    double sum = 0;
    int count = 0;
    for (int u = 0; u < labels.cols; ++u)
      if (row[u] == l) sum += u, ++count;
    Eigen::Matrix2Xd pixel(2, 1);
    pixel << sum / count, bottom + 0.5;
    const Eigen::Vector3d ray = camera.PixelRaysInWorld(pixel).col(0);
    // Cut by the image's bottom edge, its foot is nearer than the edge, by how much unseen.
    if (bottom < labels.rows - 1 && ray.y() < -1e-6 && eye.y() > 0) {
      const Eigen::Vector3d foot = eye + ray * (-eye.y() / ray.y());
      object.distance_mm = std::hypot(foot.x() - eye.x(), foot.z() - eye.z());
    }
    objects.push_back(std::move(object));
  }
  return objects;
}

Eigen::Vector3d FloorPointUnder(const std::vector<Capsule>& capsules) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Capsule& c : capsules) sum += c.from_mm + c.to_mm;
  if (!capsules.empty()) sum /= 2.0 * capsules.size();
  sum.y() = 0;
  return sum;
}

bool Hides(const PaintedObject& object, const Eigen::Vector3d& floor_point_mm,
           const Eigen::Vector3d& camera_centre_mm) {
  return !std::isfinite(object.distance_mm) ||
         std::hypot(floor_point_mm.x() - camera_centre_mm.x(), floor_point_mm.z() - camera_centre_mm.z()) >
             object.distance_mm;
}

}  // namespace jgpm
