#include "tracker/filter/view_alignment.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Cholesky>
#include <opencv2/core.hpp>

#include "io/base/error.h"

namespace jgpm {
namespace {

// The part of the image both `at` and `at` moved by `shift` cover, as the rectangle at
// `at` (its moved twin is the same rectangle plus `shift`).
cv::Rect Common(const cv::Rect& at, const cv::Point& shift, const cv::Size& size) {
  const cv::Rect image(0, 0, size.width, size.height);
  const cv::Rect moved = (at + shift) & image;
  return (moved - shift) & image & at;
}

}  // namespace

bool ViewAlignmentOptions::Check(std::string* why) const {
  const char* problem = nullptr;
  if (search_px < 1 || search_px > 20) problem = "alignment search_px must be in [1, 20]";
  else if (!(rate > 0 && rate <= 1)) problem = "alignment rate must be in (0, 1]";
  if (problem && why) *why = problem;
  return problem == nullptr;
}

ViewAlignment::ViewAlignment(const std::vector<Camera>& cameras, const ViewAlignmentOptions& options)
    : cameras_(cameras), options_(options), offsets_(cameras.size(), cv::Point2d(0, 0)) {
  std::string why;
  if (!options.Check(&why)) ThrowInputError("tracking options", why);
  for (const Camera& camera : cameras) {
    const double f = 0.5 * (camera.fx + camera.fy);
    limits_.push_back(2 * (f * std::tan(0.7 * std::numbers::pi / 180) + 4));
  }
  active_ = options.enabled && cameras.size() >= 2;
}

cv::Mat ViewAlignment::Apply(int c, const cv::Mat& mask) const {
  const cv::Point shift(static_cast<int>(std::lround(offsets_[c].x)), static_cast<int>(std::lround(offsets_[c].y)));
  if (!active_ || mask.empty() || shift == cv::Point(0, 0)) return mask;
  // out(x) = mask(x + shift)
  cv::Mat out = cv::Mat::zeros(mask.size(), mask.type());
  const cv::Rect to = Common(cv::Rect(0, 0, mask.cols, mask.rows), shift, mask.size());
  if (!to.empty()) mask(to + shift).copyTo(out(to));
  return out;
}

cv::Point ViewAlignment::BestShift(const cv::Mat& silhouette, const cv::Mat& mask, const cv::Rect& region,
                                   int search) {
  JGPM_CHECK(silhouette.size() == mask.size());
  const cv::Rect r = region & cv::Rect(0, 0, mask.cols, mask.rows);
  cv::Point best(0, 0);
  double best_iou = -1;
  cv::Mat both, either;
  for (int dy = -search; dy <= search; ++dy) {
    for (int dx = -search; dx <= search; ++dx) {
      const cv::Point shift(dx, dy);
      const cv::Rect at = Common(r, shift, mask.size());
      if (at.empty()) continue;
      cv::bitwise_and(silhouette(at), mask(at + shift), both);
      cv::bitwise_or(silhouette(at), mask(at + shift), either);
      const int joined = cv::countNonZero(either);
      const double iou = joined > 0 ? static_cast<double>(cv::countNonZero(both)) / joined : 0;
      // Ties go to the smaller shift: no evidence, no move.
      if (iou > best_iou + 1e-12 ||
          (std::abs(iou - best_iou) <= 1e-12 && std::abs(dx) + std::abs(dy) < std::abs(best.x) + std::abs(best.y))) {
        best_iou = iou;
        best = shift;
      }
    }
  }
  return best;
}

void ViewAlignment::Update(const std::vector<cv::Mat>& silhouettes, const std::vector<cv::Mat>& aligned_masks,
                           const std::vector<cv::Rect>& regions, const Eigen::Vector3d& person_mm) {
  if (!active_) return;
  const int n = static_cast<int>(cameras_.size());
  JGPM_CHECK(static_cast<int>(silhouettes.size()) == n && static_cast<int>(aligned_masks.size()) == n &&
             static_cast<int>(regions.size()) == n);
  // Each camera's best shift, and what 1 mm of the person's move along x and z does in
  // its image there (finite differences of the projection, 1 m up the body).
  std::vector<int> seen;
  std::vector<Eigen::Vector2d> shifts;
  std::vector<Eigen::Matrix2d> jacobians;
  const Eigen::Vector3d at(person_mm.x(), 1000, person_mm.z());
  for (int c = 0; c < n; ++c) {
    if (silhouettes[c].empty() || aligned_masks[c].empty() || cv::countNonZero(silhouettes[c]) == 0) continue;
    Eigen::Vector2d p0, px, pz;
    const Camera& camera = cameras_[c];
    if (!camera.Project(at, &p0) || !camera.Project(at + Eigen::Vector3d(10, 0, 0), &px) ||
        !camera.Project(at + Eigen::Vector3d(0, 0, 10), &pz)) {
      continue;
    }
    const cv::Point s = BestShift(silhouettes[c], aligned_masks[c], regions[c], options_.search_px);
    Eigen::Matrix2d j;
    j.col(0) = (px - p0) / 10;
    j.col(1) = (pz - p0) / 10;
    seen.push_back(c);
    shifts.emplace_back(s.x, s.y);
    jacobians.push_back(j);
  }
  if (seen.size() < 2) return;  // one view alone cannot tell its error from the person's place
  // The offsets step towards the best shifts, then lose whatever of them a floor move of
  // the person would do: t minimising sum |o_c - J_c t|^2 is taken out.
  std::vector<Eigen::Vector2d> next(seen.size());
  Eigen::Matrix2d a = Eigen::Matrix2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();
  for (size_t k = 0; k < seen.size(); ++k) {
    const cv::Point2d& d = offsets_[seen[k]];
    next[k] = Eigen::Vector2d(d.x, d.y) + options_.rate * shifts[k];
    a += jacobians[k].transpose() * jacobians[k];
    b += jacobians[k].transpose() * next[k];
  }
  const Eigen::Vector2d t = a.ldlt().solve(b);
  for (size_t k = 0; k < seen.size(); ++k) {
    const Eigen::Vector2d left = next[k] - jacobians[k] * t;
    cv::Point2d& d = offsets_[seen[k]];
    d = cv::Point2d(left.x(), left.y());
    const double length = std::hypot(d.x, d.y);
    if (length > limits_[seen[k]]) d *= limits_[seen[k]] / length;
  }
}

}  // namespace jgpm
