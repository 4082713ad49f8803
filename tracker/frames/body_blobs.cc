#include "tracker/frames/body_blobs.h"

#include <algorithm>

#include <opencv2/imgproc.hpp>

namespace jgpm {

int BodyBlobs(const cv::Mat& mask, cv::Mat* labels, std::vector<int>* areas, std::vector<cv::Rect>* boxes) {
  cv::Mat stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask != 0, *labels, stats, centroids, 8, CV_32S);
  std::vector<int> root(n);
  for (int l = 0; l < n; ++l) root[l] = l;
  const auto find = [&](int l) {
    while (root[l] != l) l = root[l] = root[root[l]];
    return l;
  };
  auto box_of = [&](int l) {
    return cv::Rect(stats.at<int>(l, cv::CC_STAT_LEFT), stats.at<int>(l, cv::CC_STAT_TOP),
                    stats.at<int>(l, cv::CC_STAT_WIDTH), stats.at<int>(l, cv::CC_STAT_HEIGHT));
  };
  for (int a = 1; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      const cv::Rect p = box_of(a), q = box_of(b);
      const int overlap = std::min(p.x + p.width, q.x + q.width) - std::max(p.x, q.x);
      const int gap = std::max(p.y, q.y) - std::min(p.y + p.height, q.y + q.height);
      const int joint = std::max(p.y + p.height, q.y + q.height) - std::min(p.y, q.y);
      if (overlap >= 0.5 * std::min(p.width, q.width) && gap >= 0 && gap < 0.1 * joint) root[find(b)] = find(a);
    }
  }
  std::vector<int> joined(n, 0);
  int count = 1;
  for (int l = 1; l < n; ++l)
    if (find(l) == l) joined[l] = count++;
  areas->assign(count, 0);
  boxes->assign(count, cv::Rect());
  for (int l = 1; l < n; ++l) {
    const int j = joined[find(l)];
    (*areas)[j] += stats.at<int>(l, cv::CC_STAT_AREA);
    (*boxes)[j] = (*boxes)[j].empty() ? box_of(l) : ((*boxes)[j] | box_of(l));
  }
  if (count < n) {
    for (int v = 0; v < labels->rows; ++v) {
      int* row = labels->ptr<int>(v);
      for (int u = 0; u < labels->cols; ++u) row[u] = joined[find(row[u])];
    }
  }
  return count;
}

}  // namespace jgpm
