// Particles of the trackers whose prior has no gait manifold (GPLVM, GPDM, B-GPDM,
// LL-GPDM, PCA): a point of the model's latent space plus the shared placement
// (tracker/state/state_model.h), with the walking speed as its rate.
//
// Dynamics, per frame of dt seconds: GPDM family, the latent point moves by the learned
// dynamics' mean step once per 1/30 s (the models learned 30 poses per ~1.1 s cycle, about
// a frame at 30 fps): whole steps, then the fraction of the next, so a dropped frame or a
// 15 fps source advances as far as the time passed) plus noise; the others, a random walk.
// Noise: half the mean training step per 1/30 s, growing with sqrt(dt). Speed and heading are slow random walks; the root moves at the speed along the
// heading. Assumed: one person walking forwards on a flat floor.
#pragma once

#include "prior/model/gait_model.h"
#include "tracker/state/pose_table.h"
#include "tracker/state/state_model.h"

namespace jgpm {

struct LatentDynamics {
  double latent_noise = 0.5;        // in mean training steps (GPDM: around the dynamics' mean)
  double speed_noise_mm_s = 30;
  double heading_noise_deg = 1.0;  // a mixture, as ManifoldDynamics' (tracker/state/manifold_state.h)
  double turn_share = 0.1, turn_noise_deg = 6.0;
  double root_noise_mm = 8;
  double size_noise = 0.001;
  double width_noise = kWidthNoise;
  double min_speed_mm_s = 200, max_speed_mm_s = 2500;
  double min_size = 0.75, max_size = 1.3;
  double min_width = kMinWidth, max_width = kMaxWidth;
  // The annealing's diffusion at its first layer (latent: in mean training steps).
  double latent_diffusion = 1.5, root_diffusion_mm = 30, heading_diffusion_deg = 6, speed_diffusion_mm_s = 60,
         size_diffusion = 0.01, width_diffusion = kWidthDiffusion;
};

class LatentStateModel : public StateModel {
 public:
  static constexpr double kStepsPerSecond = 30;  // dynamics steps per second of the walk

  // `model` and `table` (built from it) must outlive this.
  LatentStateModel(const GaitModel& model, const PoseTable& table, const LatentDynamics& dynamics = {});

  std::string Name() const override { return "latent"; }
  int Dimension() const override { return 9; }
  const Skeleton& skeleton() const override { return model_.skeleton(); }
  void Sample(const InitialGuess& guess, Random* random, double* state) const override;
  void Predict(double dt, Random* random, double* state) const override;
  Eigen::VectorXd DiffusionStd() const override;
  void Normalise(double* state) const override;
  double Period(int dimension) const override;
  double Evaluate(const double* state, Eigen::Matrix3Xd* joints) const override;
  Eigen::VectorXd Pose(const double* state) const override;
  std::vector<std::string> CoordinateNames() const override { return {"x1", "x2", "x3"}; }

 private:
  const GaitModel& model_;
  const PoseTable& table_;
  LimbScaler limbs_;
  LatentDynamics d_;
  double step_;  // mean latent step between consecutive training poses
};

}  // namespace jgpm
