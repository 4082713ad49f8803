#include "prior/model/latent_density.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <nanoflann.hpp>

#include "io/base/error.h"

namespace jgpm {
namespace {
constexpr double kTwoPi = 2 * std::numbers::pi;
}  // namespace

LatentDensity::LatentDensity(const Eigen::MatrixXd& points, int neighbours) : points_(points) {
  const int n = static_cast<int>(points_.rows());
  JGPM_CHECK(neighbours >= 1 && n > neighbours && points_.cols() == 3);
  // Width: the median distance from a point to its k-th nearest neighbour (the first of its
  // k + 1 nearest being itself or a duplicate at distance 0).
  const nanoflann::KDTreeEigenMatrixAdaptor<Eigen::MatrixXd> tree(3, std::cref(points_));
  std::vector<double> nearest(n);
  std::vector<Eigen::Index> index(neighbours + 1);
  std::vector<double> distance2(neighbours + 1);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d query = points_.row(i).transpose();
    tree.index->knnSearch(query.data(), neighbours + 1, index.data(), distance2.data());
    nearest[i] = distance2[neighbours];
  }
  std::nth_element(nearest.begin(), nearest.begin() + n / 2, nearest.end());
  width_ = std::max(1e-6, std::sqrt(nearest[n / 2]));
  log_n_ = std::log(static_cast<double>(n));
  log_width_ = std::log(width_);
}

double LatentDensity::LogDensity(const Eigen::Vector3d& x, Eigen::Vector3d* gradient) const {
  const double h2 = width_ * width_;
  const Eigen::VectorXd d2 = (points_.rowwise() - x.transpose()).rowwise().squaredNorm();
  const double nearest = d2.minCoeff();
  const Eigen::VectorXd w = (-(d2.array() - nearest) / (2 * h2)).exp();
  const double sum = w.sum();
  if (gradient) *gradient = (points_.transpose() * w / sum - x) / h2;
  return std::log(sum) - nearest / (2 * h2) - log_n_ - 3 * log_width_ - 1.5 * std::log(kTwoPi);
}

double LatentDensity::LogDensity(const Eigen::Vector3d& x, Eigen::Ref<Eigen::VectorXd> distances2) const {
  JGPM_CHECK(distances2.size() == points_.rows());
  const double h2 = width_ * width_;
  distances2 = (points_.rowwise() - x.transpose()).rowwise().squaredNorm();
  const double nearest = distances2.minCoeff();
  const double sum = (-(distances2.array() - nearest) / (2 * h2)).exp().sum();
  return std::log(sum) - nearest / (2 * h2) - log_n_ - 3 * log_width_ - 1.5 * std::log(kTwoPi);
}

}  // namespace jgpm
