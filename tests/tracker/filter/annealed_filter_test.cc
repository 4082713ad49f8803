// The annealed filter's weighting and resampling against the posterior they must reproduce:
// on a linear-Gaussian model the Kalman filter is the exact answer, so one importance
// step (Weights at beta = 1) and a whole bootstrap filter (Weights + Resample per step)
// must give its mean and variance to Monte-Carlo accuracy. FindBeta must hit the
// effective sample size it promises, and systematic resampling must give every particle
// floor(N w) or ceil(N w) copies.
#include "tracker/filter/annealed_filter.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "tracker/state/random.h"

namespace jgpm {
namespace {

// Effective sample size of normalised-or-not weights, as a fraction of their number.
double EssFraction(const std::vector<double>& w) {
  double sum = 0, squares = 0;
  for (double x : w) sum += x, squares += x * x;
  return sum * sum / squares / w.size();
}

struct Moments {
  double mean = 0, variance = 0;
};
Moments Weighted(const std::vector<double>& x, const std::vector<double>& w) {
  Moments m;
  double total = 0;
  for (size_t i = 0; i < x.size(); ++i) total += w[i], m.mean += w[i] * x[i];
  m.mean /= total;
  for (size_t i = 0; i < x.size(); ++i) m.variance += w[i] * (x[i] - m.mean) * (x[i] - m.mean);
  m.variance /= total;
  return m;
}
Moments Equal(const std::vector<double>& x) { return Weighted(x, std::vector<double>(x.size(), 1.0)); }

// The filter's cost for a scalar observation y of x with noise variance r: the negative
// log-likelihood, so that weights exp(-cost) at beta = 1 are the exact likelihood.
std::vector<double> GaussianCost(const std::vector<double>& x, double y, double r) {
  std::vector<double> cost(x.size());
  for (size_t i = 0; i < x.size(); ++i) cost[i] = (x[i] - y) * (x[i] - y) / (2 * r);
  return cost;
}

TEST(AnnealedFilter, OneWeightingStepIsTheKalmanUpdate) {
  // Prior N(m0, P), observation y = x + N(0, R): posterior mean m0 + K (y - m0), variance
  // (1 - K) P with K = P / (P + R). y is 1.5 prior sigmas off, so the weights matter.
  const double m0 = 2, p = 4, r = 1, y = 5;
  const double k = p / (p + r), mean = m0 + k * (y - m0), variance = (1 - k) * p;
  const int n = 200000;
  std::vector<double> x(n);
  for (int i = 0; i < n; ++i) {
    Random random(7, 0, 0, i);
    x[i] = m0 + std::sqrt(p) * random.Normal();
  }
  const std::vector<double> w = AnnealedFilter::Weights(GaussianCost(x, y, r), std::vector<double>(n, 0.0), 1.0);
  double total = 0;
  for (double v : w) total += v;
  EXPECT_NEAR(total, 1.0, 1e-9);  // normalised
  const Moments weighted = Weighted(x, w);
  // Monte-Carlo standard errors with the weights' effective sample size (measured 0.27 N):
  // mean sqrt(var / ESS) ~ 0.004, variance var sqrt(2 / ESS) ~ 0.005 (Gaussian
  // approximation); 5 of them. Measured: 0.0031 and 0.0012 off.
  const double ess = EssFraction(w) * n;
  EXPECT_GT(ess, 0.2 * n);
  EXPECT_NEAR(weighted.mean, mean, 5 * std::sqrt(variance / ess));
  EXPECT_NEAR(weighted.variance, variance, 5 * variance * std::sqrt(2 / ess));
  // Resampled, the equally weighted particles hold the same posterior (resampling adds
  // at most the noise of N draws).
  std::vector<double> resampled;
  for (int i : AnnealedFilter::Resample(w, n, 0.37)) resampled.push_back(x[i]);
  const Moments after = Equal(resampled);
  EXPECT_NEAR(after.mean, mean, 5 * std::sqrt(variance / ess) + 5 * std::sqrt(variance / n));
  EXPECT_NEAR(after.variance, variance, 5 * variance * (std::sqrt(2 / ess) + std::sqrt(2.0 / n)));
  std::printf("posterior mean %.5f (Kalman %.5f), variance %.5f (Kalman %.5f), ESS %.0f of %d\n", weighted.mean,
              mean, weighted.variance, variance, ess, n);
}

TEST(AnnealedFilter, BootstrapFilterTracksTheKalmanFilter) {
  // A random walk x_t = x_{t-1} + N(0, q) seen as y_t = x_t + N(0, r), filtered by
  // predicting every particle, weighing it by the likelihood (beta 1, no prior term) and
  // resampling: each step's particle mean and variance against the Kalman filter's.
  const double q = 0.5, r = 1.0, p0 = 2.0;
  const int n = 20000, steps = 25;
  Random world(99);
  double truth = 0;
  std::vector<double> x(n);
  for (int i = 0; i < n; ++i) {
    Random random(11, 0, 0, i);
    x[i] = std::sqrt(p0) * random.Normal();
  }
  double kalman_mean = 0, kalman_variance = p0;
  double worst_mean_sigmas = 0, worst_variance_ratio = 0;
  for (int t = 1; t <= steps; ++t) {
    truth += std::sqrt(q) * world.Normal();
    const double y = truth + std::sqrt(r) * world.Normal();
    // Kalman filter.
    const double predicted = kalman_variance + q;
    const double gain = predicted / (predicted + r);
    kalman_mean += gain * (y - kalman_mean);
    kalman_variance = (1 - gain) * predicted;
    // Bootstrap particle filter.
    for (int i = 0; i < n; ++i) {
      Random random(11, t, 1, i);
      x[i] += std::sqrt(q) * random.Normal();
    }
    const std::vector<double> w = AnnealedFilter::Weights(GaussianCost(x, y, r), std::vector<double>(n, 0.0), 1.0);
    Random offset(11, t, 2, 0);
    std::vector<double> next(n);
    const std::vector<int> chosen = AnnealedFilter::Resample(w, n, offset.Uniform());
    for (int i = 0; i < n; ++i) next[i] = x[chosen[i]];
    x.swap(next);
    const Moments m = Equal(x);
    // Standard errors: the filter's particles are correlated through resampling, so allow
    // for an effective size of N / 4. Measured over the 25 steps: mean at worst 2.2 of
    // them off, variance 2.8% off.
    const double mean_error = std::sqrt(kalman_variance / (n / 4.0));
    EXPECT_NEAR(m.mean, kalman_mean, 5 * mean_error) << "step " << t;
    EXPECT_NEAR(m.variance, kalman_variance, 0.06 * kalman_variance) << "step " << t;
    worst_mean_sigmas = std::max(worst_mean_sigmas, std::abs(m.mean - kalman_mean) / mean_error);
    worst_variance_ratio = std::max(worst_variance_ratio, std::abs(m.variance / kalman_variance - 1));
  }
  std::printf("worst step: mean %.2f standard errors off, variance %.2f%% off (Kalman variance %.4f)\n",
              worst_mean_sigmas, 100 * worst_variance_ratio, kalman_variance);
}

TEST(AnnealedFilter, FindBetaHitsTheSurvivalRate) {
  const int n = 500;
  for (int trial = 0; trial < 6; ++trial) {
    std::vector<double> cost(n), log_prior(n, 0.0);
    for (int i = 0; i < n; ++i) {
      Random random(5, trial, 0, i);
      cost[i] = 3 + 2 * random.Normal();                    // silhouette costs are of order 1
      if (trial % 2) log_prior[i] = 0.3 * random.Normal();  // and a mild prior term on odd trials
    }
    for (double survival : {0.2, 0.5, 0.8}) {
      const double beta = AnnealedFilter::FindBeta(cost, log_prior, survival);
      EXPECT_GT(beta, 0) << trial << " " << survival;
      EXPECT_NEAR(EssFraction(AnnealedFilter::Weights(cost, log_prior, beta)), survival, 1e-3)
          << "trial " << trial << " survival " << survival << " beta " << beta;
    }
  }
  // Costs of very different scales: beta must follow (ESS depends on beta * spread only).
  std::vector<double> small(n), large(n), none(n, 0.0);
  for (int i = 0; i < n; ++i) {
    Random random(6, 0, 0, i);
    small[i] = 0.01 * random.Normal();
    large[i] = 100 * small[i];
  }
  const double beta_small = AnnealedFilter::FindBeta(small, none, 0.5);
  const double beta_large = AnnealedFilter::FindBeta(large, none, 0.5);
  EXPECT_NEAR(beta_small / beta_large, 100, 0.5);
  // The prior alone already below the target, so no beta reaches it: the images still
  // count, at the beta the likelihood alone would have (it was 0, and the layer ignored
  // them).
  std::vector<double> wild_prior(n);
  for (int i = 0; i < n; ++i) {
    Random random(8, 0, 0, i);
    wild_prior[i] = 4 * random.Normal();
  }
  ASSERT_LT(EssFraction(AnnealedFilter::Weights(none, wild_prior, 0)), 0.5);
  EXPECT_GT(AnnealedFilter::FindBeta(small, wild_prior, 0.5), 0.0);
  EXPECT_EQ(AnnealedFilter::FindBeta(small, wild_prior, 0.5), beta_small);
}

// The periodic weighted mean, by hand: two modes half a period apart average to the
// heavier one's mean, not to the pose between them; a wrap does not average to the middle.
TEST(AnnealedFilter, PeriodicMeanTakesTheDominantMode) {
  // Phases 0.1 and 0.12 (weights 0.3, 0.3) against their mirror 0.6 (0.4): 0.11.
  EXPECT_NEAR(AnnealedFilter::PeriodicMean({0.1, 0.12, 0.6}, {0.3, 0.3, 0.4}, 1.0), 0.11, 1e-12);
  // The heaviest particle alone is not the mode: 0.6 (0.4) loses to 0.1 + 0.12 (0.6).
  EXPECT_EQ(AnnealedFilter::DominantMode({0.1, 0.12, 0.6}, {0.3, 0.3, 0.4}, 1.0), (std::vector<bool>{true, true, false}));
  // Across the wrap: 0.95 and 0.05 average to 0.0 (as 1.0), not 0.5.
  EXPECT_NEAR(std::remainder(AnnealedFilter::PeriodicMean({0.95, 0.05}, {0.5, 0.5}, 1.0), 1.0), 0.0, 1e-12);
  // A heading: 170 and -170 degrees (weights 1, 3) average to -175.
  const double deg = std::numbers::pi / 180;
  EXPECT_NEAR(AnnealedFilter::PeriodicMean({170 * deg, -170 * deg}, {1, 3}, 2 * std::numbers::pi), -175 * deg, 1e-12);
  // One mode: the plain weighted mean.
  EXPECT_NEAR(AnnealedFilter::PeriodicMean({0.2, 0.3, 0.4}, {1, 1, 2}, 1.0), 0.325, 1e-12);
}

// The particles that carry the estimate, by hand: the phase's dominant mode first, then,
// among those, the heading's. Rows (phase, heading, cadence): two walkers facing +z, one
// with the legs the other way (phase + 0.5), and two turned round walking backwards; the
// mean of the chosen rows' cadence is the forward walkers' (averaged with the turned
// round ones' it was 0.4).
TEST(AnnealedFilter, TheEstimateIsOneWalkerNotAnAverageOfModes) {
  StateMatrix particles(5, 3);
  const double pi = std::numbers::pi;
  particles << 0.10, 0.05, 0.9,   //
      0.12, -0.05, 0.8,           //
      0.61, 0.00, 0.9,            // the mirror pose: another phase mode
      0.11, pi - 0.05, -0.9,      // turned round, walking backwards
      0.60, -pi + 0.1, -0.85;     // the same, half a cycle on
  const std::vector<double> weights = {0.25, 0.25, 0.1, 0.2, 0.2};
  // Phase: 0.10, 0.12, 0.11 weigh 0.7 against 0.3; heading among those: 0.5 against 0.2.
  EXPECT_EQ(AnnealedFilter::ModeParticles(particles, weights, {{0, 1.0}, {1, 2 * pi}}), (std::vector<int>{0, 1}));
  // The heading alone: 0.6 near 0 against 0.4 turned round.
  EXPECT_EQ(AnnealedFilter::ModeParticles(particles, weights, {{1, 2 * pi}}), (std::vector<int>{0, 1, 2}));
  // Periods of 0 (coordinates that are not periodic) choose nothing out.
  EXPECT_EQ(AnnealedFilter::ModeParticles(particles, weights, {{0, 0.0}, {2, 0.0}}).size(), 5u);
}

TEST(AnnealedFilter, SystematicResamplingKeepsCountsWithinOneOfNw) {
  for (int trial = 0; trial < 20; ++trial) {
    const int m = 50 + 37 * trial, count = trial % 3 == 0 ? m : 3 * m / 2 + 1;
    std::vector<double> weights(m);
    double total = 0;
    for (int i = 0; i < m; ++i) {
      Random random(3, trial, 0, i);
      // Skewed, some exactly zero, unnormalised: Resample normalises by their sum.
      const double u = random.Uniform();
      weights[i] = i % 7 == 3 ? 0.0 : std::exp(4 * u * u);
      total += weights[i];
    }
    for (double offset : {1e-9, 0.25, 0.5, 0.999999}) {
      const std::vector<int> chosen = AnnealedFilter::Resample(weights, count, offset);
      ASSERT_EQ(static_cast<int>(chosen.size()), count);
      EXPECT_TRUE(std::is_sorted(chosen.begin(), chosen.end()));
      std::vector<int> copies(m, 0);
      for (int i : chosen) {
        ASSERT_GE(i, 0);
        ASSERT_LT(i, m);
        ++copies[i];
      }
      for (int i = 0; i < m; ++i) {
        const double expected = count * weights[i] / total;
        EXPECT_LT(std::abs(copies[i] - expected), 1.0)
            << "trial " << trial << " offset " << offset << " particle " << i << ": " << copies[i]
            << " copies, expected " << expected;
        if (weights[i] == 0) {
          EXPECT_EQ(copies[i], 0) << "trial " << trial << " particle " << i;
        }
      }
    }
  }
}

}  // namespace
}  // namespace jgpm
