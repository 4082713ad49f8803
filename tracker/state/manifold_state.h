// Particles of the JGPM family's trackers: a point of the joint gait-pose manifold (pose
// phase along the walking cycle, position along the gait manifold, stride scale), plus the
// shared placement (tracker/state/state_model.h) with the cadence as its rate.
//
// Dynamics, per frame of dt seconds (noise standard deviations are per 1/30 s and grow with
// sqrt(dt)):
//   phase   += cadence dt + noise: the walking cycle advances at the cadence; a negative
//           cadence runs it back, which is walking backwards (backward walking is close to
//           forward walking played in reverse);
//   cadence, gait position, stride scale, heading, size, width: slow random walks (a walker keeps
//           their style; the layers of a multi-layer model are reached by the scale's drift);
//   root    += stride(gait, scale) size cadence dt along the heading, + noise: a walker
//           moves as far per cycle as the stance foot is carried back (prior/pose_table.h),
//           which ties speed to stride and cadence instead of leaving it free (against the
//           heading when the cadence is negative).
// The cadence keeps its sign: its noise never takes a walker from forwards to backwards
// (the tracker negates every particle's cadence at once when the estimates' travel goes
// against their dynamics: tracker/filter/travel_check.h), and a walker who stops keeps
// the way they were going (Pace brings the cadence down to min_cadence, the legs all but
// still).
// Assumed: one person walking on a flat floor (y = 0, or the height the tracker learns:
// StateModel::SetFloor), facing where they go or its opposite.
#pragma once

#include "prior/model/gait_model.h"
#include "tracker/state/pose_table.h"
#include "tracker/state/state_model.h"

namespace jgpm {

struct ManifoldDynamics {
  double phase_noise = 0.015;     // cycles
  double cadence_noise = 0.01;    // cycles per second
  double gait_noise = 0.03;       // gait positions
  double scale_noise = 0.01;
  // The heading's random walk is a mixture: people walk straight most of the time (1
  // degree a frame) and now and then turn 90 degrees in a second or two, so a tenth of
  // the particles each frame turns with 6 degrees a frame. One noise of 2.5 degrees for
  // all helped the turning tuning clip (147 -> 137 mm) and hurt the occluded monocular one
  // (153 -> 162 mm) and a monocular straight walk, where the heading is what places the
  // body in depth; the mixture was chosen on the realism tuning clips (4 seeds).
  double heading_noise_deg = 1.0;
  double turn_share = 0.1, turn_noise_deg = 6.0;
  double root_noise_mm = 8;
  double size_noise = 0.001;
  double width_noise = kWidthNoise;
  // Cycles per second, either way. A walker who stops is at min_cadence: a twentieth of a
  // cycle a second, a standing person's sway, and above 0 so that the annealing's
  // diffusion (0.03 at its first layer) hardly ever turns the walk's direction through a
  // stop (from 0.05 it takes a 3-sigma step). The tracker brings a stop's cadence down
  // (TrackerOptions::pace); the dynamics alone never do, as each frame is fitted alone.
  double min_cadence = 0.05, max_cadence = 1.6;
  // The least cadence of a walker (a slow walk's): always when nothing paces it
  // (TrackerOptions::pace off), and where the pace sees them go at stop_speed_mm_s or
  // faster. Free down to min_cadence there, walkers at 1 m/s drifted to 0.4 cycles a
  // second (07_03 seed 1: 0.37-0.4).
  double walking_min_cadence = 0.5;
  // Slower than this the pace sets the cadence that covers the speed (a stop, a shuffle);
  // faster, it only keeps the cadence at walking_min_cadence or more, and the annealing
  // chooses it. Set to cover every speed, the pace fed itself where the images say little
  // of depth: a monocular estimate follows its prediction along the line of sight, so
  // the speed it is seen to go is the cadence's own, and on vtest.avi (--person auto, one
  // camera 5.7 m up) the cadence ran to 1.6 and the walker was lost 4 times (49 frames,
  // against 2 without the pace). 300 mm/s: a quarter of a walking pace, above what a
  // standing person's estimate wanders (2-8 mm over a 1.5 s stop on 07_07).
  double stop_speed_mm_s = 300;
  double min_size = 0.75, max_size = 1.3;
  double min_width = kMinWidth, max_width = kMaxWidth;
  // A start without a manifold point draws the stride scale from N(1, start_scale_std)
  // within the layers' range (0: uniform over it). Scale 1 is the recorded strides; the
  // other layers are the training data stretched or shrunk (eq. 5) to cover other people,
  // so most walkers are near 1 and a uniform start spends most particles far from it.
  // Checked on the realism tuning clips (5 clips, seeds 1-3, bodytrack 14 mean absolute mm;
  // 0.15 gives 127.5): 0.075 gives 196.9 (one start fails outright), 0.3 gives 140.9.
  double start_scale_std = 0.15;
  // The annealing's diffusion at its first layer.
  double phase_diffusion = 0.04, gait_diffusion = 0.4, scale_diffusion = 0.06, root_diffusion_mm = 30,
         heading_diffusion_deg = 6, cadence_diffusion = 0.03, size_diffusion = 0.01,
         width_diffusion = kWidthDiffusion;
};

class ManifoldStateModel : public StateModel {
 public:
  // `model` (a JGPM-family model) and `table` (built from it) must outlive this.
  ManifoldStateModel(const GaitModel& model, const PoseTable& table, const ManifoldDynamics& dynamics = {});

  std::string Name() const override { return "manifold"; }
  int Dimension() const override { return 9; }
  const Skeleton& skeleton() const override { return model_.skeleton(); }
  void Sample(const InitialGuess& guess, Random* random, double* state) const override;
  void Predict(double dt, Random* random, double* state) const override;
  void Pace(double speed_mm_s, double share, double* state, bool cover = false) const override;
  Eigen::VectorXd DiffusionStd() const override;
  void Normalise(double* state) const override;
  double Period(int dimension) const override;
  double Evaluate(const double* state, Eigen::Matrix3Xd* joints) const override;
  Eigen::VectorXd Pose(const double* state) const override;
  std::vector<std::string> CoordinateNames() const override { return {"phase", "gait", "scale"}; }

 private:
  const GaitModel& model_;
  const PoseTable& table_;
  LimbScaler limbs_;
  ManifoldDynamics d_;
};

}  // namespace jgpm
