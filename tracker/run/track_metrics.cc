#include "tracker/run/track_metrics.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "io/base/error.h"

namespace jgpm {
namespace {

std::vector<int> Columns(const std::vector<std::string>& bones, const std::vector<std::string>& joints,
                         const std::string& which) {
  std::vector<int> columns;
  for (const std::string& joint : joints) {
    const auto it = std::find(bones.begin(), bones.end(), joint);
    if (it == bones.end()) ThrowInputError(which, "has no bone '" + joint + "' to compare");
    columns.push_back(static_cast<int>(it - bones.begin()));
  }
  return columns;
}

Eigen::Matrix3Xd Select(const Eigen::Matrix3Xd& m, const std::vector<int>& columns) {
  Eigen::Matrix3Xd out(3, columns.size());
  for (size_t j = 0; j < columns.size(); ++j) out.col(j) = m.col(columns[j]);
  return out;
}

double MeanDistance(const Eigen::Matrix3Xd& a, const Eigen::Matrix3Xd& b) { return (a - b).colwise().norm().mean(); }

}  // namespace

const std::vector<std::string>& Bodytrack14() {
  static const std::vector<std::string> joints = {"lhipjoint", "rhipjoint", "lfemur", "rfemur", "ltibia",
                                                  "rtibia",    "lclavicle", "rclavicle", "lhumerus", "rhumerus",
                                                  "lradius",   "rradius",   "thorax", "head"};
  return joints;
}

const std::vector<std::string>& Gait17() {
  static const std::vector<std::string> joints = {"lowerback", "upperback", "thorax",  "upperneck", "head",
                                                  "lfemur",    "ltibia",    "lfoot",   "lhumerus",  "lradius",
                                                  "lwrist",    "rfemur",    "rtibia",  "rfoot",     "rhumerus",
                                                  "rradius",   "rwrist"};
  return joints;
}

Eigen::Matrix3Xd ProcrustesAlign(const Eigen::Matrix3Xd& from, const Eigen::Matrix3Xd& to) {
  const Eigen::Matrix4d t = Eigen::umeyama(from, to, true);
  return (t.topLeftCorner<3, 3>() * from).colwise() + t.topRightCorner<3, 1>();
}

TrackErrors CompareTracks(const std::vector<Eigen::Matrix3Xd>& estimate, const std::vector<std::string>& estimate_bones,
                          const std::vector<Eigen::Matrix3Xd>& truth, const std::vector<std::string>& truth_bones,
                          const std::vector<std::string>& joints) {
  JGPM_CHECK(estimate.size() == truth.size());
  const std::vector<int> e = Columns(estimate_bones, joints, "the track's skeleton");
  const std::vector<int> g = Columns(truth_bones, joints, "the truth's skeleton");
  const int er = Columns(estimate_bones, {"root"}, "the track's skeleton")[0];
  const int gr = Columns(truth_bones, {"root"}, "the truth's skeleton")[0];
  // Legs exchanged: each knee, ankle and foot with its twin on the other side (the hips stay:
  // a leg swap is the walk half a cycle off, not a mirrored body).
  std::vector<int> swapped(joints.size());
  for (size_t j = 0; j < joints.size(); ++j) {
    std::string twin = joints[j];
    const std::string part = twin.size() > 1 ? twin.substr(1) : "";
    if ((twin[0] == 'l' || twin[0] == 'r') && (part == "femur" || part == "tibia" || part == "foot" || part == "toes")) {
      twin[0] = twin[0] == 'l' ? 'r' : 'l';
      const auto it = std::find(joints.begin(), joints.end(), twin);
      swapped[j] = it != joints.end() ? static_cast<int>(it - joints.begin()) : static_cast<int>(j);
    } else {
      swapped[j] = static_cast<int>(j);
    }
  }
  TrackErrors r;
  r.joints = joints;
  r.per_joint_mm.assign(joints.size(), 0.0);
  int failed = 0, swaps = 0;
  std::vector<Eigen::VectorXd> rows;
  for (size_t f = 0; f < truth.size(); ++f) {
    if (truth[f].cols() == 0) continue;
    ++r.frames;
    if (estimate[f].cols() == 0) {
      ++failed;
      r.per_frame_mm.push_back(std::nan(""));
      rows.push_back(Eigen::VectorXd::Constant(joints.size(), std::nan("")));
      continue;
    }
    const Eigen::Matrix3Xd a = Select(estimate[f], e), b = Select(truth[f], g);
    const Eigen::VectorXd distance = (a - b).colwise().norm();
    rows.push_back(distance);
    const double absolute = distance.mean();
    r.absolute_mm += absolute;
    for (size_t j = 0; j < joints.size(); ++j) r.per_joint_mm[j] += distance[j];
    r.root_relative_mm += MeanDistance(a.colwise() - estimate[f].col(er), b.colwise() - truth[f].col(gr));
    r.procrustes_mm += MeanDistance(ProcrustesAlign(a, b), b);
    failed += absolute > 150;
    Eigen::Matrix3Xd exchanged(3, joints.size());
    for (size_t j = 0; j < joints.size(); ++j) exchanged.col(j) = a.col(swapped[j]);
    swaps += MeanDistance(exchanged, b) < absolute - 1e-9 && (exchanged - a).norm() > 0;
    r.per_frame_mm.push_back(absolute);
  }
  r.distances_mm.resize(static_cast<int>(rows.size()), static_cast<int>(joints.size()));
  for (size_t f = 0; f < rows.size(); ++f) r.distances_mm.row(f) = rows[f].transpose();
  const int seen = r.frames - static_cast<int>(std::count_if(r.per_frame_mm.begin(), r.per_frame_mm.end(),
                                                               [](double x) { return std::isnan(x); }));
  if (seen > 0) {
    r.absolute_mm /= seen;
    r.root_relative_mm /= seen;
    r.procrustes_mm /= seen;
    for (double& x : r.per_joint_mm) x /= seen;
    r.swap_rate = static_cast<double>(swaps) / seen;
  }
  if (r.frames > 0) r.failure_rate = static_cast<double>(failed) / r.frames;
  return r;
}

}  // namespace jgpm
