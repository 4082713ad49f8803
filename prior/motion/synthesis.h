// Motion synthesis by walking through a JGPM-family latent space (paper section VI-D,
// Fig. 14), and the files people look at: AMC (with its ASF) or BVH, and a PNG strip of
// stick figures.
//
// Paths, in manifold coordinates (pose phase, gait position, stride scale):
//   line          a straight latent segment at one pose phase and gait, from the innermost
//                 layer (smallest stride) to the outermost: the same pose, growing stride;
//   outer-spiral  the pose phase goes round `cycles` times while the gait position
//                 advances by `gait_span`, on the outermost layer: a spiral round the
//                 torus or cylinder, walking with the largest strides;
//   inner-spiral  the same on the innermost layer: the smallest strides.
// A single-layer model (jgpm) has one stride scale; its paths are scaled about the latent
// centre by the ML-JGPM layer scales (0.4 .. 1.25), i.e. they leave the learned manifold,
// as the paper's comparison does.
#pragma once

#include <filesystem>
#include <string_view>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "io/mocap/motion.h"
#include "prior/model/gait_model.h"

namespace jgpm {

enum class SynthesisPath { kLine, kOuterSpiral, kInnerSpiral };
std::string_view SynthesisPathName(SynthesisPath path);  // "line", "outer-spiral", "inner-spiral"
bool ParseSynthesisPath(std::string_view name, SynthesisPath* path);

struct SynthesisOptions {
  int frames = 120;
  double frames_per_second = 30;
  double phase = 0.25;     // line: the pose phase held
  double gait = 0;         // line: the gait position; spirals: where they start
  double cycles = 2;       // spirals: walking cycles
  double gait_span = 2;    // spirals: gait positions travelled
  bool Check(std::string* why) const;
};

struct SynthesisResult {
  Eigen::MatrixXd latent;     // frames x 3
  Eigen::MatrixXd poses_deg;  // frames x D, the mean poses
};

// InputError if the model has no manifold coordinates (only the JGPM family has them) or
// the options are bad.
SynthesisResult Synthesise(const GaitModel& model, SynthesisPath path, const SynthesisOptions& options = {});

// Gait poses as a motion of the model's reference skeleton, in place (the poses carry no
// root translation), with the root raised so the lowest foot of the whole motion touches
// the floor (y = 0).
Motion PosesToMotion(const GaitModel& model, const Eigen::MatrixXd& poses_deg, double frames_per_second);

// A strip of `figures` stick figures seen from the side (walking to the right), evenly
// spaced over the motion.
cv::Mat StickFigures(const Skeleton& skeleton, const Motion& motion, int figures = 12);

// Writes OUT.amc with OUT.asf beside it (`asf_text`, the skeleton's file), or OUT.bvh; the
// format follows the extension; with `png`, also StickFigures there. All the files or
// none. Returns the files written. InputError for another extension or a file not writable.
std::vector<std::filesystem::path> WriteSynthesis(const Skeleton& skeleton, const std::string& asf_text,
                                                  const Motion& motion, const std::filesystem::path& out,
                                                  const std::filesystem::path& png = {});

}  // namespace jgpm
