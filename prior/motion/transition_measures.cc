#include "prior/motion/transition_measures.h"

#include <cmath>
#include <string>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>

#include "io/base/error.h"
#include "io/gait/gait_pose.h"
#include "io/mocap/kinematics.h"

namespace jgpm {
namespace {

struct Track {
  std::vector<Eigen::Matrix3Xd> joints;                 // every bone end, mm
  std::vector<std::vector<Eigen::Quaterniond>> rotations;  // every bone's world rotation
};

Track Compute(const Kinematics& kinematics, const RowMatrixXd& frames) {
  Track track;
  std::vector<Eigen::Matrix3d> rotations;
  for (Eigen::Index f = 0; f < frames.rows(); ++f) {
    Eigen::Matrix3Xd joints;
    kinematics.Compute(frames.row(f).data(), &joints, &rotations);
    track.joints.push_back(joints);
    std::vector<Eigen::Quaterniond> q;
    for (size_t b = 0; b < rotations.size(); ++b) {
      q.emplace_back(rotations[b]);
      // q and -q are one rotation: keep each bone's sequence in one hemisphere, as a
      // spectrum over time would otherwise see the sign flips.
      if (!track.rotations.empty() && q.back().dot(track.rotations.back()[b]) < 0) q.back().coeffs() *= -1;
    }
    track.rotations.push_back(q);
  }
  return track;
}

// Power spectrum (one-sided, bins 0 .. n/2) of a real sequence, normalised to sum 1; its
// total power before normalising in `power`.
std::vector<double> Spectrum(const std::vector<double>& values, double* power) {
  cv::Mat in(1, static_cast<int>(values.size()), CV_64F, const_cast<double*>(values.data())), out;
  cv::dft(in, out, cv::DFT_COMPLEX_OUTPUT);
  std::vector<double> spectrum(values.size() / 2 + 1);
  *power = 0;
  for (size_t k = 0; k < spectrum.size(); ++k) {
    const cv::Vec2d c = out.at<cv::Vec2d>(0, static_cast<int>(k));
    spectrum[k] = c[0] * c[0] + c[1] * c[1];
    *power += spectrum[k];
  }
  if (*power > 0) for (double& s : spectrum) s /= *power;
  return spectrum;
}

}  // namespace

TransitionMeasures MeasureTransition(const Skeleton& skeleton, const RowMatrixXd& truth, const RowMatrixXd& estimate,
                                     const TransitionWindow& window) {
  const int n = window.frames, first = window.first;
  if (truth.rows() != estimate.rows() || truth.cols() != skeleton.NumChannels() ||
      estimate.cols() != skeleton.NumChannels()) {
    ThrowInputError("transition measures", "the truth (" + std::to_string(truth.rows()) + " x " +
                                               std::to_string(truth.cols()) + ") and the estimate (" +
                                               std::to_string(estimate.rows()) + " x " +
                                               std::to_string(estimate.cols()) + ") must be frames of the skeleton's " +
                                               std::to_string(skeleton.NumChannels()) + " channels, as many");
  }
  if (n < 1 || first < 2 || first + n + 2 > truth.rows()) {
    ThrowInputError("transition measures", "the window of " + std::to_string(n) + " frames from frame " +
                                               std::to_string(first) + " needs 2 frames before and after it in " +
                                               std::to_string(truth.rows()) + " frames");
  }
  if (!(window.frames_per_second > 0)) ThrowInputError("transition measures", "frames_per_second must be > 0");
  if (!truth.allFinite() || !estimate.allFinite()) ThrowInputError("transition measures", "a frame is not finite");
  const GaitPoseLayout layout(skeleton, "transition measures");
  const std::vector<int>& measured = layout.measured_columns();
  const std::vector<int> feet = skeleton.FootBones();
  const Kinematics kinematics(skeleton);
  const Track t = Compute(kinematics, truth), e = Compute(kinematics, estimate);
  const double fps = window.frames_per_second;

  TransitionMeasures m;
  double skate = 0, true_skate = 0;
  int contacts = 0, true_contacts = 0;
  for (int f = first; f < first + n; ++f) {
    double world = 0, aligned = 0, l2p = 0, l2q = 0;
    for (int c : measured) {
      const Eigen::Vector3d d = e.joints[f].col(c) - t.joints[f].col(c);
      world += d.norm() / measured.size();
      aligned += (d - (e.joints[f].col(0) - t.joints[f].col(0))).norm() / measured.size();
      l2p += d.squaredNorm();
    }
    for (size_t b = 0; b < t.rotations[f].size(); ++b) {
      const Eigen::Quaterniond& qt = t.rotations[f][b];
      Eigen::Quaterniond qe = e.rotations[f][b];
      if (qe.dot(qt) < 0) qe.coeffs() = -qe.coeffs();
      l2q += (qe.coeffs() - qt.coeffs()).squaredNorm();
    }
    m.eq23_mm.push_back(world);
    m.eq23_root_aligned_mm.push_back(aligned);
    m.eq23_mean_mm += world / n;
    m.eq23_root_aligned_mean_mm += aligned / n;
    m.l2p_m += std::sqrt(l2p) / 1000 / n;
    m.l2q += std::sqrt(l2q) / n;
    // Foot skating: horizontal speed by the central difference, on the floor at f.
    for (int foot : feet) {
      for (const Track* track : {&t, &e}) {
        const Eigen::Vector3d p = track->joints[f].col(foot);
        if (p.y() - window.floor_mm > window.contact_mm) continue;
        Eigen::Vector3d v = (track->joints[f + 1].col(foot) - track->joints[f - 1].col(foot)) * fps / 2 / 1000;
        v.y() = 0;
        if (track == &t) true_skate += v.norm(), ++true_contacts;
        else skate += v.norm(), ++contacts;
      }
    }
  }
  if (contacts) m.foot_skate_mps = skate / contacts;
  if (true_contacts) m.true_foot_skate_mps = true_skate / true_contacts;

  // Seams at A's last frame and the transition's last frame.
  const std::array<int, 2> seams = {first - 1, first + n - 1};
  for (int s = 0; s < 2; ++s) {
    for (const Track* track : {&t, &e}) {
      double jump = 0;
      const int at = seams[s];
      for (int c : measured) {
        jump += (track->joints[at + 1].col(c) - 2 * track->joints[at].col(c) + track->joints[at - 1].col(c)).norm() *
                fps / 1000 / measured.size();
      }
      (track == &t ? m.true_seam_jump_mps : m.seam_jump_mps)[s] = jump;
    }
  }

  // NPSS over every bone's quaternion components along the transition.
  double weighted = 0, weights = 0;
  for (size_t b = 0; b < t.rotations[first].size(); ++b) {
    for (int k = 0; k < 4; ++k) {
      std::vector<double> a(n), z(n);
      for (int f = first; f < first + n; ++f) {
        const Eigen::Quaterniond& qt = t.rotations[f][b];
        Eigen::Quaterniond qe = e.rotations[f][b];
        if (qe.dot(qt) < 0) qe.coeffs() = -qe.coeffs();
        a[f - first] = qt.coeffs()(k);
        z[f - first] = qe.coeffs()(k);
      }
      double power_true, power_estimate;
      const std::vector<double> p = Spectrum(a, &power_true), q = Spectrum(z, &power_estimate);
      if (!(power_true > 0) || !(power_estimate > 0)) continue;
      double emd = 0, cp = 0, cq = 0;
      for (size_t i = 0; i < p.size(); ++i) cp += p[i], cq += q[i], emd += std::abs(cp - cq);
      weighted += power_true * emd;
      weights += power_true;
    }
  }
  if (weights > 0) m.npss = weighted / weights;
  return m;
}

}  // namespace jgpm
