#include "calibration/walker_calibration.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <numbers>

#include <Eigen/Geometry>
#include <ceres/ceres.h>

#include "calibration/walker_camera.h"
#include "io/base/error.h"

namespace jgpm {
namespace {

constexpr double kDeg = std::numbers::pi / 180;
constexpr double kMaxRollDeg = 30;

// The camera's parameters as Ceres sees them: walker_camera.h.
constexpr int kCameraParameters = kWalkerCameraParameters;
// Each walker's: height (mm) and lean (mm: the head's sideways offset from the feet's
// vertical, as seen from the camera).
enum { kWalkerHeight, kWalkerLean, kWalkerParameters };

// One head-foot pair in "ideal" pixels: offsets from the principal point, undistorted, so
// that (q / f, 1) is the ray in the camera's frame.
struct Pair {
  Eigen::Vector2d head, foot;
  double sd_within_mm = 0, sd_line_mm = 0;
};

// Where the head pixel's ray passes the person's vertical, the vertical line through the
// point where the foot pixel's ray falls to `foot_mm` above the floor: the height there
// (mm), the sideways miss (mm) and the head's depth (mm). False when the foot's ray does
// not go down to that height or the head is not in front of the camera.
// The camera sits at C = (0, h, 0) (walker_camera.h).
template <typename T>
bool HeadOnVertical(const T* camera, const Pair& pair, const T& head_radius_mm, const T& foot_mm, T* head_height,
                    T* miss_mm, T* depth_mm) {
  using std::exp, std::sqrt;
  const T h = exp(camera[kLogHeight]);
  auto ray = [camera](const Eigen::Vector2d& q, T* w) { WalkerCameraRay(camera, q, w); };
  T d[3], g[3];
  ray(pair.foot, d);
  ray(pair.head, g);
  if (!(d[1] < T(-1e-9))) return false;  // the foot's ray never meets the floor
  // The foot point: C + s d at height foot_mm. w = C - F, horizontally.
  const T s = (h - foot_mm) / -d[1];
  if (!(s > T(0))) return false;
  const T wx = -s * d[0], wz = -s * d[2];
  // Closest approach of C + t g to the vertical through F: horizontal geometry only.
  const T gh2 = g[0] * g[0] + g[2] * g[2];
  if (!(gh2 > T(1e-18))) return false;
  const T t = -(g[0] * wx + g[2] * wz) / gh2;  // t is also the depth: g's camera z is 1
  if (!(t > T(1e-6))) return false;
  // Seen from above, the silhouette's top is the ray grazing the far side of a round head
  // (radius r, centre H - r), which meets the vertical at H - r + r / cos(depression):
  // the head's height is that, less the excess.
  const T cos_depression = sqrt(gh2 / (gh2 + g[1] * g[1]));
  *head_height = h + t * g[1] - head_radius_mm * (T(1) / cos_depression - T(1));
  const T mx = wx + t * g[0], mz = wz + t * g[2];
  *miss_mm = (g[0] * mz - g[2] * mx) / sqrt(gh2);
  *depth_mm = t;
  return true;
}

// A walker's frame. Lengths are measured in units of the walker's own height (times the
// prior's mean, to read as mm): the world's scale is then set by the stature prior alone
// (in plain mm, shrinking the world would shrink every residual, and on vtest.avi that
// put the walkers at 1.51 m against a 1.70 m prior). A head scales with its person.
struct PairCost {
  Pair pair;
  double person_height_mm;
  double head_radius_mm;
  double foot_share;
  template <typename T>
  bool operator()(const T* camera, const T* walker, T* residual) const {
    const T own = walker[kWalkerHeight] / person_height_mm;
    T height, miss, depth;
    if (!HeadOnVertical(camera, pair, own * head_radius_mm, walker[kWalkerHeight] * foot_share, &height, &miss, &depth))
      return false;
    residual[0] = (height - walker[kWalkerHeight]) / (own * pair.sd_within_mm);
    residual[1] = (miss - walker[kWalkerLean]) / (own * pair.sd_line_mm);
    return true;
  }
};

struct WalkerPrior {
  double height_mm, height_sd_mm, lean_sd_mm;
  template <typename T>
  bool operator()(const T* walker, T* residual) const {
    residual[0] = (walker[kWalkerHeight] - height_mm) / height_sd_mm;
    residual[1] = walker[kWalkerLean] / lean_sd_mm;
    return true;
  }
};

std::string Fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

}  // namespace

void RequireDetermined(const std::string& where, const Estimate& focal_px, const Estimate& height_mm,
                       const Estimate& tilt_deg, const Estimate& roll_deg, const WalkerCalibrationOptions& options) {
  auto refuse = [&](const std::string& name, const std::string& value) {
    ThrowInputError(where, "the walkers do not determine the " + name + " (" + value +
                               "): walkers nearer to and farther from the camera, more of them, or a longer video "
                               "would; or give the camera's intrinsics (--camera)");
  };
  if (focal_px.sd > options.max_relative_sd * focal_px.value) {
    refuse("focal length", Fixed(focal_px.value, 0) + " +- " + Fixed(focal_px.sd, 0) + " px");
  }
  if (height_mm.sd > options.max_relative_sd * height_mm.value) {
    refuse("camera's height", Fixed(height_mm.value, 0) + " +- " + Fixed(height_mm.sd, 0) + " mm");
  }
  if (tilt_deg.sd > options.max_angle_sd_deg) {
    refuse("tilt", Fixed(tilt_deg.value, 1) + " +- " + Fixed(tilt_deg.sd, 1) + " degrees");
  }
  if (roll_deg.sd > options.max_angle_sd_deg) {
    refuse("roll", Fixed(roll_deg.value, 1) + " +- " + Fixed(roll_deg.sd, 1) + " degrees");
  }
}

CameraAngles AnglesOf(const Camera& camera) {
  const Eigen::Matrix3d& r = camera.cam_from_world_rotation;
  const Eigen::Vector3d up_in_camera = r.col(1);
  CameraAngles angles;
  angles.tilt_deg = std::asin(std::clamp(-r(2, 1), -1.0, 1.0)) / kDeg;
  angles.roll_deg = std::atan2(up_in_camera.x(), -up_in_camera.y()) / kDeg;
  angles.height_mm = camera.CentreInWorld().y();
  return angles;
}

WalkerCalibration CalibrateFromWalkers(const std::vector<HeadFoot>& points, int width, int height,
                                       const WalkerCalibrationOptions& options) {
  const std::string where = "calibration from walkers";
  if (width <= 0 || height <= 0) ThrowInputError(where, "the image size must be positive");
  if (static_cast<int>(points.size()) < options.min_points) {
    ThrowInputError(where, "need at least " + std::to_string(options.min_points) +
                               " head-foot points of people wholly in view, got " + std::to_string(points.size()) +
                               " (a longer video, or walkers who stay clear of the image's edges)");
  }
  // Ideal pixels, and the person's height in them for the noise model.
  const Camera reference = LookAtCamera("cam0", width, height, 1, Eigen::Vector3d(0, 1000, 0),
                                        Eigen::Vector3d(0, 1000, 1000));
  const bool fixed_focal = options.intrinsics.has_value();
  Camera intrinsics = fixed_focal ? *options.intrinsics : reference;
  intrinsics.cam_from_world_rotation.setIdentity();
  intrinsics.cam_from_world_translation_mm.setZero();
  if (fixed_focal && (intrinsics.width != width || intrinsics.height != height)) {
    ThrowInputError(where, "the camera's intrinsics are for " + std::to_string(intrinsics.width) + "x" +
                               std::to_string(intrinsics.height) + " images, the video's are " +
                               std::to_string(width) + "x" + std::to_string(height));
  }
  auto ideal = [&](const Eigen::Vector2d& pixel) { return IdealPixel(intrinsics, pixel); };
  std::map<int, int> walker_index;
  std::vector<Pair> pairs;
  std::vector<int> pair_walker;
  for (const HeadFoot& point : points) {
    if (!point.head_px.allFinite() || !point.foot_px.allFinite()) ThrowInputError(where, "a point is not finite");
    Pair pair{ideal(point.head_px), ideal(point.foot_px)};
    const double apart_px = (pair.foot - pair.head).norm();
    if (!(apart_px > 4)) ThrowInputError(where, "a head and foot point less than 4 px apart");
    const double person_px = apart_px / (1 - options.foot_share);
    pair.sd_within_mm = std::hypot(options.within_sd_mm, options.edge_sd_px * options.person_height_mm / person_px);
    pair.sd_line_mm = std::hypot(options.line_sd_mm, options.edge_sd_px * options.person_height_mm / person_px);
    pairs.push_back(pair);
    pair_walker.push_back(walker_index.emplace(point.walker, walker_index.size()).first->second);
  }
  const int walkers = static_cast<int>(walker_index.size());
  std::vector<int> frames_of(walkers, 0);
  for (int w : pair_walker) ++frames_of[w];
  for (size_t i = 0; i < pairs.size(); ++i) {
    const double correlated = std::sqrt(std::clamp<double>(frames_of[pair_walker[i]], 1, options.correlated_frames));
    pairs[i].sd_within_mm *= correlated;
    pairs[i].sd_line_mm *= correlated;
  }

  double camera[kCameraParameters] = {0, 0, 0, 0};
  std::vector<double> walker(walkers * kWalkerParameters);
  auto reset_walkers = [&] {
    for (int w = 0; w < walkers; ++w) {
      walker[w * kWalkerParameters + kWalkerHeight] = options.person_height_mm;
      walker[w * kWalkerParameters + kWalkerLean] = 0;
    }
  };
  // The fit over the walkers `kept` says yes to (all when empty), of `cam` and `own`.
  auto add_fit = [&](ceres::Problem* problem, double* cam, std::vector<double>* own, const std::vector<bool>& kept) {
    for (size_t i = 0; i < pairs.size(); ++i) {
      if (!kept.empty() && !kept[pair_walker[i]]) continue;
      auto* cost = new PairCost{pairs[i], options.person_height_mm, options.head_radius_mm, options.foot_share};
      problem->AddResidualBlock(
          new ceres::AutoDiffCostFunction<PairCost, 2, kCameraParameters, kWalkerParameters>(cost),
          new ceres::HuberLoss(2.0), cam, &(*own)[pair_walker[i] * kWalkerParameters]);
    }
    for (int w = 0; w < walkers; ++w) {
      if (!kept.empty() && !kept[w]) continue;
      problem->AddResidualBlock(new ceres::AutoDiffCostFunction<WalkerPrior, 2, kWalkerParameters>(new WalkerPrior{
                                    options.person_height_mm, options.person_height_sd_mm, options.lean_sd_mm}),
                                nullptr, &(*own)[w * kWalkerParameters]);
    }
    if (fixed_focal) problem->SetManifold(cam, new ceres::SubsetManifold(kCameraParameters, {kLogFocal}));
    // A camera on its side or upside down would explain heads below feet: rolls beyond
    // kMaxRoll are not cameras over walkers (their images are turned upright first).
    problem->SetParameterLowerBound(cam, kRoll, -kMaxRollDeg * kDeg);
    problem->SetParameterUpperBound(cam, kRoll, kMaxRollDeg * kDeg);
  };
  ceres::Problem problem;
  add_fit(&problem, camera, &walker, {});

  // Starts: a grid of fields of view and tilts (roll 0), each with the height that makes
  // the median walker person-height tall (heights scale with the camera's, the head's
  // roundness aside); the best few by their starting cost are solved.
  struct Start {
    double cost;
    double camera[kCameraParameters];
  };
  std::vector<Start> starts;
  const std::vector<double> fovs = fixed_focal ? std::vector<double>{0} : std::vector<double>{30, 45, 60, 75, 90, 110};
  for (double fov : fovs) {
    for (double tilt : {-5.0, 5.0, 15.0, 25.0, 35.0, 50.0, 65.0}) {
      Start start;
      start.camera[kLogFocal] =
          fixed_focal ? std::log(intrinsics.fx) : std::log(width / 2.0 / std::tan(fov * kDeg / 2));
      start.camera[kTilt] = tilt * kDeg;
      start.camera[kRoll] = 0;
      start.camera[kLogHeight] = 0;
      std::vector<double> unit_heights;
      bool valid = true;
      for (const Pair& pair : pairs) {
        double head_height, miss, depth;
        valid = valid && HeadOnVertical(start.camera, pair, 0.0, 0.0, &head_height, &miss, &depth) && head_height > 0;
        if (!valid) break;
        unit_heights.push_back(head_height);
      }
      if (!valid) continue;
      std::nth_element(unit_heights.begin(), unit_heights.begin() + unit_heights.size() / 2, unit_heights.end());
      start.camera[kLogHeight] = std::log(options.person_height_mm / unit_heights[unit_heights.size() / 2]);
      std::copy(start.camera, start.camera + kCameraParameters, camera);
      reset_walkers();
      if (!problem.Evaluate(ceres::Problem::EvaluateOptions(), &start.cost, nullptr, nullptr, nullptr)) continue;
      starts.push_back(start);
    }
  }
  if (starts.empty()) {
    ThrowInputError(where, "no camera looking down at a floor puts every foot point below its horizon: are these "
                           "upright people on one floor, and the image the right way up?");
  }
  std::sort(starts.begin(), starts.end(), [](const Start& a, const Start& b) { return a.cost < b.cost; });
  starts.resize(std::min<size_t>(starts.size(), 5));

  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = 200;
  solver.logging_type = ceres::SILENT;
  double best_cost = HUGE_VAL;
  std::vector<double> best_walker;
  double best_camera[kCameraParameters];
  for (const Start& start : starts) {
    std::copy(start.camera, start.camera + kCameraParameters, camera);
    reset_walkers();
    ceres::Solver::Summary summary;
    ceres::Solve(solver, &problem, &summary);
    if (summary.IsSolutionUsable() && summary.final_cost < best_cost) {
      best_cost = summary.final_cost;
      std::copy(camera, camera + kCameraParameters, best_camera);
      best_walker = walker;
    }
  }
  if (!std::isfinite(best_cost)) ThrowInputError(where, "the fit did not converge from any start");
  std::copy(best_camera, best_camera + kCameraParameters, camera);
  walker = best_walker;

  // Uncertainty: the covariance at the minimum (singular: a direction the walkers leave
  // free), scaled by the residuals' spread when it exceeds the noise stated above.
  ceres::Covariance::Options covariance_options;
  covariance_options.algorithm_type = ceres::DENSE_SVD;
  covariance_options.null_space_rank = 0;
  ceres::Covariance covariance(covariance_options);
  const std::vector<std::pair<const double*, const double*>> blocks = {{camera, camera}};
  double c[kCameraParameters * kCameraParameters];
  if (!covariance.Compute(blocks, &problem) || !covariance.GetCovarianceBlock(camera, camera, c)) {
    ThrowInputError(where, "the walkers do not determine the camera (the fit's covariance is singular): walkers "
                           "nearer to and farther from the camera, or in more of the image, would");
  }
  const int residuals = problem.NumResiduals();
  const int parameters = (fixed_focal ? 3 : 4) + walkers * kWalkerParameters;
  const double spread = residuals > parameters ? 2 * best_cost / (residuals - parameters) : 1;
  const double scale = std::max(1.0, spread);
  auto sd = [&](int i) { return std::sqrt(std::max(0.0, c[i * kCameraParameters + i] * scale)); };

  // The jackknife over groups of walkers (the options say why), each refit from the fit.
  Eigen::Vector4d walkers_sd = Eigen::Vector4d::Zero();
  const int groups = std::min(options.jackknife_groups, walkers);
  if (groups >= 3) {
    std::vector<Eigen::Vector4d> fits;
    ceres::Solver::Options refit = solver;
    refit.linear_solver_type = ceres::DENSE_SCHUR;  // the walkers' blocks eliminated first
    for (int g = 0; g < groups; ++g) {
      std::vector<bool> kept(walkers);
      for (int w = 0; w < walkers; ++w) kept[w] = w % groups != g;
      Eigen::Vector4d cam = Eigen::Map<const Eigen::Vector4d>(camera);
      std::vector<double> own = walker;
      ceres::Problem without;
      add_fit(&without, cam.data(), &own, kept);
      ceres::Solver::Summary summary;
      ceres::Solve(refit, &without, &summary);
      if (summary.IsSolutionUsable()) fits.push_back(cam);
    }
    if (static_cast<int>(fits.size()) == groups) {
      Eigen::Vector4d mean = Eigen::Vector4d::Zero();
      for (const Eigen::Vector4d& f : fits) mean += f / groups;
      for (const Eigen::Vector4d& f : fits) walkers_sd += (f - mean).cwiseAbs2() * (groups - 1.0) / groups;
      walkers_sd = walkers_sd.cwiseSqrt();
    }
  }

  WalkerCalibration result;
  result.walkers = walkers;
  std::copy(camera, camera + kCameraParameters, result.parameters.begin());
  result.covariance = Eigen::Map<const Eigen::Matrix4d>(c) * scale;  // symmetric: storage order moot
  const double focal = std::exp(camera[kLogFocal]);
  const double camera_height = std::exp(camera[kLogHeight]);
  result.focal_px = {fixed_focal ? intrinsics.fx : focal, fixed_focal ? 0 : focal * sd(kLogFocal),
                     fixed_focal ? 0 : focal * walkers_sd[kLogFocal]};
  result.height_mm = {camera_height, camera_height * sd(kLogHeight), camera_height * walkers_sd[kLogHeight]};
  result.tilt_deg = {camera[kTilt] / kDeg, sd(kTilt) / kDeg, walkers_sd[kTilt] / kDeg};
  result.roll_deg = {camera[kRoll] / kDeg, sd(kRoll) / kDeg, walkers_sd[kRoll] / kDeg};
  for (int w = 0; w < walkers; ++w) result.walker_heights_mm.push_back(walker[w * kWalkerParameters + kWalkerHeight]);
  double line2 = 0, height2 = 0;
  for (size_t i = 0; i < pairs.size(); ++i) {
    double head_height = 0, miss = 0, depth = 1;
    const double* own = &walker[pair_walker[i] * kWalkerParameters];
    HeadOnVertical(camera, pairs[i], options.head_radius_mm * own[kWalkerHeight] / options.person_height_mm,
                   own[kWalkerHeight] * options.foot_share, &head_height, &miss, &depth);
    line2 += std::pow((miss - own[kWalkerLean]) * focal / depth, 2);
    height2 += std::pow(head_height - own[kWalkerHeight], 2);
  }
  result.rms_line_px = std::sqrt(line2 / pairs.size());
  result.rms_height_mm = std::sqrt(height2 / pairs.size());

  if (options.refuse_undetermined) {
    RequireDetermined(where, result.focal_px, result.height_mm, result.tilt_deg, result.roll_deg, options);
  }

  const Camera placed = WalkerCamera(intrinsics, result.parameters, fixed_focal);
  result.camera = placed;
  return result;
}

}  // namespace jgpm
