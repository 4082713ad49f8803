// Particles of the latent-space trackers (tracker/state/latent_state.h): the GPDM dynamics
// advance as far as the time that passed, a step per 1/30 s (they took one step per frame
// whatever the frame's length), against the model's own NextLatent.
#include "tracker/state/latent_state.h"

#include <gtest/gtest.h>

#include "prior/prior_test_support.h"
#include "tracker/state/random.h"

namespace jgpm {
namespace {

TEST(LatentState, DynamicsAdvanceAsFarAsTheTimePassed) {
  const auto model = test::TrainOnFirstWalks(ModelKind::kGpdm, 3, 5);
  ASSERT_TRUE(model->HasDynamics());
  const PoseTable table(*model, {});
  LatentDynamics quiet;  // no noise: the mean step alone
  quiet.latent_noise = quiet.speed_noise_mm_s = quiet.heading_noise_deg = quiet.turn_noise_deg = 0;
  quiet.root_noise_mm = quiet.size_noise = 0;
  const LatentStateModel states(*model, table, quiet);
  const Eigen::Vector3d x0 = model->latent().row(12).transpose();
  const Eigen::Vector3d x1 = model->NextLatent(x0, nullptr), x2 = model->NextLatent(x1, nullptr);
  auto predict = [&](double dt) {
    double s[9] = {x0.x(), x0.y(), x0.z(), 100, 200, 0, 1200, 1, 1};
    Random random(1);
    states.Predict(dt, &random, s);
    return std::pair{Eigen::Vector3d(s[0], s[1], s[2]), Eigen::Vector2d(s[3], s[4])};
  };
  EXPECT_TRUE(predict(1.0 / 30).first.isApprox(x1, 1e-12));                    // a frame at 30 fps: a step
  EXPECT_TRUE(predict(2.0 / 30).first.isApprox(x2, 1e-12));                    // a dropped frame: two
  EXPECT_TRUE(predict(0).first.isApprox(x0, 1e-12));                           // no time: none
  EXPECT_TRUE(predict(1.0 / 60).first.isApprox(x0 + 0.5 * (x1 - x0), 1e-12));  // 60 fps: half
  EXPECT_TRUE(predict(2.5 / 30).first.isApprox(x2 + 0.5 * (model->NextLatent(x2, nullptr) - x2), 1e-12));
  // The root goes at the speed along the heading (+z at heading 0).
  EXPECT_TRUE(predict(0.5).second.isApprox(Eigen::Vector2d(100, 200 + 600), 1e-12));
}

}  // namespace
}  // namespace jgpm
