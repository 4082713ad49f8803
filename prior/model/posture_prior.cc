#include "prior/model/posture_prior.h"

#include <cmath>
#include <limits>
#include <map>
#include <numbers>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "io/base/error.h"
#include "io/gait/split.h"

namespace jgpm {

bool PosturePriorOptions::Check(std::string* why) const {
  const char* problem = nullptr;
  if (!(correlation_weight >= 0 && correlation_weight <= 1)) problem = "correlation_weight must be in [0, 1]";
  else if (!(floor_deg > 0)) problem = "floor_deg must be > 0";
  if (problem && why) *why = problem;  // `why` may be null
  return problem == nullptr;
}

namespace {

// The unbiased covariance of the columns of `means` (D x n); zero for one column.
Eigen::MatrixXd Spread(const Eigen::MatrixXd& means) {
  const Eigen::Index n = means.cols();
  if (n < 2) return Eigen::MatrixXd::Zero(means.rows(), means.rows());
  const Eigen::MatrixXd centred = means.colwise() - means.rowwise().mean();
  return centred * centred.transpose() / static_cast<double>(n - 1);
}

// Sigma: S with its off-diagonal (its correlations) kept at weight c, plus the floor.
Eigen::MatrixXd Shrunk(const Eigen::MatrixXd& spread, double correlation_weight, double floor_deg) {
  Eigen::MatrixXd covariance = correlation_weight * spread;
  covariance.diagonal() = spread.diagonal().array() + floor_deg * floor_deg;
  return covariance;
}

}  // namespace

double HeldOutSubjectLogDensity(const Eigen::MatrixXd& means, double correlation_weight, double floor_deg) {
  const Eigen::Index d = means.rows(), n = means.cols();
  JGPM_CHECK(n >= 3 && floor_deg > 0);
  double sum = 0;
  for (Eigen::Index held = 0; held < n; ++held) {
    Eigen::MatrixXd others(d, n - 1);
    for (Eigen::Index s = 0, k = 0; s < n; ++s) {
      if (s != held) others.col(k++) = means.col(s);
    }
    // The floor keeps Sigma's eigenvalues >= floor^2, so a plain Cholesky cannot fail.
    const Eigen::LLT<Eigen::MatrixXd> llt(Shrunk(Spread(others), correlation_weight, floor_deg));
    JGPM_CHECK(llt.info() == Eigen::Success);
    const Eigen::VectorXd whitened = llt.matrixL().solve(means.col(held) - others.rowwise().mean());
    const double log_det = 2 * llt.matrixLLT().diagonal().array().log().sum();
    sum += -0.5 * (whitened.squaredNorm() + log_det + static_cast<double>(d) * std::log(2 * std::numbers::pi));
  }
  return sum / static_cast<double>(n);
}

PosturePrior PosturePrior::FromTrainingSet(const TrainingSet& set, const PosturePriorOptions& options) {
  std::string why;
  if (!options.Check(&why)) ThrowInputError("posture prior options", why);
  const int d = set.NumChannels(), p = set.poses_per_gait;
  JGPM_CHECK(d > 0 && p > 0 && set.NumGaits() > 0);
  // Each subject's mean posture: the mean of its cycles' means. Scaling a cycle keeps its
  // mean (eq. 5), so the first layer serves whatever its scale.
  std::map<std::string, std::pair<Eigen::VectorXd, int>> subjects;
  for (int g = 0; g < set.NumGaits(); ++g) {
    TrialId id;
    const std::string subject = ParseTrialId(set.gait_ids[g], &id) ? id.subject : set.gait_ids[g];
    auto [it, fresh] = subjects.try_emplace(subject, Eigen::VectorXd::Zero(d), 0);
    it->second.first += set.y_deg.middleRows(set.Row(0, g, 0), p).colwise().mean().transpose();
    ++it->second.second;
  }
  const int n = static_cast<int>(subjects.size());
  Eigen::MatrixXd means(d, n);
  int s = 0;
  for (const auto& [name, sum] : subjects) means.col(s++) = sum.first / sum.second;

  PosturePrior prior;
  prior.subjects_ = n;
  prior.correlation_weight_ = options.correlation_weight;
  prior.floor_deg_ = options.floor_deg;
  prior.selected_ = options.select && n >= 3;
  if (prior.selected_) {
    double best = -std::numeric_limits<double>::infinity();
    for (const double c : kPostureCorrelationWeights) {
      for (const double floor : kPostureFloorsDeg) {
        const double score = HeldOutSubjectLogDensity(means, c, floor);
        if (score > best) {  // strict: ties keep the less correlated, smaller floor
          best = score;
          prior.correlation_weight_ = c;
          prior.floor_deg_ = floor;
        }
      }
    }
  }
  prior.Factorise(Shrunk(Spread(means), prior.correlation_weight_, prior.floor_deg_));
  return prior;
}

PosturePrior::PosturePrior(const Eigen::MatrixXd& covariance_deg2) { Factorise(covariance_deg2); }

void PosturePrior::Factorise(const Eigen::MatrixXd& c) {
  if (c.rows() < 1 || c.rows() != c.cols() || !c.allFinite() || !c.isApprox(c.transpose(), 1e-12)) {
    ThrowInputError("posture prior", "the covariance must be a finite symmetric D x D matrix");
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(c);
  if (eigen.info() != Eigen::Success || !(eigen.eigenvalues().minCoeff() > 1e-12 * eigen.eigenvalues().maxCoeff())) {
    ThrowInputError("posture prior", "the covariance is not positive definite");
  }
  covariance_ = c;
  root_ = eigen.eigenvectors() * eigen.eigenvalues().cwiseSqrt().asDiagonal();
  whitening_ = eigen.eigenvalues().cwiseSqrt().cwiseInverse().asDiagonal() * eigen.eigenvectors().transpose();
}

}  // namespace jgpm
