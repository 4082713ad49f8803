#include "io/mocap/motion_file.h"

#include <algorithm>
#include <cctype>
#include <cstdio>

#include "io/base/error.h"
#include "io/base/text_reader.h"
#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/bvh.h"
#include "io/mocap/bvh_conversion.h"
#include "io/mocap/kinematics.h"

namespace jgpm {
namespace fs = std::filesystem;
namespace {

std::string Printf(const char* format, auto... args) {
  const int size = std::snprintf(nullptr, 0, format, args...);
  std::string text(static_cast<size_t>(size) + 1, '\0');
  std::snprintf(text.data(), text.size(), format, args...);
  text.pop_back();
  return text;
}

// Horizontal distance the root travels over the motion, metres.
double RootTravelMetres(const std::vector<Eigen::Matrix3Xd>& joints, int root_column) {
  double travel = 0;
  for (size_t f = 1; f < joints.size(); ++f) {
    const Eigen::Vector3d step = joints[f].col(root_column) - joints[f - 1].col(root_column);
    travel += std::hypot(step.x(), step.z());
  }
  return travel / 1000.0;
}

std::string DescribeSkeleton(const Skeleton& skeleton) {
  std::string out = Printf("ASF skeleton '%s': %zu bones (root included), %d channels per frame\n",
                           skeleton.name.c_str(), skeleton.bones.size(), skeleton.NumChannels());
  out += Printf("units: length %g (1 unit = %.4f mm), angles in degrees; root order",
                skeleton.length_scale, skeleton.MillimetresPerUnit());
  for (Dof dof : skeleton.bones[0].dofs) out += " " + std::string(DofName(dof));
  out += ", axis " + AxisOrderName(skeleton.bones[0].axis_order) + "\n";
  out += Printf("%-12s %-12s %10s  %s\n", "bone", "parent", "length_mm", "dofs");
  for (const Bone& bone : skeleton.bones) {
    std::string dofs;
    for (Dof dof : bone.dofs) dofs += std::string(DofName(dof)) + " ";
    out += Printf("%-12s %-12s %10.1f  %s\n", bone.name.c_str(),
                  bone.parent < 0 ? "-" : skeleton.bones[bone.parent].name.c_str(),
                  bone.length * skeleton.MillimetresPerUnit(), dofs.empty() ? "-" : dofs.c_str());
  }
  return out;
}

}  // namespace

MotionFormat FormatFromPath(const fs::path& path, const std::string& what) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (extension == ".asf") return MotionFormat::kAsf;
  if (extension == ".amc") return MotionFormat::kAmc;
  if (extension == ".bvh") return MotionFormat::kBvh;
  ThrowInputError(what, "expected a .asf, .amc or .bvh file, found " + path.string());
}

fs::path SkeletonForAmc(const fs::path& amc, const MotionFileOptions& options) {
  if (options.asf) return *options.asf;
  CheckInputFile(amc, "an AMC motion");
  std::error_code ec;
  const std::string stem = amc.stem().string();
  fs::path same_stem = amc;
  same_stem.replace_extension(".asf");  // how jgpm writes motions (jgpm synth)
  if (fs::is_regular_file(same_stem, ec)) return same_stem;
  const fs::path sibling = amc.parent_path() / (stem.substr(0, stem.find('_')) + ".asf");
  if (stem.find('_') != std::string::npos && fs::is_regular_file(sibling, ec)) return sibling;
  ThrowInputError(amc.string(), "needs its skeleton: pass --asf SKEL.asf (no " + same_stem.string() +
                                    (stem.find('_') != std::string::npos ? " or " + sibling.string() : std::string()) +
                                    " next to it)");
}

std::string DescribeMotionFile(const fs::path& path, const MotionFileOptions& options) {
  CheckInputFile(path, "an ASF, AMC or BVH file");
  switch (FormatFromPath(path, path.string())) {
    case MotionFormat::kAsf:
      return DescribeSkeleton(ReadAsf(path));
    case MotionFormat::kAmc: {
      const fs::path asf = SkeletonForAmc(path, options);
      const Skeleton skeleton = ReadAsf(asf);
      Motion motion = ReadAmc(path, skeleton);
      motion.frames_per_second = options.amc_frames_per_second;
      const auto joints = ComputeJointPositions(skeleton, motion);
      return Printf(
          "AMC motion %s (skeleton %s)\nframes %d (numbered %d-%d), %.1f fps (assumed: AMC "
          "stores no rate), %.2f s\njoints %zu (root included), channels %d\nroot travels "
          "%.2f m horizontally\n",
          path.string().c_str(), asf.string().c_str(), motion.NumFrames(),
          motion.first_frame_number, motion.first_frame_number + motion.NumFrames() - 1,
          motion.frames_per_second, motion.NumFrames() / motion.frames_per_second,
          skeleton.bones.size(), skeleton.NumChannels(), RootTravelMetres(joints, 0));
    }
    case MotionFormat::kBvh: {
      const Bvh bvh = ReadBvh(path, options.bvh_mm_per_unit);
      int end_sites = 0;
      for (const BvhJoint& joint : bvh.joints) end_sites += joint.end_site ? 1 : 0;
      std::vector<Eigen::Matrix3Xd> joints(bvh.frames.rows());
      for (int f = 0; f < bvh.frames.rows(); ++f) ComputeBvhPose(bvh, f, &joints[f]);
      return Printf(
          "BVH motion %s\nframes %d, %.3f fps (frame time %g s), %.2f s\njoints %zu (+ %d end "
          "sites), channels %d\nroot travels %.2f m horizontally (assuming %g mm per unit)\n",
          path.string().c_str(), static_cast<int>(bvh.frames.rows()), 1.0 / bvh.frame_time,
          bvh.frame_time, bvh.frames.rows() * bvh.frame_time, bvh.joints.size() - end_sites,
          end_sites, bvh.NumChannels(), RootTravelMetres(joints, 0), bvh.mm_per_unit);
    }
  }
  return {};
}

std::string ConvertMotionFile(const fs::path& in, const fs::path& out,
                              const MotionFileOptions& options) {
  CheckInputFile(in, "an AMC or BVH motion");
  const MotionFormat in_format = FormatFromPath(in, in.string());
  const MotionFormat out_format = FormatFromPath(out, "--out");
  if (in_format == MotionFormat::kAsf) {
    ThrowInputError(in.string(), "is a skeleton; convert its motion (.amc) instead");
  }
  if (out_format == MotionFormat::kAsf) ThrowInputError("--out", "expected a .amc or .bvh file");
  std::error_code ec;
  if (fs::exists(out, ec) && fs::equivalent(in, out, ec)) {
    ThrowInputError("--out", "is the input file; choose another output name");
  }

  Skeleton skeleton;
  fs::path asf;
  if (in_format == MotionFormat::kAmc || out_format == MotionFormat::kAmc) {
    if (in_format == MotionFormat::kBvh && !options.asf) {
      ThrowInputError("--asf", "needed to write AMC: the skeleton the motion is for");
    }
    asf = in_format == MotionFormat::kAmc ? SkeletonForAmc(in, options) : *options.asf;
    skeleton = ReadAsf(asf);
  }
  Motion motion;
  Bvh bvh;
  if (in_format == MotionFormat::kAmc) {
    motion = ReadAmc(in, skeleton);
    motion.frames_per_second = options.amc_frames_per_second;
    if (out_format == MotionFormat::kBvh) bvh = AcclaimToBvh(skeleton, motion, options.bvh_mm_per_unit);
  } else {
    bvh = ReadBvh(in, options.bvh_mm_per_unit);
    if (out_format == MotionFormat::kAmc) motion = BvhToAcclaim(bvh, skeleton, in.string());
  }
  if (out_format == MotionFormat::kAmc) {
    WriteAmc(out, motion, skeleton);
    return Printf("wrote %s: %d frames, %d channels (skeleton %s)", out.string().c_str(),
                  motion.NumFrames(), skeleton.NumChannels(), asf.string().c_str());
  }
  WriteBvh(out, bvh);
  int end_sites = 0;
  for (const BvhJoint& joint : bvh.joints) end_sites += joint.end_site ? 1 : 0;
  return Printf("wrote %s: %d frames at %.3f fps, %zu joints + %d end sites, %d channels, %g mm "
                "per unit", out.string().c_str(), static_cast<int>(bvh.frames.rows()),
                1.0 / bvh.frame_time, bvh.joints.size() - end_sites, end_sites, bvh.NumChannels(),
                bvh.mm_per_unit);
}

}  // namespace jgpm
