// The classic baseline without a learned prior (Deutscher's annealed particle filter, as
// PARSEC's bodytrack runs it): particles search the 43 joint-angle channels and the root
// directly. What it knows of walking is only what a classic tracker is given: each
// channel's range (the training poses' range plus 10 degrees, as joint limits) and its
// typical change per frame (from consecutive training poses), which set the process and
// diffusion noise; it starts from the training poses' mean pose. No pose is more likely
// than another inside the limits (ln p = 0).
#pragma once

#include <memory>

#include "prior/model/gait_model.h"
#include "tracker/state/state_model.h"

namespace jgpm {

class JointSpaceStateModel : public StateModel {
 public:
  // Uses the model's skeleton and training poses only (not its latent space); `model`
  // must outlive this. `known_size`: the skeleton is the subject's own, size stays 1.
  explicit JointSpaceStateModel(const GaitModel& model, bool known_size = false);

  std::string Name() const override { return "joint-space"; }
  int Dimension() const override { return channels_ + 6; }
  const Skeleton& skeleton() const override { return model_.skeleton(); }
  void Sample(const InitialGuess& guess, Random* random, double* state) const override;
  void Predict(double dt, Random* random, double* state) const override;
  Eigen::VectorXd DiffusionStd() const override;
  void Normalise(double* state) const override;
  double Period(int dimension) const override;
  double Evaluate(const double* state, Eigen::Matrix3Xd* joints) const override;
  Eigen::VectorXd Pose(const double* state) const override;
  std::vector<std::string> CoordinateNames() const override;
  void SetProportions(const Proportions& proportions) override {
    StateModel::SetProportions(proportions);
    placer_.SetProportions(proportions);
  }
  void SetFloor(double floor_mm) override {
    StateModel::SetFloor(floor_mm);
    placer_.SetFloor(floor_mm);
  }

 private:
  bool known_size_ = false;
  const GaitModel& model_;
  int channels_;
  PosePlacer placer_;
  Eigen::VectorXd mean_, spread_, step_, low_, high_;  // per channel, degrees
};

}  // namespace jgpm
