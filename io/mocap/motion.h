// Motion of an Acclaim skeleton: one row of dof values per frame (the content of an AMC
// file, also what BVH files convert to).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace jgpm {

using RowMatrixXd = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct Motion {
  // frames x Skeleton::NumChannels(); columns follow Skeleton::ChannelOffsets(). Rotations
  // in degrees, root translation in skeleton length units.
  RowMatrixXd values;
  // Number of the first frame in the AMC file (CMU files count from 1).
  int first_frame_number = 1;
  // AMC files do not store a rate; CMU captured these trials at 120 frames per second.
  double frames_per_second = 120.0;
  // Order in which the AMC file lists bones in each frame (skeleton bone indices), kept
  // so that writing reproduces the file. Empty means skeleton order.
  std::vector<int> bone_order;
  // '#' comment lines before the AMC keywords, kept for writing.
  std::vector<std::string> header_comments;

  int NumFrames() const { return static_cast<int>(values.rows()); }
  const double* Frame(int frame) const { return values.row(frame).data(); }
};

}  // namespace jgpm
