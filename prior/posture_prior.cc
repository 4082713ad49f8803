#include "prior/posture_prior.h"

#include <map>

#include <Eigen/Eigenvalues>

#include "io/error.h"
#include "io/split.h"

namespace jgpm {

bool PosturePriorOptions::Check(std::string* why) const {
  const char* problem = nullptr;
  if (!(correlation_weight >= 0 && correlation_weight <= 1)) problem = "correlation_weight must be in [0, 1]";
  else if (!(floor_deg > 0)) problem = "floor_deg must be > 0";
  if (problem && why) *why = problem;  // `why` may be null
  return problem == nullptr;
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
  Eigen::MatrixXd spread = Eigen::MatrixXd::Zero(d, d);
  if (n > 1) {
    const Eigen::MatrixXd centred = means.colwise() - means.rowwise().mean();
    spread = centred * centred.transpose() / (n - 1);
  }
  // S with its off-diagonal (its correlations) kept at weight c, plus the floor.
  Eigen::MatrixXd covariance = options.correlation_weight * spread;
  covariance.diagonal() = spread.diagonal().array() + options.floor_deg * options.floor_deg;
  PosturePrior prior;
  prior.Factorise(covariance);
  prior.subjects_ = n;
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
