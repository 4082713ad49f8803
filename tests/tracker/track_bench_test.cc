// The benchmark's tables: one line per row (track.csv), per row and joint (joints.csv) and
// per row and frame (frames.csv), with the values given, in the order given.
#include "tracker/track_bench.h"

#include <cmath>

#include <gtest/gtest.h>

namespace jgpm {
namespace {

TEST(TrackBench, TablesHoldEveryRowJointAndFrame) {
  TrackBenchRow a;
  a.clip = "c1", a.model = "m", a.method = "prior", a.cameras = 4, a.frames = 3, a.seeds = 2;
  a.bt14_mm = 12.345, a.fps = 30.5, a.evaluations_per_frame = 930;
  a.joints = {"lfemur", "rfemur"};
  a.per_joint_mm = {10.004, 20.5};
  a.per_frame_mm = {1, std::nan(""), 3.25};
  TrackBenchRow b = a;
  b.method = "joint-space", b.floor_g17_root_mm = -1;
  const std::string track = TrackBenchCsv({a, b});
  EXPECT_EQ(std::count(track.begin(), track.end(), '\n'), 3);
  EXPECT_NE(track.find("\nc1,m,prior,4,3,2,12.35,"), std::string::npos) << track;
  EXPECT_NE(track.find("\nc1,m,joint-space,4,3,2,"), std::string::npos) << track;
  EXPECT_EQ(TrackBenchJointsCsv({a}),
            "clip,model,method,joint,mm\nc1,m,prior,lfemur,10.00\nc1,m,prior,rfemur,20.50\n");
  EXPECT_EQ(TrackBenchFramesCsv({a}),
            "clip,model,method,frame,mm\nc1,m,prior,0,1.00\nc1,m,prior,1,nan\nc1,m,prior,2,3.25\n");
}

}  // namespace
}  // namespace jgpm
