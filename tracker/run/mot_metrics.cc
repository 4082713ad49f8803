#include "tracker/run/mot_metrics.h"

#include <algorithm>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>

#include "tracker/filter/assignment.h"

namespace jgpm {
namespace {

void CheckList(const std::vector<MotPoint>& points) {
  std::set<int> ids;
  for (const MotPoint& p : points) {
    if (!ids.insert(p.id).second) throw std::invalid_argument("ClearMot: id " + std::to_string(p.id) + " given twice in a frame");
    if (!p.floor_mm.allFinite()) throw std::invalid_argument("ClearMot: a point is not finite");
  }
}

}  // namespace

MotResult ClearMot(const std::vector<MotFrame>& frames, double match_mm) {
  MotResult r;
  r.frames = static_cast<int>(frames.size());
  std::map<int, int> kept;       // true id -> tracked id paired in the frame before
  std::map<int, int> last;       // true id -> tracked id it was last paired with
  std::map<int, bool> was_paired;   // true id -> paired when it was last present
  std::map<int, bool> gap;          // true id -> unpaired since its last pairing
  std::set<int> tracks;
  double distance_sum = 0;
  for (int t = 0; t < r.frames; ++t) {
    const MotFrame& f = frames[t];
    CheckList(f.truth);
    CheckList(f.tracked);
    const int n = static_cast<int>(f.truth.size()), m = static_cast<int>(f.tracked.size());
    r.truth += n;
    Eigen::MatrixXd distance(n, m);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < m; ++j) distance(i, j) = (f.truth[i].floor_mm - f.tracked[j].floor_mm).norm();
    std::vector<int> pair(n, -1);
    std::vector<bool> taken(m, false);
    // 1. The frame before's correspondences that still hold.
    for (int i = 0; i < n; ++i) {
      const auto before = kept.find(f.truth[i].id);
      if (before == kept.end()) continue;
      for (int j = 0; j < m; ++j) {
        if (f.tracked[j].id == before->second && distance(i, j) <= match_mm) {
          pair[i] = j;
          taken[j] = true;
        }
      }
    }
    // 2. The others at least total distance (out-of-reach pairs cost more than any pair in
    //    reach, so they never displace one).
    std::vector<int> rows, columns;
    for (int i = 0; i < n; ++i) if (pair[i] < 0) rows.push_back(i);
    for (int j = 0; j < m; ++j) if (!taken[j]) columns.push_back(j);
    Eigen::MatrixXd cost(rows.size(), columns.size());
    const double beyond = match_mm * (1 + static_cast<double>(n + m));
    for (size_t a = 0; a < rows.size(); ++a)
      for (size_t b = 0; b < columns.size(); ++b) cost(a, b) = std::min(distance(rows[a], columns[b]), beyond);
    const std::vector<int> chosen = MinCostAssignment(cost, match_mm);
    for (size_t a = 0; a < rows.size(); ++a) {
      if (chosen[a] < 0) continue;
      const int i = rows[a], j = columns[chosen[a]];
      pair[i] = j;
      const auto previous = last.find(f.truth[i].id);
      if (previous != last.end() && previous->second != f.tracked[j].id) ++r.id_switches;
    }
    // 3. Count.
    kept.clear();
    int paired_now = 0;
    for (int i = 0; i < n; ++i) {
      const int id = f.truth[i].id;
      tracks.insert(id);
      if (pair[i] < 0) {
        ++r.misses;
        if (was_paired.count(id) && was_paired[id]) gap[id] = true;
        was_paired[id] = false;
        continue;
      }
      const int j = pair[i];
      ++paired_now;
      if (gap[id]) ++r.fragmentations;
      gap[id] = false;
      was_paired[id] = true;
      kept[id] = last[id] = f.tracked[j].id;
      distance_sum += distance(i, j);
      r.paired.push_back({t, id, f.tracked[j].id, distance(i, j)});
    }
    r.false_positives += m - paired_now;
    r.pairs += paired_now;
  }
  r.truth_tracks = static_cast<int>(tracks.size());
  r.motp_mm = r.pairs > 0 ? distance_sum / r.pairs : 0;
  const int errors = r.misses + r.false_positives + r.id_switches;
  r.mota = r.truth > 0 ? 1.0 - static_cast<double>(errors) / r.truth : (errors == 0 ? 1.0 : -errors);
  return r;
}

bool JointsHalfInView(const std::vector<Camera>& cameras, const Eigen::Matrix3Xd& joints) {
  for (const Camera& camera : cameras) {
    int inside = 0;
    for (int j = 0; j < joints.cols(); ++j) {
      Eigen::Vector2d p;
      inside += camera.Project(joints.col(j), &p) && p.x() >= 0 && p.y() >= 0 && p.x() < camera.width &&
                p.y() < camera.height;
    }
    if (2 * inside >= joints.cols() && joints.cols() > 0) return true;
  }
  return false;
}

std::vector<std::vector<MotPoint>> TruePeople(const ClipGroundTruth& truth, int frames) {
  const std::vector<Camera>& cameras = truth.render_cameras.empty() ? truth.cameras : truth.render_cameras;
  frames = std::min<int>(frames, truth.frames.size());
  std::vector<std::vector<MotPoint>> people(frames);
  const auto add = [&](int id, int k, const Eigen::Matrix3Xd& joints) {
    if (k < frames && JointsHalfInView(cameras, joints)) people[k].push_back({id, Eigen::Vector2d(joints(0, 0), joints(2, 0))});
  };
  if (truth.people.empty()) {
    for (int k = 0; k < frames; ++k) add(1, k, truth.frames[k].joints_mm);
  } else {
    for (const ClipPerson& p : truth.people)
      for (const ClipPersonFrame& f : p.frames) add(p.id, f.frame, f.joints_mm);
  }
  return people;
}

}  // namespace jgpm
