// The annealed particle filter (Deutscher, Blake & Reid 2000; as HumanEva's baseline and
// PARSEC's bodytrack run it), over any StateModel. Per frame:
//   predict   every particle moves by the model's dynamics;
//   layers    L times: weigh each particle by exp(-beta_l cost) p(x|M)^(1/L), the cost
//             from the silhouette likelihood and p(x|M) the model's latent prior; beta_l
//             is found by bisection so that the effective sample size is `survival` of
//             the particles (bodytrack's rule: about half survive); then resample
//             (systematic) and diffuse with the model's diffusion, shrunk by
//             `diffusion_shrink` each layer; the last layer is weighed, not diffused.
// The prior is not tempered, and it is applied once per frame: a particle that survives the
// L layers has been weighed by p(x|M) in all. Applied whole in every layer, it would count
// L times (seen: a kernel density varying by 1.3 nats over the manifold then outweighed the
// silhouettes, 81 mm against 35 mm without it on 20 frames of 07_01).
// The estimate is the last layer's weighted mean over the dominant mode of the first
// coordinate when it is periodic (the walking phase: particles half a cycle apart are
// mirror poses, and their average one with the legs crossed); periodic coordinates are
// averaged about the best particle, so a wrap does not average to the middle. Every particle's random
// numbers come from (seed, frame, layer, index), so results do not depend on the threads.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "tracker/body/body_model.h"
#include "tracker/filter/likelihood.h"
#include "tracker/filter/thread_pool.h"
#include "tracker/state/state_model.h"

namespace jgpm {

struct AnnealingOptions {
  int particles = 200;
  int layers = 4;
  double survival = 0.5;          // effective sample size aimed at per layer (fraction)
  double diffusion_shrink = 0.5;  // the diffusion's scale from one layer to the next
  bool latent_prior = true;       // weigh by p(x|M)
  uint64_t seed = 1;

  bool Check(std::string* why) const;
};

// How one frame's annealing went.
struct AnnealingReport {
  Eigen::VectorXd estimate;      // the state estimate
  double ess = 0;                // last layer's effective sample size / particles
  double best_cost = 0;          // the lowest cost seen in the last layer
  std::vector<double> betas;     // per layer
  int evaluations = 0;
};

using StateMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

class AnnealedFilter {
 public:
  // Everything given must outlive the filter.
  AnnealedFilter(const StateModel& model, const SilhouetteLikelihood& likelihood, const BodyModel& body,
                 const AnnealingOptions& options, ThreadPool* pool);

  // `count` particles drawn around a guess (frame: the random streams' key).
  void Initialise(const InitialGuess& guess, int count, int frame);
  // Moves every particle `dt` seconds on (the frame's dynamics; alone for a dropped frame).
  void Predict(double dt, int frame);
  // The annealing layers against one frame's observations (one per camera, each with the
  // region where the person is expected); `layers` 0: the options'. Ends with
  // options().particles particles.
  AnnealingReport Update(const std::vector<CameraObservation>& observations, int frame, int layers = 0);

  const StateMatrix& particles() const { return particles_; }
  // Puts back particles taken from particles() (an update undone).
  void Reset(const StateMatrix& particles) { particles_ = particles; }
  // Adds `offset` to one coordinate of every particle, or of every `every`-th one (then
  // normalises them).
  void Shift(int dimension, double offset, int every = 1);
  // Changes every particle, or every `every`-th one, by `change` (then normalises it).
  void Transform(const std::function<void(double* state)>& change, int every = 1);
  // Sets one coordinate of every particle to `value`.
  void Set(int dimension, double value) { particles_.col(dimension).setConstant(value); }
  // Moves every `every`-th particle's place on the floor to about `floor_mm` (normal, `std_mm`
  // each way), the rest of its state kept: a second look where the masks say the person
  // is, which the annealing then keeps or drops. `frame` keys the random numbers. With
  // `size` > 0 their size goes with it (normal, `size_std` relative): where the person's
  // height was read too, a body of the wrong size stays off in depth (a shorter body
  // placed farther draws the same head) however its place is moved.
  void Relocate(const Eigen::Vector2d& floor_mm, double std_mm, int every, int frame, double size = 0,
                double size_std = 0);
  // Turns every `every`-th particle to a heading drawn uniformly, the rest of its state
  // kept: a look in every direction, which the annealing keeps where the silhouettes
  // agree. `frame` keys the random numbers.
  void Reorient(int every, int frame);
  // The particles' mean (they are equally weighted between frames), periodic coordinates
  // about the first particle.
  Eigen::VectorXd Mean() const;
  const AnnealingOptions& options() const { return options_; }

  // One state's cost (and per-camera scores), and its placed body.
  double Score(const double* state, const std::vector<CameraObservation>& observations,
               std::vector<CameraScore>* scores) const;
  void Body(const double* state, Eigen::Matrix3Xd* joints, std::vector<Capsule>* capsules) const;

  // Weights exp(-beta cost + log_prior) normalised, and the beta giving an effective sample
  // size of `survival` (bisection; when the prior alone is already below it, the beta the
  // likelihood alone would need, so that no layer ignores the images). Exposed for tests.
  static double FindBeta(const std::vector<double>& cost, const std::vector<double>& log_prior, double survival);
  static std::vector<double> Weights(const std::vector<double>& cost, const std::vector<double>& log_prior, double beta);
  // The dominant mode of a periodic coordinate: the particles within a quarter period of
  // the heaviest one, or of the heaviest of the others when those weigh more.
  static std::vector<bool> DominantMode(const std::vector<double>& values, const std::vector<double>& weights,
                                        double period);
  // The particles (rows) that carry the estimate: those of the dominant mode of each
  // periodic coordinate of `dimensions` in turn, as (column, period); a period of 0 is
  // skipped. The walking phase and then the heading: half a cycle on is the mirror pose,
  // half a turn the walker turned round and walking the other way (reverse_every in
  // tracker.h), and an average over either pair is neither.
  static std::vector<int> ModeParticles(const StateMatrix& particles, const std::vector<double>& weights,
                                        const std::vector<std::pair<int, double>>& dimensions);
  // The weighted mean of a periodic coordinate over its dominant mode, about its heaviest
  // particle (not the average of two modes half a period apart).
  static double PeriodicMean(const std::vector<double>& values, const std::vector<double>& weights, double period);
  // Systematic resampling: `count` indices drawn in proportion to `weights`, from one
  // uniform offset.
  static std::vector<int> Resample(const std::vector<double>& weights, int count, double offset);

 private:
  void Evaluate(std::vector<double>* cost, std::vector<double>* log_prior,
                const std::vector<CameraObservation>& observations);
  Eigen::VectorXd WeightedMean(const std::vector<double>& weights) const;

  const StateModel& model_;
  const SilhouetteLikelihood& likelihood_;
  const BodyModel& body_;
  AnnealingOptions options_;
  ThreadPool* pool_;
  StateMatrix particles_;
  struct Scratch {
    Eigen::Matrix3Xd joints;
    std::vector<Capsule> capsules;
    SilhouetteLikelihood::Workspace workspace;
  };
  std::vector<Scratch> scratch_;  // one per worker
};

}  // namespace jgpm
