#include "tracker/filter/person_locator.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace jgpm {
namespace {

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

PersonSighting LocatePerson(const std::vector<Camera>& cameras, const std::vector<cv::Mat>& masks, int min_blob_px) {
  PersonSighting sighting;
  sighting.boxes.assign(cameras.size(), cv::Rect());
  // Per camera, every blob big enough, with where it stands and how tall it is there.
  struct Candidate {
    int area;
    cv::Rect box;
    Eigen::Vector2d floor;
    double height;
  };
  std::vector<std::vector<Candidate>> candidates(cameras.size());
  for (size_t c = 0; c < cameras.size() && c < masks.size(); ++c) {
    if (masks[c].empty()) continue;
    cv::Mat labels, stats, centroids;
    const int n = cv::connectedComponentsWithStats(masks[c] != 0, labels, stats, centroids, 8, CV_32S);
    const Eigen::Vector3d eye = cameras[c].CentreInWorld();
    if (eye.y() <= 0) continue;
    for (int l = 1; l < n; ++l) {
      const int area = stats.at<int>(l, cv::CC_STAT_AREA);
      if (area < min_blob_px) continue;
      const cv::Rect box(stats.at<int>(l, cv::CC_STAT_LEFT), stats.at<int>(l, cv::CC_STAT_TOP),
                         stats.at<int>(l, cv::CC_STAT_WIDTH), stats.at<int>(l, cv::CC_STAT_HEIGHT));
      // The feet: the blob's pixels in its lowest 4 rows; the head: its top row.
      double foot_u = 0, top_u = 0;
      int foot_count = 0, top_count = 0;
      const int bottom = box.y + box.height - 1;
      for (int v = std::max(box.y, bottom - 3); v <= bottom; ++v) {
        const int* row = labels.ptr<int>(v);
        for (int u = box.x; u < box.x + box.width; ++u)
          if (row[u] == l) foot_u += u, ++foot_count;
      }
      const int* top_row = labels.ptr<int>(box.y);
      for (int u = box.x; u < box.x + box.width; ++u)
        if (top_row[u] == l) top_u += u, ++top_count;
      Eigen::Matrix2Xd pixels(2, 2);
      pixels << foot_u / std::max(1, foot_count), top_u / std::max(1, top_count), bottom + 0.5, box.y - 0.5;
      const Eigen::Matrix3Xd rays = cameras[c].PixelRaysInWorld(pixels);
      if (!(rays(1, 0) < -1e-6)) continue;  // the foot ray must go down to the floor
      const Eigen::Vector3d floor = eye + rays.col(0) * (-eye.y() / rays(1, 0));
      // Height: the top ray's point nearest the vertical line through the floor point.
      const Eigen::Vector3d r = rays.col(1);
      const Eigen::Vector2d horizontal(r.x(), r.z());
      const Eigen::Vector2d to_floor(floor.x() - eye.x(), floor.z() - eye.z());
      if (horizontal.squaredNorm() < 1e-12) continue;
      const double along = horizontal.dot(to_floor) / horizontal.squaredNorm();
      const double height = eye.y() + along * r.y();
      // A person stands 1-2.3 m tall; clutter (a blob in the air, a shadow) does not.
      if (!(along > 0 && height > 1000 && height < 2300)) continue;
      candidates[c].push_back({area, box, Eigen::Vector2d(floor.x(), floor.z()), height});
    }
  }
  // The person's place is the candidate place most cameras agree on (a candidate within
  // 1 m), ties going to the larger total blob area: a ghost blob that only one camera sees
  // cannot outvote cameras that agree, even when it is that camera's largest blob.
  constexpr double kAgreeMm = 1000;
  Eigen::Vector2d centre;
  int best_cameras = 0;
  long best_area = -1;
  for (const auto& own : candidates) {
    for (const Candidate& hypothesis : own) {
      int agreeing = 0;
      long area = 0;
      for (const auto& other : candidates) {
        int largest = 0;
        for (const Candidate& q : other)
          if ((q.floor - hypothesis.floor).norm() < kAgreeMm) largest = std::max(largest, q.area);
        agreeing += largest > 0;
        area += largest;
      }
      if (agreeing > best_cameras || (agreeing == best_cameras && area > best_area))
        best_cameras = agreeing, best_area = area, centre = hypothesis.floor;
    }
  }
  if (best_cameras == 0) return sighting;
  std::vector<double> agreeing_x, agreeing_z, heights;
  for (size_t c = 0; c < candidates.size(); ++c) {
    // The blob nearest that place, if near enough.
    int best = -1;
    double nearest = kAgreeMm;
    for (size_t k = 0; k < candidates[c].size(); ++k) {
      const double d = (candidates[c][k].floor - centre).norm();
      if (d < nearest) nearest = d, best = static_cast<int>(k);
    }
    if (best < 0) continue;
    const Candidate& p = candidates[c][best];
    sighting.boxes[c] = p.box;
    agreeing_x.push_back(p.floor.x());
    agreeing_z.push_back(p.floor.y());
    heights.push_back(p.height);
  }
  if (agreeing_x.empty()) return sighting;
  sighting.found = true;
  sighting.cameras = static_cast<int>(agreeing_x.size());
  sighting.floor_mm = Eigen::Vector2d(Median(agreeing_x), Median(agreeing_z));
  sighting.height_mm = Median(heights);
  return sighting;
}

}  // namespace jgpm
