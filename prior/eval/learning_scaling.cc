#include "prior/eval/learning_scaling.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <set>
#include <string>

#include <opencv2/imgproc.hpp>

#include "io/base/error.h"
#include "prior/learning/full_trainer.h"

namespace jgpm {

SyntheticGpProblem MakeSyntheticGpProblem(int n, int m) {
  JGPM_CHECK(n >= 2 && m >= 0 && m <= n);
  const int channels = 43, poses = 30;
  std::mt19937 random(3);
  std::normal_distribution<double> noise(0, 0.05);
  SyntheticGpProblem problem;
  GpParameters& p = problem.params;
  p.x.resize(n, 3);
  problem.y.resize(n, channels);
  for (int i = 0; i < n; ++i) {
    const double phase = 2 * std::numbers::pi * (i % poses) / poses, gait = (i / poses) * 0.05;
    p.x.row(i) << std::cos(phase) + noise(random), std::sin(phase) + noise(random), gait;
    for (int d = 0; d < channels; ++d) problem.y(i, d) = std::sin(phase * (1 + d % 3) + 0.1 * d + gait) + noise(random);
    if (i % poses == 0) problem.sequences.push_back({i, std::min(poses, n - i)});
  }
  p.log_beta = Eigen::Vector3d(0, 0, std::log(100.0));
  p.log_alpha = Eigen::Vector4d(0, 0, std::log(0.1), std::log(1e4));
  p.log_w = Eigen::VectorXd::Zero(channels);
  if (m > 0) {
    p.u.resize(m, 3);
    p.u_dynamics.resize(m, 3);
    for (int k = 0; k < m; ++k) p.u.row(k) = p.u_dynamics.row(k) = p.x.row(static_cast<long>(k) * n / m);
  }
  return problem;
}

ScalingPoint TimeObjectiveEvaluation(int n, int m, int repeats) {
  JGPM_CHECK(repeats >= 1);
  const SyntheticGpProblem problem = MakeSyntheticGpProblem(n, m);
  ObjectiveTerms terms;
  terms.channel_scales = terms.dynamics = true;
  const GpObjective objective(problem.y, problem.sequences, nullptr, terms);
  GpParameters gradient;
  ScalingPoint point{n, m, 0, 0};
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r <= repeats; ++r) {  // r = 0 warms caches and allocations up
    const auto start = std::chrono::steady_clock::now();
    const ObjectiveValue value = objective.Evaluate(problem.params, &gradient);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!value.ok) ThrowInputError("objective N = " + std::to_string(n) + ", M = " + std::to_string(m), value.why);
    point.objective = value.total;
    if (r > 0) best = std::min(best, seconds);
  }
  point.seconds = best;
  return point;
}

ConvergencePoint TimeToConverge(int n, int m, double max_seconds) {
  SyntheticGpProblem problem = MakeSyntheticGpProblem(n, m);
  ObjectiveTerms terms;
  terms.channel_scales = terms.dynamics = true;
  const GpObjective objective(problem.y, problem.sequences, nullptr, terms);
  FullTrainingOptions options;
  options.max_iterations = 1000000;  // the time budget or the stopping rule ends it
  options.budget.max_seconds = max_seconds;
  const TrainingSummary s = TrainFull(objective, &problem.params, options);
  return {n, m, s.wall_seconds, s.iterations, s.termination, s.initial_objective, s.final_objective};
}

cv::Mat ScalingPlot(const std::vector<ScalingPoint>& points) {
  JGPM_CHECK(!points.empty());
  const int width = 760, height = 480, left = 70, bottom = 50, top = 40, right = 150;
  cv::Mat image(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  double n_lo = 1e9, n_hi = 0, s_lo = 1e9, s_hi = 0;
  for (const ScalingPoint& p : points) {
    n_lo = std::min<double>(n_lo, p.n), n_hi = std::max<double>(n_hi, p.n);
    s_lo = std::min(s_lo, p.seconds), s_hi = std::max(s_hi, p.seconds);
  }
  const double lx0 = std::log10(n_lo) - 0.1, lx1 = std::log10(n_hi) + 0.1;
  const double ly0 = std::floor(std::log10(s_lo)), ly1 = std::ceil(std::log10(s_hi));
  auto to_pixel = [&](double n, double s) {
    return cv::Point(left + static_cast<int>((std::log10(n) - lx0) / (lx1 - lx0) * (width - left - right)),
                     top + static_cast<int>((1 - (std::log10(s) - ly0) / (ly1 - ly0)) * (height - top - bottom)));
  };
  auto text = [&](const std::string& s, cv::Point at, cv::Scalar colour = {0, 0, 0}, double scale = 0.42) {
    cv::putText(image, s, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv::LINE_AA);
  };
  for (double e = ly0; e <= ly1; ++e) {  // decades of seconds
    const cv::Point a = to_pixel(std::pow(10, lx0), std::pow(10, e)), b = to_pixel(std::pow(10, lx1), std::pow(10, e));
    cv::line(image, a, b, cv::Scalar(228, 228, 228));
    const double ms = std::pow(10, e) * 1e3;
    text(ms >= 1 ? std::to_string(static_cast<long>(ms)) + " ms" : std::to_string(ms).substr(0, 5) + " ms", {6, a.y + 4});
  }
  std::set<int> ns;
  for (const ScalingPoint& p : points) ns.insert(p.n);
  for (const int n : ns) {
    const cv::Point at = to_pixel(n, std::pow(10, ly0));
    cv::line(image, {at.x, top}, at, cv::Scalar(228, 228, 228));
    text(std::to_string(n), {at.x - 14, at.y + 18});
  }
  text("latent points N (log)", {width / 2 - 80, height - 12});
  text("One objective evaluation with its gradient, seconds (log), one thread", {left, 24}, {0, 0, 0}, 0.5);
  const cv::Scalar colours[] = {{180, 110, 30}, {40, 150, 40}, {150, 60, 150}, {30, 140, 200}, {120, 120, 120}};
  int sparse = 0;  // sparse series drawn so far
  std::map<int, std::vector<ScalingPoint>> lines;  // by M
  for (const ScalingPoint& p : points) lines[p.m].push_back(p);
  int row = 0;
  for (auto& [m, line] : lines) {
    std::sort(line.begin(), line.end(), [](const ScalingPoint& a, const ScalingPoint& b) { return a.n < b.n; });
    const cv::Scalar colour = m == 0 ? cv::Scalar(60, 60, 200) : colours[sparse++ % 5];
    for (size_t i = 0; i < line.size(); ++i) {
      if (i + 1 < line.size()) {
        cv::line(image, to_pixel(line[i].n, line[i].seconds), to_pixel(line[i + 1].n, line[i + 1].seconds), colour, 2,
                 cv::LINE_AA);
      }
      cv::circle(image, to_pixel(line[i].n, line[i].seconds), 4, colour, cv::FILLED, cv::LINE_AA);
    }
    text(m == 0 ? "exact (N^3)" : "sparse M = " + std::to_string(m), {width - right + 10, top + 20 + 20 * row}, colour,
         0.45);
    ++row;
  }
  // Linear growth for reference, from the largest M's smallest N.
  const ScalingPoint& base = lines.rbegin()->second.front();
  const double ratio = n_hi / base.n;
  cv::line(image, to_pixel(base.n, base.seconds), to_pixel(n_hi, base.seconds * ratio), cv::Scalar(160, 160, 160), 1,
           cv::LINE_AA);
  text("slope 1 (linear)", to_pixel(n_hi, base.seconds * ratio) + cv::Point(-120, -10), {120, 120, 120}, 0.38);
  return image;
}

}  // namespace jgpm
