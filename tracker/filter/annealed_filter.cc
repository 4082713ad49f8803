#include "tracker/filter/annealed_filter.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "io/base/error.h"

namespace jgpm {
namespace {

double EffectiveFraction(const std::vector<double>& weights) {
  double sum = 0, squares = 0;
  for (double w : weights) {
    sum += w;
    squares += w * w;
  }
  return squares > 0 ? sum * sum / squares / weights.size() : 0.0;
}

}  // namespace

bool AnnealingOptions::Check(std::string* why) const {
  const char* problem = nullptr;
  if (particles < 1 || particles > 1000000) problem = "particles must be in [1, 1000000]";
  else if (layers < 1 || layers > 100) problem = "layers must be in [1, 100]";
  else if (!(survival > 0 && survival < 1)) problem = "survival must be in (0, 1)";
  else if (!(diffusion_shrink > 0 && diffusion_shrink <= 1)) problem = "diffusion_shrink must be in (0, 1]";
  if (problem && why) *why = problem;  // `why` may be null
  return problem == nullptr;
}

AnnealedFilter::AnnealedFilter(const StateModel& model, const SilhouetteLikelihood& likelihood, const BodyModel& body,
                               const AnnealingOptions& options, ThreadPool* pool)
    : model_(model), likelihood_(likelihood), body_(body), options_(options), pool_(pool) {
  std::string why;
  if (!options.Check(&why)) ThrowInputError("tracking options", why);
  for (int w = 0; w < pool->size(); ++w) scratch_.push_back({Eigen::Matrix3Xd(), {}, likelihood.NewWorkspace()});
}

void AnnealedFilter::Initialise(const InitialGuess& guess, int count, int frame) {
  particles_.resize(count, model_.Dimension());
  const PlacementIndex p = model_.placement();
  pool_->For(count, [&](int begin, int end, int) {
    for (int i = begin; i < end; ++i) {
      Random random(options_.seed, frame, 1000, i);
      model_.Sample(guess, &random, particles_.row(i).data());
      const int k = i % static_cast<int>(guess.other_floors_mm.size() + 1);
      if (k > 0) {
        const Eigen::Vector2d shift = guess.other_floors_mm[k - 1] - guess.floor_mm;
        particles_(i, p.x) += shift.x();
        particles_(i, p.z) += shift.y();
      }
    }
  });
}

void AnnealedFilter::Shift(int dimension, double offset, int every) {
  Transform([&](double* state) { state[dimension] += offset; }, every);
}

void AnnealedFilter::Transform(const std::function<void(double* state)>& change, int every) {
  for (int i = every - 1; i < particles_.rows(); i += every) {
    change(particles_.row(i).data());
    model_.Normalise(particles_.row(i).data());
  }
}

void AnnealedFilter::Relocate(const Eigen::Vector2d& floor_mm, double std_mm, int every, int frame, double size,
                              double size_std) {
  const PlacementIndex p = model_.placement();
  for (int i = every - 1; i < particles_.rows(); i += every) {
    Random random(options_.seed, frame, 5000, i);
    particles_(i, p.x) = floor_mm.x() + std_mm * random.Normal();
    particles_(i, p.z) = floor_mm.y() + std_mm * random.Normal();
    if (size > 0) {
      particles_(i, p.size) = size * (1 + size_std * random.Normal());
      model_.Normalise(particles_.row(i).data());
    }
  }
}

void AnnealedFilter::Reorient(int every, int frame) {
  const PlacementIndex p = model_.placement();
  for (int i = every - 1; i < particles_.rows(); i += every) {
    Random random(options_.seed, frame, 6000, i);
    particles_(i, p.heading) = (2 * random.Uniform() - 1) * std::numbers::pi;
  }
}

void AnnealedFilter::Predict(double dt, int frame) {
  pool_->For(static_cast<int>(particles_.rows()), [&](int begin, int end, int) {
    for (int i = begin; i < end; ++i) {
      Random random(options_.seed, frame, 2000, i);
      model_.Predict(dt, &random, particles_.row(i).data());
    }
  });
}

void AnnealedFilter::Body(const double* state, Eigen::Matrix3Xd* joints, std::vector<Capsule>* capsules) const {
  model_.Evaluate(state, joints);
  body_.Place(*joints, capsules);
  const double scale = model_.RadiusScale(state);
  for (Capsule& c : *capsules) {
    c.radius_from_mm *= scale;
    c.radius_to_mm *= scale;
  }
}

double AnnealedFilter::Score(const double* state, const std::vector<CameraObservation>& observations,
                             std::vector<CameraScore>* scores) const {
  Eigen::Matrix3Xd joints;
  std::vector<Capsule> capsules;
  Body(state, &joints, &capsules);
  SilhouetteLikelihood::Workspace workspace = likelihood_.NewWorkspace();
  return likelihood_.Cost(capsules, observations, &workspace, scores);
}

void AnnealedFilter::Evaluate(std::vector<double>* cost, std::vector<double>* log_prior,
                              const std::vector<CameraObservation>& observations) {
  const int n = static_cast<int>(particles_.rows());
  cost->resize(n);
  log_prior->resize(n);
  pool_->For(n, [&](int begin, int end, int worker) {
    Scratch& s = scratch_[worker];
    for (int i = begin; i < end; ++i) {
      const double* state = particles_.row(i).data();
      const double prior = model_.Evaluate(state, &s.joints);
      (*log_prior)[i] = options_.latent_prior ? prior : 0.0;
      body_.Place(s.joints, &s.capsules);
      const double scale = model_.RadiusScale(state);
      for (Capsule& c : s.capsules) {
        c.radius_from_mm *= scale;
        c.radius_to_mm *= scale;
      }
      (*cost)[i] = likelihood_.Cost(s.capsules, observations, &s.workspace);
    }
  });
}

std::vector<double> AnnealedFilter::Weights(const std::vector<double>& cost, const std::vector<double>& log_prior,
                                            double beta) {
  const int n = static_cast<int>(cost.size());
  std::vector<double> log_w(n);
  double top = -1e300;
  for (int i = 0; i < n; ++i) {
    log_w[i] = -beta * cost[i] + log_prior[i];
    if (!std::isfinite(log_w[i])) log_w[i] = -1e300;
    top = std::max(top, log_w[i]);
  }
  std::vector<double> w(n);
  double sum = 0;
  for (int i = 0; i < n; ++i) sum += (w[i] = std::exp(log_w[i] - top));
  for (double& x : w) x /= sum;
  return w;
}

double AnnealedFilter::FindBeta(const std::vector<double>& cost, const std::vector<double>& log_prior,
                                double survival) {
  if (EffectiveFraction(Weights(cost, log_prior, 0)) <= survival) {
    // No beta reaches the target (the prior alone is below it): the likelihood's own beta,
    // so that the layer still weighs the images.
    return FindBeta(cost, std::vector<double>(cost.size(), 0.0), survival);
  }
  double low = 0, high = 1;
  while (EffectiveFraction(Weights(cost, log_prior, high)) > survival && high < 1e9) {
    low = high;
    high *= 4;
  }
  for (int iteration = 0; iteration < 40; ++iteration) {
    const double middle = 0.5 * (low + high);
    (EffectiveFraction(Weights(cost, log_prior, middle)) > survival ? low : high) = middle;
  }
  return 0.5 * (low + high);
}

std::vector<int> AnnealedFilter::Resample(const std::vector<double>& weights, int count, double offset) {
  std::vector<int> chosen(count);
  const double total = std::accumulate(weights.begin(), weights.end(), 0.0);
  double cumulative = weights.empty() ? 0 : weights[0];
  int i = 0;
  for (int k = 0; k < count; ++k) {
    const double target = (k + offset) / count * total;
    while (cumulative < target && i + 1 < static_cast<int>(weights.size())) cumulative += weights[++i];
    chosen[k] = i;
  }
  return chosen;
}

std::vector<bool> AnnealedFilter::DominantMode(const std::vector<double>& values, const std::vector<double>& weights,
                                               double period) {
  const int n = static_cast<int>(values.size());
  auto mode_about = [&](int reference, std::vector<bool>* in) {
    double weight = 0;
    in->assign(n, false);
    for (int i = 0; i < n; ++i) {
      if (std::abs(std::remainder(values[i] - values[reference], period)) <= period / 4) {
        (*in)[i] = true;
        weight += weights[i];
      }
    }
    return weight;
  };
  const int best = static_cast<int>(std::max_element(weights.begin(), weights.end()) - weights.begin());
  std::vector<bool> near, far;
  const double near_weight = mode_about(best, &near);
  int other = -1;  // the heaviest particle of the other half
  for (int i = 0; i < n; ++i)
    if (!near[i] && (other < 0 || weights[i] > weights[other])) other = i;
  if (other >= 0 && mode_about(other, &far) > near_weight) return far;
  return near;
}

std::vector<int> AnnealedFilter::ModeParticles(const StateMatrix& particles, const std::vector<double>& weights,
                                               const std::vector<std::pair<int, double>>& dimensions) {
  std::vector<int> chosen(particles.rows());
  for (int i = 0; i < static_cast<int>(chosen.size()); ++i) chosen[i] = i;
  for (const auto& [column, period] : dimensions) {
    if (period <= 0 || chosen.size() < 2) continue;
    std::vector<double> values, w;
    for (int i : chosen) values.push_back(particles(i, column)), w.push_back(weights[i]);
    const std::vector<bool> mode = DominantMode(values, w, period);
    std::vector<int> kept;
    for (size_t j = 0; j < chosen.size(); ++j)
      if (mode[j]) kept.push_back(chosen[j]);
    chosen.swap(kept);
  }
  return chosen;
}

double AnnealedFilter::PeriodicMean(const std::vector<double>& values, const std::vector<double>& weights,
                                    double period) {
  const std::vector<bool> mode = DominantMode(values, weights, period);
  int reference = -1;
  for (size_t i = 0; i < values.size(); ++i)
    if (mode[i] && (reference < 0 || weights[i] > weights[reference])) reference = static_cast<int>(i);
  double sum = 0, total = 0;
  for (size_t i = 0; i < values.size(); ++i) {
    if (!mode[i]) continue;
    sum += weights[i] * (values[reference] + std::remainder(values[i] - values[reference], period));
    total += weights[i];
  }
  return total > 0 ? sum / total : values[reference];
}

Eigen::VectorXd AnnealedFilter::WeightedMean(const std::vector<double>& weights) const {
  const int d = model_.Dimension(), heading = model_.placement().heading;
  const std::vector<int> chosen =
      ModeParticles(particles_, weights, {{0, model_.Period(0)}, {heading, model_.Period(heading)}});
  std::vector<double> w(chosen.size()), values(chosen.size());
  double total = 0;
  for (size_t j = 0; j < chosen.size(); ++j) total += (w[j] = weights[chosen[j]]);
  for (double& x : w) x = total > 0 ? x / total : 1.0 / w.size();
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(d);
  for (int k = 0; k < d; ++k) {
    for (size_t j = 0; j < chosen.size(); ++j) values[j] = particles_(chosen[j], k);
    const double period = model_.Period(k);
    if (period > 0) {
      mean[k] = PeriodicMean(values, w, period);
    } else {
      for (size_t j = 0; j < chosen.size(); ++j) mean[k] += w[j] * values[j];
    }
  }
  model_.Normalise(mean.data());
  return mean;
}

Eigen::VectorXd AnnealedFilter::Mean() const {
  return WeightedMean(std::vector<double>(particles_.rows(), 1.0 / std::max<Eigen::Index>(1, particles_.rows())));
}

AnnealingReport AnnealedFilter::Update(const std::vector<CameraObservation>& observations,
                                       int frame, int layers) {
  JGPM_CHECK(particles_.rows() > 0);
  AnnealingReport report;
  const int total_layers = layers > 0 ? layers : options_.layers;
  std::vector<double> cost, log_prior;
  double diffusion = 1;
  for (int layer = 0; layer < total_layers; ++layer) {
    Evaluate(&cost, &log_prior, observations);
    for (double& p : log_prior) p /= total_layers;  // the prior once per frame, over the layers
    report.evaluations += static_cast<int>(particles_.rows());
    const double beta = FindBeta(cost, log_prior, options_.survival);
    report.betas.push_back(beta);
    const std::vector<double> weights = Weights(cost, log_prior, beta);
    const bool last = layer + 1 == total_layers;
    if (last) {
      report.estimate = WeightedMean(weights);
      report.ess = EffectiveFraction(weights);
      report.best_cost = *std::min_element(cost.begin(), cost.end());
    }
    Random offset(options_.seed, frame, 3000 + layer, 0);
    const std::vector<int> chosen = Resample(weights, options_.particles, offset.Uniform());
    StateMatrix next(options_.particles, model_.Dimension());
    for (int k = 0; k < options_.particles; ++k) next.row(k) = particles_.row(chosen[k]);
    particles_.swap(next);
    if (last) break;
    pool_->For(options_.particles, [&](int begin, int end, int) {
      for (int i = begin; i < end; ++i) {
        Random random(options_.seed, frame, 4000 + layer, i);
        model_.Diffuse(diffusion, &random, particles_.row(i).data());
      }
    });
    diffusion *= options_.diffusion_shrink;
  }
  return report;
}

}  // namespace jgpm
