#include "calibration/rig_placement.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <optional>
#include <string>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/QR>
#include <ceres/ceres.h>

#include "calibration/walker_camera.h"
#include "io/base/error.h"

namespace jgpm {
namespace {

constexpr double kDeg = std::numbers::pi / 180;

// One sighting's floor point in its camera's world.
struct Sighting {
  int frame = 0;
  int walker = 0;  // the camera's own number
  Eigen::Vector2d floor = Eigen::Vector2d::Zero();  // (x, z), mm
  Eigen::Vector2d ideal = Eigen::Vector2d::Zero();  // the foot pixel, walker_camera.h's
};

// A similarity of the floor: p -> scale * rotation * p + shift.
struct Similarity {
  double scale = 1;
  Eigen::Matrix2d rotation = Eigen::Matrix2d::Identity();
  Eigen::Vector2d shift = Eigen::Vector2d::Zero();
  Eigen::Vector2d operator()(const Eigen::Vector2d& p) const { return scale * rotation * p + shift; }
};

// Least squares from `from` to `to` (columns matched), or nothing when the points are too
// few or too close together to fix a turn.
std::optional<Similarity> Fit(const Eigen::Matrix2Xd& from, const Eigen::Matrix2Xd& to, double min_spread_mm) {
  if (from.cols() < 3) return std::nullopt;
  const Eigen::Vector2d mean = from.rowwise().mean();
  const double spread = std::sqrt((from.colwise() - mean).squaredNorm() / from.cols());
  if (!(spread >= min_spread_mm)) return std::nullopt;
  const Eigen::Matrix3d m = Eigen::umeyama(from, to, true);
  Similarity s;
  s.scale = std::sqrt(std::abs(m.topLeftCorner<2, 2>().determinant()));
  if (!(s.scale > 0) || !m.allFinite()) return std::nullopt;
  s.rotation = m.topLeftCorner<2, 2>() / s.scale;
  s.shift = m.topRightCorner<2, 1>();
  return s;
}

// `camera` (in its own world) moved by the floor similarity into the rig's world.
Camera Moved(const Camera& camera, const Similarity& s) {
  Eigen::Matrix3d turn = Eigen::Matrix3d::Identity();  // on (x, y, z), about y
  turn(0, 0) = s.rotation(0, 0);
  turn(0, 2) = s.rotation(0, 1);
  turn(2, 0) = s.rotation(1, 0);
  turn(2, 2) = s.rotation(1, 1);
  const Eigen::Vector3d shift(s.shift.x(), 0, s.shift.y());
  // A point X in the rig's world is turn^T (X - shift) / scale in the camera's own; the
  // camera's coordinates scaled by `scale` project to the same pixels.
  Camera moved = camera;
  moved.cam_from_world_rotation = camera.cam_from_world_rotation * turn.transpose();
  moved.cam_from_world_translation_mm =
      s.scale * camera.cam_from_world_translation_mm - moved.cam_from_world_rotation * shift;
  return moved;
}

// Sightings by frame, in the rig's world, each with the camera it came from.
struct Pool {
  std::map<int, std::vector<std::pair<Eigen::Vector2d, int>>> by_frame;
  void Add(const std::vector<Sighting>& sightings, int camera) {
    for (const Sighting& s : sightings) by_frame[s.frame].push_back({s.floor, camera});
  }
  // The sighting at `frame` nearest `p` within `within`: its place in by_frame[frame], or -1.
  int Nearest(int frame, const Eigen::Vector2d& p, double within) const {
    const auto it = by_frame.find(frame);
    if (it == by_frame.end()) return -1;
    int best = -1;
    double best_distance = within;
    for (size_t i = 0; i < it->second.size(); ++i) {
      const double d = (it->second[i].first - p).norm();
      if (d <= best_distance) best_distance = d, best = static_cast<int>(i);
    }
    return best;
  }
};

// The cameras placed so far: their sightings, their walkers' tracks and where they look.
struct PlacedSet {
  Pool pool;
  std::vector<std::map<int, Eigen::Vector2d>> walkers;  // each walker's floor points by frame
  std::vector<Camera> cameras;                          // in the rig's world
  std::vector<std::pair<int, int>> spans;               // each camera's first and last frame

  void Add(const Camera& camera, const std::vector<Sighting>& sightings, int index) {
    pool.Add(sightings, index);
    std::map<int, int> walker_index;
    std::pair<int, int> span{INT_MAX, INT_MIN};
    for (const Sighting& s : sightings) {
      const auto [it, added] = walker_index.emplace(s.walker, static_cast<int>(walkers.size()));
      if (added) walkers.emplace_back();
      walkers[it->second][s.frame] = s.floor;
      span = {std::min(span.first, s.frame), std::max(span.second, s.frame)};
    }
    cameras.push_back(camera);
    spans.push_back(span);
  }

  // Whether a placed camera recording at `frame` had a person standing at `floor` wholly in
  // its view (feet and head inside the image, clear of its edges by kEdge of its size).
  bool Seen(int frame, const Eigen::Vector2d& floor, const RigPlacementOptions& options) const {
    constexpr double kEdge = 0.03;
    for (size_t c = 0; c < cameras.size(); ++c) {
      if (frame < spans[c].first || frame > spans[c].second) continue;
      const Camera& camera = cameras[c];
      auto inside = [&](double height) {
        Eigen::Vector2d q;
        return camera.Project({floor.x(), height, floor.y()}, &q) && q.x() > kEdge * camera.width &&
               q.x() < (1 - kEdge) * camera.width && q.y() > kEdge * camera.height &&
               q.y() < (1 - kEdge) * camera.height;
      };
      if (inside(options.foot_height_mm) && inside(options.person_height_mm)) return true;
    }
    return false;
  }
};

struct Matches {
  Eigen::Matrix2Xd from, to;  // the camera's floor points, and the placed ones they matched
  std::vector<int> against;   // the placed camera each match came from
  int walkers = 0;            // the camera's walkers with min_shared_frames matches or more
  int expected = 0;           // its sightings that a placed camera should have seen
  int size() const { return static_cast<int>(from.cols()); }
  // A placement is confirmed by two walkers: any straight walk seen by one camera maps onto
  // any other of about its length and speed (a similarity has four parameters), so one walker
  // cannot tell a right placement from clocks that disagree. And by the other cameras' view:
  // most of the people it puts in a placed camera's view must have been seen there (a wrong
  // placement matched 14-20% on the tests' crowds; a right one 94-99%).
  bool Confirmed(const RigPlacementOptions& options) const {
    return walkers >= 2 && size() >= options.min_matches && size() >= options.min_seen_share * expected;
  }
  bool Better(const Matches& other, const RigPlacementOptions& options) const {
    const bool confirmed = Confirmed(options), other_confirmed = other.Confirmed(options);
    return confirmed != other_confirmed ? confirmed : size() > other.size();
  }
};

Matches Match(const std::vector<Sighting>& sightings, const Similarity& s, const PlacedSet& placed,
              const RigPlacementOptions& options) {
  std::vector<Eigen::Vector2d> from, to;
  std::map<int, int> per_walker;
  Matches m;
  for (const Sighting& sighting : sightings) {
    const Eigen::Vector2d p = s(sighting.floor);
    const int q = placed.pool.Nearest(sighting.frame, p, options.match_mm);
    if (q < 0) {
      m.expected += placed.Seen(sighting.frame, p, options);
      continue;
    }
    const auto& [point, camera] = placed.pool.by_frame.at(sighting.frame)[q];
    ++m.expected;
    from.push_back(sighting.floor);
    to.push_back(point);
    m.against.push_back(camera);
    ++per_walker[sighting.walker];
  }
  for (const auto& [walker, count] : per_walker) m.walkers += count >= options.min_shared_frames;
  m.from.resize(2, from.size());
  m.to.resize(2, to.size());
  for (size_t i = 0; i < from.size(); ++i) m.from.col(i) = from[i], m.to.col(i) = to[i];
  return m;
}

struct Candidate {
  Similarity similarity;
  Matches matches;
};

// The best placement of `sightings` among the placed cameras: every walker pair's
// similarity scored by its matches, the best refitted on them.
std::optional<Candidate> BestPlacement(const std::vector<Sighting>& sightings, const PlacedSet& placed,
                                       const RigPlacementOptions& options) {
  std::map<int, std::vector<const Sighting*>> walkers;
  for (const Sighting& s : sightings) walkers[s.walker].push_back(&s);
  std::optional<Candidate> best;
  auto consider = [&](const Similarity& s) {
    if (std::abs(std::log(s.scale)) > std::log(options.max_scale_ratio)) return;
    Candidate c{s, Match(sightings, s, placed, options)};
    if (!best || c.matches.Better(best->matches, options)) best = std::move(c);
  };
  for (const auto& [id, mine] : walkers) {
    for (const std::map<int, Eigen::Vector2d>& other : placed.walkers) {
      std::vector<Eigen::Vector2d> from, to;
      for (const Sighting* s : mine) {
        const auto it = other.find(s->frame);
        if (it == other.end()) continue;
        from.push_back(s->floor);
        to.push_back(it->second);
      }
      if (static_cast<int>(from.size()) < options.min_shared_frames) continue;
      Eigen::Matrix2Xd a(2, from.size()), b(2, to.size());
      for (size_t i = 0; i < from.size(); ++i) a.col(i) = from[i], b.col(i) = to[i];
      if (const std::optional<Similarity> s = Fit(a, b, options.min_spread_mm)) consider(*s);
    }
  }
  if (!best) return best;
  // Refitted on its matches until they settle.
  for (int round = 0; round < 5; ++round) {
    const std::optional<Similarity> s = Fit(best->matches.from, best->matches.to, options.min_spread_mm);
    if (!s || std::abs(std::log(s->scale)) > std::log(options.max_scale_ratio)) break;
    Matches m = Match(sightings, *s, placed, options);
    if (!m.Better(best->matches, options) && m.size() <= best->matches.size()) break;
    best = Candidate{*s, std::move(m)};
  }
  return best;
}

// How tightly a candidate's matches agree: the sum over them of 1 - (distance /
// match_mm)^2 (RANSAC's MSAC score). Offsets a frame or two from the truth match almost as
// many sightings (a walker moves 50 mm a frame), but farther apart.
double Tightness(const Candidate& c, const RigPlacementOptions& options) {
  double score = 0;
  for (int i = 0; i < c.matches.size(); ++i) {
    const double d = (c.similarity(c.matches.from.col(i)) - c.matches.to.col(i)).norm() / options.match_mm;
    score += std::max(0.0, 1 - d * d);
  }
  return score;
}

// The best placement over the clock offsets within options.max_clock_offset_frames
// (rig_placement.h): confirmed first, then the tightest; tried every step frames, then
// frame by frame around the best; ties go to the offset nearest 0. Each offset's
// placement is refitted on its own matches, so the tightness is noisy from one offset to
// the next (+-5% on the tests' walks, across a peak about 20 frames wide): the offset
// taken is the vertex of a parabola fitted to the confirmed offsets' tightness within
// offset_fit_frames of the tightest, when it opens downwards. Its offset in `offset`.
std::optional<Candidate> BestOffsetPlacement(const std::vector<Sighting>& sightings, const PlacedSet& placed,
                                             const RigPlacementOptions& options, int* offset) {
  struct Tried {
    Candidate candidate;
    double tightness;
    bool confirmed;
  };
  std::map<int, std::optional<Tried>> tried;
  std::vector<Sighting> shifted;
  const int limit = options.max_clock_offset_frames;
  auto consider = [&](int d) {
    if (std::abs(d) > limit || tried.count(d)) return;
    shifted = sightings;
    for (Sighting& s : shifted) s.frame += d;
    std::optional<Candidate> c = BestPlacement(shifted, placed, options);
    std::optional<Tried>& t = tried[d];
    if (c) t = Tried{*c, Tightness(*c, options), c->matches.Confirmed(options)};
  };
  // Confirmed first, then the tightest, then nearest 0.
  auto best_of = [&] {
    std::optional<int> best;
    for (const auto& [d, t] : tried) {
      if (!t) continue;
      const Tried& b = best ? *tried[*best] : *t;
      if (!best || (t->confirmed != b.confirmed ? t->confirmed
                    : t->tightness != b.tightness ? t->tightness > b.tightness
                                                  : std::abs(d) < std::abs(*best))) {
        best = d;
      }
    }
    return best;
  };
  const int step = std::max(1, options.min_shared_frames / 2);
  for (int d = 0; d <= limit; d += step) consider(d), consider(-d);
  std::optional<int> best = best_of();
  if (!best) return std::nullopt;
  const int window = std::max(step, options.offset_fit_frames);
  if (limit > 0) {
    for (int d = -window; d <= window; ++d) consider(*best + d);
    best = best_of();
    // Least squares t = a d^2 + b d + c over the window's confirmed offsets (d from the best).
    std::vector<Eigen::Vector3d> rows;
    std::vector<double> values;
    for (int d = -window; d <= window; ++d) {
      const auto it = tried.find(*best + d);
      if (it == tried.end() || !it->second || !it->second->confirmed) continue;
      rows.emplace_back(d * d, d, 1);
      values.push_back(it->second->tightness);
    }
    if (rows.size() >= 5 && tried[*best]->confirmed) {
      Eigen::MatrixXd a(rows.size(), 3);
      Eigen::VectorXd t(rows.size());
      for (size_t i = 0; i < rows.size(); ++i) a.row(i) = rows[i].transpose(), t(i) = values[i];
      const Eigen::Vector3d fit = a.colPivHouseholderQr().solve(t);
      if (fit(0) < 0) {
        const int vertex = *best + static_cast<int>(std::lround(std::clamp(-fit(1) / (2 * fit(0)), -1.0 * window, 1.0 * window)));
        const auto it = tried.find(vertex);
        if (it != tried.end() && it->second && it->second->confirmed) best = vertex;
      }
    }
  }
  *offset = *best;
  return std::move(tried[*best]->candidate);
}

// A sighting's floor point in the rig's world: its ideal foot pixel's ray from the camera
// of `camera` (walker_camera.h) down to `foot_mm`, turned by pose[0] about the vertical and
// shifted by (pose[1], pose[2]) on the floor.
template <typename T>
bool FloorInRig(const T* camera, const T* pose, const Eigen::Vector2d& q, double foot_mm, T* out) {
  using std::cos, std::exp, std::sin;
  T w[3];
  WalkerCameraRay(camera, q, w);
  if (!(w[1] < T(-1e-9))) return false;
  const T t = (exp(camera[kLogHeight]) - T(foot_mm)) / -w[1];
  if (!(t > T(0))) return false;
  const T x = t * w[0], z = t * w[2], c = cos(pose[0]), s = sin(pose[0]);
  out[0] = c * x + s * z + pose[1];
  out[1] = -s * x + c * z + pose[2];
  return true;
}

// Two cameras' sightings of one person at one frame: one floor point.
struct MatchCost {
  Eigen::Vector2d a, b;  // ideal foot pixels
  double foot_mm, sd_mm;
  template <typename T>
  bool operator()(const T* camera_a, const T* pose_a, const T* camera_b, const T* pose_b, T* residual) const {
    T pa[2], pb[2];
    if (!FloorInRig(camera_a, pose_a, a, foot_mm, pa) || !FloorInRig(camera_b, pose_b, b, foot_mm, pb)) return false;
    residual[0] = (pa[0] - pb[0]) / sd_mm;
    residual[1] = (pa[1] - pb[1]) / sd_mm;
    return true;
  }
};

// A camera's own calibration as a Gaussian prior on its parameters: residual W (p - mean)
// with W^T W the covariance's pseudo-inverse (whitened by its eigenvectors; directions its
// walkers left free, such as a focal length given by the user, carry no prior).
struct OwnCalibrationCost {
  WalkerCameraParameters mean;
  Eigen::Matrix4d whiten;
  template <typename T>
  bool operator()(const T* camera, T* residual) const {
    for (int i = 0; i < 4; ++i) {
      residual[i] = T(0);
      for (int j = 0; j < 4; ++j) residual[i] += whiten(i, j) * (camera[j] - mean[j]);
    }
    return true;
  }
};

Eigen::Matrix4d Whitening(const Eigen::Matrix4d& covariance) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(covariance);
  Eigen::Matrix4d whiten = Eigen::Matrix4d::Zero();
  const double largest = eigen.eigenvalues().maxCoeff();
  for (int i = 0; i < 4; ++i) {
    const double value = eigen.eigenvalues()(i);
    if (value > 1e-12 * largest) whiten.row(i) = eigen.eigenvectors().col(i).transpose() / std::sqrt(value);
  }
  return whiten;
}

// Every camera's parameters and place refined together: each camera's own calibration as a
// prior, and every pair of sightings that the placement found to be one person at one frame
// (in any two cameras) as one floor point. Fills in rig's cameras and their uncertainties.
void Refine(const std::vector<RigCamera>& cameras, const std::vector<std::vector<Sighting>>& sightings,
            const std::vector<Similarity>& similarity, const std::vector<std::vector<Sighting>>& in_rig,
            const RigPlacementOptions& options, RigPlacement* rig) {
  const int n = static_cast<int>(cameras.size());
  std::vector<WalkerCameraParameters> camera(n);
  std::vector<std::array<double, 3>> pose(n);
  for (int k = 0; k < n; ++k) {
    camera[k] = cameras[k].calibration.parameters;
    // The similarity's scale is the camera's height's error relative to cam0's.
    camera[k][kLogHeight] += std::log(similarity[k].scale);
    pose[k] = {std::atan2(similarity[k].rotation(0, 1), similarity[k].rotation(0, 0)), similarity[k].shift.x(),
               similarity[k].shift.y()};
  }
  ceres::Problem problem;
  struct Pair {
    int a, b;
    const Sighting *sa, *sb;
  };
  std::vector<Pair> pairs;
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      Pool pool;  // b's sightings by frame, in the rig, each with its index
      for (size_t i = 0; i < in_rig[b].size(); ++i) {
        pool.by_frame[in_rig[b][i].frame].push_back({in_rig[b][i].floor, static_cast<int>(i)});
      }
      for (size_t i = 0; i < in_rig[a].size(); ++i) {
        const int q = pool.Nearest(in_rig[a][i].frame, in_rig[a][i].floor, options.match_mm);
        if (q >= 0) pairs.push_back({a, b, &sightings[a][i], &sightings[b][pool.by_frame[in_rig[a][i].frame][q].second]});
      }
    }
  }
  // Consecutive matches share their errors: each pair of cameras' matches count as one per
  // correlated_frames.
  std::map<std::pair<int, int>, int> per_pair;
  for (const Pair& p : pairs) ++per_pair[{p.a, p.b}];
  for (size_t i = 0; i < pairs.size(); ++i) {
    const Pair& p = pairs[i];
    const double correlated =
        std::sqrt(std::clamp<double>(per_pair[{p.a, p.b}], 1, options.correlated_frames));
    auto* cost = new MatchCost{p.sa->ideal,
                               p.sb->ideal, options.foot_height_mm,
                               options.match_sd_mm * correlated};
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<MatchCost, 2, 4, 3, 4, 3>(cost),
                             new ceres::HuberLoss(2.0), camera[p.a].data(), pose[p.a].data(), camera[p.b].data(),
                             pose[p.b].data());
  }
  for (int k = 0; k < n; ++k) {
    const WalkerCalibration& own = cameras[k].calibration;
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<OwnCalibrationCost, 4, 4>(
                                 new OwnCalibrationCost{own.parameters, Whitening(own.covariance)}),
                             nullptr, camera[k].data());
    if (own.covariance(kLogFocal, kLogFocal) == 0) {  // the user's focal length: kept
      problem.SetManifold(camera[k].data(), new ceres::SubsetManifold(4, {kLogFocal}));
    }
  }
  problem.SetParameterBlockConstant(pose[0].data());  // cam0's floor is the rig's
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = 100;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  if (!summary.IsSolutionUsable()) {
    ThrowInputError("placing cameras from the walkers they share", "the joint fit failed: " + summary.message);
  }
  // Uncertainties from the covariance at the minimum, scaled up by the residuals' spread
  // when wider than stated.
  ceres::Covariance::Options covariance_options;
  covariance_options.algorithm_type = ceres::DENSE_SVD;
  covariance_options.null_space_rank = -1;  // cam0's pose is constant; a user's focal too
  ceres::Covariance covariance(covariance_options);
  std::vector<std::pair<const double*, const double*>> blocks;
  for (int k = 0; k < n; ++k) {
    blocks.push_back({camera[k].data(), camera[k].data()});
    if (k > 0) blocks.push_back({pose[k].data(), pose[k].data()});
  }
  const bool have_covariance = covariance.Compute(blocks, &problem);
  const int dof = std::max(1, problem.NumResiduals() - problem.NumParameters());
  const double spread = std::max(1.0, 2 * summary.final_cost / dof);
  std::vector<double> sum2(n, 0);
  std::vector<int> count(n, 0);
  for (const Pair& p : pairs) {
    double pa[2], pb[2];
    if (!FloorInRig(camera[p.a].data(), pose[p.a].data(), p.sa->ideal,
                    options.foot_height_mm, pa) ||
        !FloorInRig(camera[p.b].data(), pose[p.b].data(), p.sb->ideal,
                    options.foot_height_mm, pb))
      continue;
    const double d2 = std::pow(pa[0] - pb[0], 2) + std::pow(pa[1] - pb[1], 2);
    for (int k : {p.a, p.b}) sum2[k] += d2, ++count[k];
  }
  for (int k = 0; k < n; ++k) {
    const WalkerCalibration& own = cameras[k].calibration;
    PlacedCamera& out = rig->cameras[k];
    const bool keep_focal = own.covariance(kLogFocal, kLogFocal) == 0;
    const Camera local = WalkerCamera(own.camera, camera[k], keep_focal);
    Similarity s;
    s.rotation << std::cos(pose[k][0]), std::sin(pose[k][0]), -std::sin(pose[k][0]), std::cos(pose[k][0]);
    s.shift = {pose[k][1], pose[k][2]};
    out.camera = Moved(local, s);
    out.camera.name = own.camera.name;
    out.rms_mm = count[k] ? std::sqrt(sum2[k] / count[k]) : 0;
    double c[16] = {0}, q[9] = {0};
    if (have_covariance) {
      covariance.GetCovarianceBlock(camera[k].data(), camera[k].data(), c);
      if (k > 0) covariance.GetCovarianceBlock(pose[k].data(), pose[k].data(), q);
    }
    auto sd = [spread](const double* m, int i, int size) { return std::sqrt(std::max(0.0, m[i * size + i] * spread)); };
    const double focal = std::exp(camera[k][kLogFocal]), height = std::exp(camera[k][kLogHeight]);
    out.focal_px = {keep_focal ? own.focal_px.value : focal, keep_focal ? 0 : focal * sd(c, kLogFocal, 4)};
    out.height_mm = {height, height * sd(c, kLogHeight, 4)};
    out.tilt_deg = {camera[k][kTilt] / kDeg, sd(c, kTilt, 4) / kDeg};
    out.roll_deg = {camera[k][kRoll] / kDeg, sd(c, kRoll, 4) / kDeg};
    out.yaw_deg = {YawOf(out.camera), sd(q, 0, 3) / kDeg};
    const Eigen::Vector3d centre = out.camera.CentreInWorld();
    out.x_mm = {centre.x(), sd(q, 1, 3)};
    out.z_mm = {centre.z(), sd(q, 2, 3)};
  }
}

}  // namespace

double YawOf(const Camera& camera) {
  const Eigen::Vector3d forward = camera.cam_from_world_rotation.row(2).transpose();
  return std::atan2(forward.x(), forward.z()) / kDeg;
}

RigPlacement PlaceRig(const std::vector<RigCamera>& cameras, const RigPlacementOptions& options) {
  const std::string where = "placing cameras from the walkers they share";
  if (cameras.size() < 2) ThrowInputError(where, "needs at least two cameras, got " + std::to_string(cameras.size()));
  const int n = static_cast<int>(cameras.size());
  std::vector<std::vector<Sighting>> sightings(n);
  for (int k = 0; k < n; ++k) {
    for (const HeadFoot& point : cameras[k].points) {
      Sighting s{point.frame, point.walker};
      s.ideal = IdealPixel(cameras[k].calibration.camera, point.foot_px);
      // In the camera's own world: its calibration, not turned or shifted.
      constexpr double kOwnPlace[3] = {0, 0, 0};
      if (FloorInRig(cameras[k].calibration.parameters.data(), kOwnPlace, s.ideal, options.foot_height_mm,
                     s.floor.data()) &&
          s.floor.allFinite()) {
        sightings[k].push_back(s);
      }
    }
  }
  RigPlacement rig;
  rig.cameras.resize(n);
  std::vector<Similarity> similarity(n);  // each camera's floor into cam0's
  std::vector<bool> placed(n, false);
  placed[0] = true;
  std::vector<std::vector<Sighting>> in_rig(n);  // placed cameras' sightings in the rig's world
  in_rig[0] = sightings[0];
  for (int round = 1; round < n; ++round) {
    PlacedSet set;
    for (int k = 0; k < n; ++k) {
      if (placed[k]) set.Add(Moved(cameras[k].calibration.camera, similarity[k]), in_rig[k], k);
    }
    int best_camera = -1, best_offset = 0;
    std::optional<Candidate> best;
    for (int k = 0; k < n; ++k) {
      if (placed[k]) continue;
      int offset = 0;
      std::optional<Candidate> c = BestOffsetPlacement(sightings[k], set, options, &offset);
      if (c && (!best || c->matches.Better(best->matches, options))) {
        best = std::move(c);
        best_camera = k;
        best_offset = offset;
      }
    }
    if (!best || !best->matches.Confirmed(options)) {
      int missing = 0;
      while (placed[missing]) ++missing;
      if (best) missing = best_camera;
      char numbers[200];
      std::snprintf(numbers, sizeof numbers, "%d walkers and %d sightings matched, %d%% of those the placed cameras "
                    "should have seen; need 2 walkers, %d sightings and %.0f%%", best ? best->matches.walkers : 0,
                    best ? best->matches.size() : 0,
                    best ? static_cast<int>(std::lround(100.0 * best->matches.size() / std::max(1, best->matches.expected))) : 0,
                    options.min_matches, 100 * options.min_seen_share);
      const std::string clocks =
          options.max_clock_offset_frames > 0
              ? "their clocks within " + std::to_string(options.max_clock_offset_frames) + " frames of each other"
              : "their videos starting together";
      ThrowInputError(where, "cam" + std::to_string(missing) + " shares too few walkers with the cameras placed (" +
                                 numbers + "): the cameras must see the same people walk by at the same time, " +
                                 clocks);
    }
    const int k = best_camera;
    const Similarity& s = best->similarity;
    const Matches& m = best->matches;
    PlacedCamera& out = rig.cameras[k];
    out.matches = m.size();
    out.clock_offset_frames = best_offset;
    std::map<int, int> against;
    for (int c : m.against) ++against[c];
    out.placed_against = std::max_element(against.begin(), against.end(), [](const auto& a, const auto& b) {
                           return a.second < b.second;
                         })->first;
    similarity[k] = s;
    for (Sighting sighting : sightings[k]) {
      sighting.floor = s(sighting.floor);
      sighting.frame += best_offset;
      in_rig[k].push_back(sighting);
    }
    placed[k] = true;
  }
  Refine(cameras, sightings, similarity, in_rig, options, &rig);
  WalkerCalibrationOptions bounds;
  bounds.max_relative_sd = options.max_relative_sd;
  bounds.max_angle_sd_deg = options.max_angle_sd_deg;
  for (int k = 0; k < n; ++k) {
    const PlacedCamera& c = rig.cameras[k];
    RequireDetermined("cam" + std::to_string(k) + ", placed with the others", c.focal_px, c.height_mm, c.tilt_deg,
                      c.roll_deg, bounds);
  }
  return rig;
}

}  // namespace jgpm
