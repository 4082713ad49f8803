#include "prior/motion/synthesis.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "io/base/enum_name.h"
#include "io/base/error.h"
#include "io/base/output_batch.h"
#include "io/base/png_file.h"
#include "io/base/text_reader.h"
#include "io/gait/gait_pose.h"
#include "io/mocap/amc.h"
#include "io/mocap/bvh.h"
#include "io/mocap/bvh_conversion.h"
#include "io/mocap/kinematics.h"

namespace jgpm {
namespace {

// The ML-JGPM layer scales, for single-layer models (see the header).
constexpr double kInnerScale = 0.4, kOuterScale = 1.25;

}  // namespace

std::string_view SynthesisPathName(SynthesisPath path) {
  switch (path) {
    case SynthesisPath::kLine: return "line";
    case SynthesisPath::kOuterSpiral: return "outer-spiral";
    case SynthesisPath::kInnerSpiral: return "inner-spiral";
  }
  return "?";
}

bool ParseSynthesisPath(std::string_view name, SynthesisPath* path) {
  return ParseByName(name, {SynthesisPath::kLine, SynthesisPath::kOuterSpiral, SynthesisPath::kInnerSpiral},
                     SynthesisPathName, path);
}

bool SynthesisOptions::Check(std::string* why) const {
  const char* problem = nullptr;
  if (frames < 2) problem = "frames must be >= 2";
  else if (!(frames_per_second > 0)) problem = "frames per second must be > 0";
  else if (!std::isfinite(phase) || !std::isfinite(gait)) problem = "phase and gait must be finite";
  else if (!(cycles > 0) || !std::isfinite(cycles)) problem = "cycles must be > 0";
  else if (!std::isfinite(gait_span)) problem = "gait span must be finite";
  if (problem && why) *why = problem;  // `why` may be null, as for every other Check
  return problem == nullptr;
}

SynthesisResult Synthesise(const GaitModel& model, SynthesisPath path, const SynthesisOptions& o) {
  if (!model.HasManifold()) {
    ThrowInputError(std::string(ModelKindName(model.kind())) + " model",
                    "synthesis walks the manifold coordinates of jgpm, mljgpm-torus or mljgpm-cyl; this model has none");
  }
  std::string why;
  if (!o.Check(&why)) ThrowInputError("synthesis options", why);
  const std::vector<double>& scales = model.data().set.layer_scales;
  const double low = *std::min_element(scales.begin(), scales.end());
  const double high = *std::max_element(scales.begin(), scales.end());
  const bool one_layer = scales.size() == 1;
  const Eigen::Vector3d centre = model.latent().colwise().mean().transpose();
  // One layer: the manifold at its only scale, pushed out from or pulled in to the centre.
  auto at = [&](double phase, double gait, double scale) -> Eigen::Vector3d {
    if (!one_layer) return model.ManifoldToLatent({phase, gait, scale});
    return centre + scale * (model.ManifoldToLatent({phase, gait, scales[0]}) - centre);
  };
  const double inner = one_layer ? kInnerScale : low, outer = one_layer ? kOuterScale : high;

  SynthesisResult result;
  result.latent.resize(o.frames, 3);
  for (int t = 0; t < o.frames; ++t) {
    const double u = static_cast<double>(t) / (o.frames - 1);
    if (path == SynthesisPath::kLine) {
      result.latent.row(t) = ((1 - u) * at(o.phase, o.gait, inner) + u * at(o.phase, o.gait, outer)).transpose();
    } else {
      const double scale = path == SynthesisPath::kOuterSpiral ? outer : inner;
      // u runs to 1 inclusive, so the phase ends where it began after whole cycles.
      result.latent.row(t) = at(o.cycles * u, o.gait + o.gait_span * u, scale).transpose();
    }
  }
  result.poses_deg = model.MeanPoses(result.latent);
  return result;
}

Motion PosesToMotion(const GaitModel& model, const Eigen::MatrixXd& poses_deg, double frames_per_second) {
  const Skeleton& skeleton = model.skeleton();
  const GaitPoseLayout layout(skeleton, "reference skeleton");
  JGPM_CHECK(poses_deg.cols() == layout.NumChannels());
  Motion motion;
  motion.frames_per_second = frames_per_second;
  motion.values = RowMatrixXd::Zero(poses_deg.rows(), skeleton.NumChannels());
  const Kinematics kinematics(skeleton);
  double lowest = std::numeric_limits<double>::infinity();
  for (int t = 0; t < poses_deg.rows(); ++t) {
    const Eigen::VectorXd pose = poses_deg.row(t).transpose();
    layout.ToFrame(pose.data(), motion.values.row(t).data());
    lowest = std::min(lowest, kinematics.Compute(motion.Frame(t)).row(1).minCoeff());
  }
  const std::vector<std::string> names = skeleton.ChannelNames();
  const auto ty = std::find(names.begin(), names.end(), "root.ty");
  if (ty != names.end()) motion.values.col(ty - names.begin()).array() -= lowest / skeleton.MillimetresPerUnit();
  return motion;
}

std::vector<std::filesystem::path> WriteSynthesis(const Skeleton& skeleton, const std::string& asf_text,
                                                  const Motion& motion, const std::filesystem::path& out,
                                                  const std::filesystem::path& png) {
  const std::string extension = out.extension().string();
  OutputBatch batch;
  if (extension == ".amc") {
    batch.Add(out, FormatAmc(motion, skeleton));
    std::filesystem::path asf = out;
    asf.replace_extension(".asf");
    batch.Add(asf, asf_text);
  } else if (extension == ".bvh") {
    batch.Add(out, FormatBvh(AcclaimToBvh(skeleton, motion)));
  } else {
    ThrowInputError(out.string(), "expected a .amc or .bvh file name");
  }
  if (!png.empty()) batch.Add(png, EncodePng(StickFigures(skeleton, motion), png.string()));
  return batch.Commit();
}

cv::Mat StickFigures(const Skeleton& skeleton, const Motion& motion, int figures) {
  const Kinematics kinematics(skeleton);
  figures = std::max(1, std::min(figures, motion.NumFrames()));
  const int cell = 150, height = 260;
  cv::Mat image(height + 30, cell * figures, CV_8UC3, cv::Scalar(255, 255, 255));
  // Side view: forward (+z) to the right, up (+y) up; one scale for all figures.
  std::vector<int> frames;
  std::vector<Eigen::Matrix3Xd> poses;
  double top = 1;
  for (int f = 0; f < figures; ++f) {
    frames.push_back(figures == 1 ? 0 : f * (motion.NumFrames() - 1) / (figures - 1));
    poses.push_back(kinematics.Compute(motion.Frame(frames.back())));
    top = std::max(top, poses.back().row(1).maxCoeff());
  }
  const double pixels_per_mm = (height - 20) / top;
  for (int f = 0; f < figures; ++f) {
    const Eigen::Matrix3Xd& p = poses[f];
    const double centre_z = p(2, 0);
    auto to_image = [&](int column) {
      return cv::Point2d(f * cell + cell / 2.0 + pixels_per_mm * (p(2, column) - centre_z),
                         height - pixels_per_mm * p(1, column));
    };
    cv::line(image, {f * cell + 5, height}, {(f + 1) * cell - 5, height}, {180, 180, 180});
    for (size_t b = 1; b < skeleton.bones.size(); ++b) {
      const std::string& name = skeleton.bones[b].name;
      // Left side blue, right side red, the trunk black (BGR).
      const cv::Scalar colour = name[0] == 'l' && name != "lowerback" && name != "lowerneck" ? cv::Scalar(200, 90, 30)
                                : name[0] == 'r'                                              ? cv::Scalar(40, 40, 200)
                                                                                              : cv::Scalar(30, 30, 30);
      cv::line(image, to_image(skeleton.bones[b].parent), to_image(static_cast<int>(b)), colour, 2, cv::LINE_AA);
    }
    cv::putText(image, std::to_string(frames[f]), {f * cell + 5, height + 22}, cv::FONT_HERSHEY_SIMPLEX, 0.45, {0, 0, 0}, 1,
                cv::LINE_AA);
  }
  return image;
}

}  // namespace jgpm
