#include "tracker/filter/pose_refiner.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "io/base/error.h"

namespace jgpm {
namespace {


// Training points the prior's variance is first bounded from.
constexpr int kVarianceNeighbours = 32;

// The blocks searched together: joints whose channels move one part of the silhouette.
const std::vector<std::vector<std::string>>& BlockBones() {
  static const std::vector<std::vector<std::string>> blocks = {
      {"lhumerus", "lradius", "lwrist"}, {"rhumerus", "rradius", "rwrist"}, {"lfemur", "ltibia", "lfoot"},
      {"rfemur", "rtibia", "rfoot"},     {"root", "lowerback", "upperback", "thorax"}, {"lowerneck", "upperneck", "head"},
  };
  return blocks;
}

// Placement's spread per unit of step (mm, mm, radians, size) and its penalty's scale.
constexpr double kPlacementStep[4] = {3.0, 3.0, std::numbers::pi / 180, 0.003};
constexpr double kPlacementScale[4] = {40, 40, 5 * std::numbers::pi / 180, 0.03};

}  // namespace

bool RefinementOptions::Check(std::string* why) const {
  const char* problem = nullptr;
  if (rounds < 0 || rounds > 20) problem = "rounds must be in [0, 20]";
  else if (candidates < 1 || candidates > 1000) problem = "candidates must be in [1, 1000]";
  else if (!(step_deg > 0) || !(step_shrink > 0 && step_shrink <= 1)) problem = "steps must be positive";
  else if (!(floor_deg > 0)) problem = "floor_deg must be > 0";
  else if (!(temperature > 0)) problem = "temperature must be > 0";
  else if (!(offset_rate >= 0 && offset_rate <= 1)) problem = "offset_rate must be in [0, 1]";
  else if (!posture.Check(why)) return false;
  if (problem && why) *why = problem;  // `why` may be null
  return problem == nullptr;
}

PoseRefiner::PoseRefiner(const GaitModel& model, const SilhouetteLikelihood& likelihood, const BodyModel& body,
                         const RefinementOptions& options, ThreadPool* pool)
    : model_(model), likelihood_(likelihood), body_(body), options_(options), pool_(pool), placer_(model.skeleton()) {
  std::string why;
  if (!options.Check(&why)) ThrowInputError("refinement options", why);
  const std::vector<std::string>& names = model.data().set.channel_names;
  for (const std::vector<std::string>& bones : BlockBones()) {
    std::vector<int> channels;
    for (size_t c = 0; c < names.size(); ++c) {
      const std::string bone = names[c].substr(0, names[c].find('.'));
      if (std::find(bones.begin(), bones.end(), bone) != bones.end()) channels.push_back(static_cast<int>(c));
    }
    if (!channels.empty()) blocks_.push_back(channels);
  }
  if (options.adapt_posture) posture_.emplace(PosturePrior::FromTrainingSet(model.data().set), options.posture);
  Reset();
  for (int w = 0; w < pool->size(); ++w) scratch_.push_back({Eigen::Matrix3Xd(), {}, likelihood.NewWorkspace()});
}

void PoseRefiner::Reset() {
  offset_ = Eigen::VectorXd::Zero(model_.NumChannels());
  if (posture_) posture_->Reset();
}

double PoseRefiner::Cost(const Eigen::VectorXd& pose, const double* p, double width,
                         const std::vector<CameraObservation>& observations, int worker) const {
  Scratch& s = scratch_[worker];
  placer_.Place(pose.data(), p[0], p[1], p[2], p[3], &s.joints);
  body_.Place(s.joints, &s.capsules);
  for (Capsule& c : s.capsules) {
    c.radius_from_mm *= p[3] * width;
    c.radius_to_mm *= p[3] * width;
  }
  return likelihood_.Cost(s.capsules, observations, &s.workspace);
}

PoseRefiner::Result PoseRefiner::Refine(const Eigen::VectorXd& pose_deg, const Eigen::Vector3d& latent, double x_mm,
                                        double z_mm, double heading_rad, double size, double width,
                                        const std::vector<CameraObservation>& observations, int frame) {
  // The prior's standard deviation per channel, degrees.
  // s_k = max(sqrt(variance) scale_k, floor): when a bound on the variance from the nearest
  // training points (O(1)) already leaves every channel at the floor, as near the
  // manifold, the exact O(N^2) variance (~0.7 ms for ML-JGPM) is not needed.
  const double floor_variance = std::pow(options_.floor_deg / model_.data().set.scale.maxCoeff(), 2);
  double variance = model_.VarianceBound(latent, kVarianceNeighbours);
  Eigen::VectorXd mean_pose;
  if (variance > floor_variance) model_.Predict(latent, &mean_pose, &variance);
  const Eigen::VectorXd s = (std::sqrt(std::max(variance, 0.0)) * model_.data().set.scale.transpose())
                                .cwiseMax(options_.floor_deg);
  const double start[4] = {x_mm, z_mm, heading_rad, size};
  const Eigen::VectorXd centre = posture_ ? Eigen::VectorXd(pose_deg + offset_) : pose_deg;
  auto energy = [&](const Eigen::VectorXd& pose, const double* p, int worker) {
    double penalty = 0.5 * ((pose - centre).cwiseQuotient(s)).squaredNorm();
    for (int i = 0; i < 4; ++i) penalty += 0.5 * std::pow((p[i] - start[i]) / kPlacementScale[i], 2);
    return Cost(pose, p, width, observations, worker) / options_.temperature + penalty;
  };
  Result r;
  r.cost_before = Cost(pose_deg, start, width, observations, 0);
  Eigen::VectorXd current = pose_deg + offset_;
  double placement[4] = {x_mm, z_mm, heading_rad, size};
  double best = energy(current, placement, 0);
  r.evaluations = 2;
  const int n = options_.candidates;
  std::vector<Eigen::VectorXd> poses(n);
  std::vector<std::array<double, 4>> places(n);
  std::vector<double> energies(n);
  double step = options_.step_deg;
  for (int round = 0; round < options_.rounds; ++round, step *= options_.step_shrink) {
    for (size_t b = 0; b <= blocks_.size(); ++b) {  // the last block is the placement
      pool_->For(n, [&](int begin, int end, int worker) {
        for (int i = begin; i < end; ++i) {
          Random random(options_.seed, frame, 64 * round + b, i);
          poses[i] = current;
          for (int k = 0; k < 4; ++k) places[i][k] = placement[k];
          if (b < blocks_.size()) {
            for (int c : blocks_[b]) poses[i][c] += step * random.Normal();
          } else {
            for (int k = 0; k < 4; ++k) places[i][k] += step * kPlacementStep[k] * random.Normal();
            if (!options_.refine_size) places[i][3] = placement[3];
          }
          energies[i] = energy(poses[i], places[i].data(), worker);
        }
      });
      r.evaluations += n;
      const int i = static_cast<int>(std::min_element(energies.begin(), energies.end()) - energies.begin());
      if (energies[i] < best) {
        best = energies[i];
        current = poses[i];
        for (int k = 0; k < 4; ++k) placement[k] = places[i][k];
      }
    }
  }
  if (posture_) {
    posture_->Add(current - pose_deg);
    offset_ = posture_->offset();
  } else {
    offset_ += options_.offset_rate * ((current - pose_deg) - offset_);
  }
  r.pose_deg = current;
  r.x_mm = placement[0];
  r.z_mm = placement[1];
  r.heading_rad = placement[2];
  r.size = placement[3];
  r.cost_after = Cost(current, placement, width, observations, 0);
  return r;
}

}  // namespace jgpm
