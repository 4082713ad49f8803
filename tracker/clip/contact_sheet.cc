#include "tracker/clip/contact_sheet.h"

#include <opencv2/imgproc.hpp>

#include "io/base/error.h"

namespace jgpm {

void DrawSkeleton(const Skeleton& skeleton, const Camera& camera,
                  const Eigen::Matrix3Xd& joint_in_world_mm, cv::Mat* image) {
  JGPM_CHECK(joint_in_world_mm.cols() == static_cast<int>(skeleton.bones.size()));
  constexpr int kShift = 3;
  auto pixel = [&](int joint, cv::Point* p) {
    Eigen::Vector2d q;
    if (!camera.Project(joint_in_world_mm.col(joint), &q)) return false;
    *p = cv::Point(static_cast<int>(q.x() * (1 << kShift)), static_cast<int>(q.y() * (1 << kShift)));
    return true;
  };
  for (size_t b = 1; b < skeleton.bones.size(); ++b) {
    const std::string& name = skeleton.bones[b].name;
    const cv::Scalar colour = name[0] == 'l' && name != "lowerback" && name != "lowerneck"
                                  ? cv::Scalar(40, 40, 230)
                              : name[0] == 'r' ? cv::Scalar(230, 90, 30)
                                               : cv::Scalar(40, 190, 40);
    cv::Point a, e;
    if (pixel(skeleton.bones[b].parent, &a) && pixel(static_cast<int>(b), &e))
      cv::line(*image, a, e, colour, 1, cv::LINE_AA, kShift);
  }
  for (int j = 0; j < joint_in_world_mm.cols(); ++j) {
    cv::Point p;
    if (pixel(j, &p)) cv::circle(*image, p, 1 << kShift, cv::Scalar(0, 220, 255), -1, cv::LINE_AA, kShift);
  }
}

cv::Mat TileImages(const std::vector<cv::Mat>& tiles, const std::vector<std::string>& labels,
                   int columns) {
  JGPM_CHECK(!tiles.empty() && tiles.size() == labels.size() && columns > 0);
  const cv::Size size = tiles[0].size();
  const int rows = (static_cast<int>(tiles.size()) + columns - 1) / columns;
  cv::Mat sheet(rows * size.height, std::min<int>(columns, tiles.size()) * size.width, CV_8UC3,
                cv::Scalar(40, 40, 40));
  for (size_t i = 0; i < tiles.size(); ++i) {
    JGPM_CHECK(tiles[i].size() == size && tiles[i].type() == CV_8UC3);
    const cv::Rect cell((i % columns) * size.width, (i / columns) * size.height, size.width, size.height);
    tiles[i].copyTo(sheet(cell));
    cv::rectangle(sheet, cell, cv::Scalar(90, 90, 90), 1);
    cv::putText(sheet, labels[i], cell.tl() + cv::Point(5, 16), cv::FONT_HERSHEY_SIMPLEX, 0.45,
                cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  }
  return sheet;
}

}  // namespace jgpm
