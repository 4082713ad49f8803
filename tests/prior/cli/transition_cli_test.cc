// `jgpm transition` end to end on a real trial (131_05: a start, a duck under something,
// a stop): A and B are the trial's own frames every 4th (120 -> 30 fps), read back from
// the written AMC exactly; the transition between them has N frames, SLERP's ends meet A
// and B; LSOPA's joints lie between A's end and B's start; every bad request is refused
// on one line with nothing written.
#include <cstdio>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>

#include <gtest/gtest.h>

#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/kinematics.h"
#include "prior/motion/transition_event.h"
#include "test_support.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

std::string Trial() { return (test::CmuRoot() / "subjects/131/131_05.amc").string(); }
Skeleton Skeleton131() { return ReadAsf(test::CmuRoot() / "subjects/131/131.asf"); }


TEST(TransitionCli, JoinsTwoRangesOfATrial) {
  const test::TempDir dir;
  const Skeleton skeleton = Skeleton131();
  const Motion trial = ReadAmc(Trial(), skeleton);
  const Kinematics kinematics(skeleton);
  for (const char* method : {"lsopa", "lsopa-rt", "li", "ri", "slerp", "hold"}) {
    const fs::path out = dir.path() / (std::string(method) + ".amc");
    const test::CommandResult r = test::RunJgpm("transition --from " + Trial() + ":500-740 --to " + Trial() +
                                                ":804-1000 --frames 15 --method " + method + " --out " +
                                                out.string() + " --png " + (dir.path() / "strip.png").string());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("A 61, transition 15 (from frame 61), B 50"), std::string::npos) << r.out;
    const Motion m = ReadAmc(out, ReadAsf(dir.path() / (std::string(method) + ".asf")));
    ASSERT_EQ(m.NumFrames(), 61 + 15 + 50);
    // A: frames 500 + 4k ending on 740; B: 804 + 4k (file numbers count from 1).
    for (int k = 0; k < 61; ++k) {
      EXPECT_LT((m.values.row(k) - trial.values.row(500 - 1 + 4 * k)).cwiseAbs().maxCoeff(), 1e-5) << k;
    }
    for (int k = 0; k < 50; ++k) {
      EXPECT_LT((m.values.row(76 + k) - trial.values.row(804 - 1 + 4 * k)).cwiseAbs().maxCoeff(), 1e-5) << k;
    }
    if (std::string(method) == "hold") {  // A's last frame, root included, N times
      for (int i = 1; i <= 15; ++i) EXPECT_EQ(m.values.row(60 + i), m.values.row(60)) << i;
      continue;
    }
    if (std::string(method) == "lsopa-rt") {
      EXPECT_NE(r.out.find("retraining on [A; transition; B] moved"), std::string::npos) << r.out;
    }
    // The transition's root moves from A's last root to B's first, evenly.
    const Eigen::Vector3d start = kinematics.Compute(m.Frame(60)).col(0), end = kinematics.Compute(m.Frame(76)).col(0);
    for (int i = 1; i <= 15; ++i) {
      const Eigen::Vector3d root = kinematics.Compute(m.Frame(60 + i)).col(0);
      EXPECT_LT((root - (start + (end - start) * i / 16.0)).norm(), 1e-3) << method << " frame " << i;
    }
    // Every transition joint within the box of A's end and B's start poses, grown by 0.5 m:
    // nothing flies off.
    const Eigen::Matrix3Xd a = kinematics.Compute(m.Frame(60)), b = kinematics.Compute(m.Frame(76));
    const Eigen::Vector3d lo = a.rowwise().minCoeff().cwiseMin(b.rowwise().minCoeff()).array() - 500;
    const Eigen::Vector3d hi = a.rowwise().maxCoeff().cwiseMax(b.rowwise().maxCoeff()).array() + 500;
    for (int i = 1; i <= 15; ++i) {
      const Eigen::Matrix3Xd p = kinematics.Compute(m.Frame(60 + i));
      EXPECT_TRUE(((p.colwise() - lo).array() >= 0).all() && ((p.colwise() - hi).array() <= 0).all())
          << method << " frame " << i;
    }
  }
  EXPECT_TRUE(fs::exists(dir.path() / "strip.png"));
}

// 131_09 turns by about 100 degrees between A's end and B's start. The latent paths must
// turn the body, not tumble it: the root's tilt from upright stays within that of the two
// end frames plus 20 degrees (before the per-motion headings it reached about 90).
TEST(TransitionCli, TurnsWithoutTumbling) {
  const test::TempDir dir;
  const std::string trial = (test::CmuRoot() / "subjects/131/131_09.amc").string();
  const Skeleton skeleton = Skeleton131();
  const Kinematics kinematics(skeleton);
  for (const char* method : {"lsopa", "li"}) {
    const fs::path out = dir.path() / (std::string(method) + ".amc");
    const test::CommandResult r = test::RunJgpm("transition --from " + trial + ":1150-1334 --to " + trial +
                                                ":1398-1578 --frames 15 --method " + method + " --out " + out.string());
    ASSERT_EQ(r.status, 0) << r.err;
    const Motion m = ReadAmc(out, skeleton);
    auto tilt_deg = [&](int frame) {
      Eigen::Matrix3Xd joints;
      std::vector<Eigen::Matrix3d> rotations;
      kinematics.Compute(m.Frame(frame), &joints, &rotations);
      return std::acos(std::clamp((rotations[0] * Eigen::Vector3d::UnitY()).y(), -1.0, 1.0)) * 180 / std::numbers::pi;
    };
    const int first = 47;  // A: frames 1150-1334 every 4th
    const double ends = std::max(tilt_deg(first - 1), tilt_deg(first + 15));
    for (int i = 0; i < 15; ++i) EXPECT_LT(tilt_deg(first + i), ends + 20) << method << " frame " << i;
  }
}

TEST(TransitionCli, RefusesBadRequestsOnOneLine) {
  const test::TempDir dir;
  const fs::path out = dir.path() / "t.amc";
  const std::string small = dir.Write("small.asf", test::SmallAsfText()).string();
  // Motion B on another skeleton, without A's bones: b.amc with b.asf beside it.
  dir.Write("b.asf", test::SmallAsfText());
  std::string frames = ":FULLY-SPECIFIED\n:DEGREES\n";
  for (int f = 1; f <= 40; ++f) {
    frames += std::to_string(f) + "\nroot 0 0 0 0 0 0\nthigh 0 0\nshin 0\nspine 0 0 0\n";
  }
  const std::string other = dir.Write("b.amc", frames).string();
  const std::string cases[][2] = {
      {"--from " + Trial() + ":740-500 --to " + Trial(), "not within"},
      {"--from " + Trial() + ":1-99999 --to " + Trial(), "not within"},
      {"--from " + Trial() + ":500-505 --to " + Trial(), "at least 3"},
      {"--from " + Trial() + " --to " + Trial() + " --method spline", "lsopa, lsopa-rt, li, ri, slerp or hold"},
      {"--from " + Trial() + " --to " + Trial() + " --method oracle", "lsopa, lsopa-rt, li, ri, slerp or hold"},
      {"--from " + Trial() + " --to " + (dir.path() / "none.amc").string(), "none.amc"},
      {"--from " + Trial() + " --to " + Trial() + " --asf " + small, "not in the ASF skeleton"},
      {"--from " + Trial() + " --to " + other, "its skeleton has no channel"},
  };
  for (const auto& [arguments, phrase] : cases) {
    const test::CommandResult r = test::RunJgpm("transition " + arguments + " --out " + out.string());
    EXPECT_NE(r.status, 0) << arguments;
    EXPECT_EQ(test::CountLines(r.err), 1) << arguments << "\n" << r.err;
    EXPECT_NE(r.err.find(phrase), std::string::npos) << arguments << "\n" << r.err;
    EXPECT_FALSE(fs::exists(out)) << arguments;
  }
  const test::CommandResult bad_out =
      test::RunJgpm("transition --from " + Trial() + " --to " + Trial() + " --out " + (dir.path() / "t.fbx").string());
  EXPECT_NE(bad_out.status, 0);
  EXPECT_NE(bad_out.err.find(".amc or .bvh"), std::string::npos) << bad_out.err;
}

// The suite on one event: its frame is the rule's (the oracle: FindTransitionFrame on the
// trial), every shift x N x method asked for that fits in the trial has a row with finite
// measures and N per-frame rows, the latent oracle is below the latent line, and the
// strip, plots and intervals are written; a malformed list or method is refused on one line.
TEST(TransitionCli, SuiteMeasuresEveryCaseOfAnEvent) {
  const test::TempDir dir;
  const std::string events = dir.Write("events.txt", "# one event\n131_05 duck\n").string();
  const fs::path out = dir.path() / "out";
  const test::CommandResult r =
      test::RunJgpm("eval --suite transitions --events " + events + " --data " + test::CmuRoot().string() +
                    " --methods lsopa,li,hold,oracle --frames 5,15,30 --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const Skeleton skeleton = Skeleton131();
  const Motion trial = ReadAmc(Trial(), skeleton);
  const int expected = FindTransitionFrame(skeleton, trial, TransitionKind::kDuck, {}, "131_05") + trial.first_frame_number;
  std::ifstream csv(out / "transitions.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line.rfind("trial,kind,tune,event_frame,shift,N,method,eq23_mm,", 0), 0u) << line;
  std::map<std::string, int> methods;
  std::map<std::string, double> eq23;
  int rows = 0, frames = 0;
  while (std::getline(csv, line)) {
    std::vector<std::string> cells;
    std::stringstream split(line);
    for (std::string cell; std::getline(split, cell, ',');) cells.push_back(cell);
    ASSERT_EQ(cells.size(), 22u) << line;
    EXPECT_EQ(std::stoi(cells[3]), expected) << line;
    ++methods[cells[6]];
    eq23[cells[6]] += std::stod(cells[7]);
    frames += std::stoi(cells[5]);
    for (size_t c = 7; c < cells.size(); ++c) EXPECT_TRUE(std::isfinite(std::stod(cells[c]))) << line;
    ++rows;
  }
  // 3 shifts x 3 N, less the cases outside the trial, each with the 4 methods.
  const int skipped = std::stoi(r.out.substr(r.out.find(" rows, ") + 7));
  EXPECT_EQ(rows, (9 - skipped) * 4) << r.out;
  EXPECT_EQ(methods.size(), 4u);
  EXPECT_LT(eq23["oracle"], eq23["li"]) << r.out;
  std::ifstream per_frame(out / "per_frame.csv");
  int per_frame_rows = -1;  // the header
  while (std::getline(per_frame, line)) ++per_frame_rows;
  EXPECT_EQ(per_frame_rows, frames);
  EXPECT_TRUE(fs::exists(out / "strips" / "131_05-duck.png"));
  EXPECT_TRUE(fs::exists(out / "plots" / "duck-15.png"));
  std::ifstream intervals(out / "intervals.csv");
  std::getline(intervals, line);
  EXPECT_EQ(line, "scope,other,cases,events,lsopa_minus_other_mm,low_mm,high_mm,lsopa_lower");
  std::getline(intervals, line);
  EXPECT_EQ(line.rfind("all,li,", 0), 0u) << line;
  EXPECT_NE(r.out.find("LSOPA minus each method"), std::string::npos) << r.out;

  const test::CommandResult bad_method = test::RunJgpm("eval --suite transitions --events " + events +
                                                       " --methods lsopa,spline --out " + (dir.path() / "out3").string());
  EXPECT_NE(bad_method.status, 0);
  EXPECT_EQ(test::CountLines(bad_method.err), 1) << bad_method.err;
  EXPECT_NE(bad_method.err.find("--methods: 'spline' is not"), std::string::npos) << bad_method.err;
  EXPECT_FALSE(fs::exists(dir.path() / "out3"));

  const std::string bad = dir.Write("bad.txt", "131_05 hop\n").string();
  const test::CommandResult refused =
      test::RunJgpm("eval --suite transitions --events " + bad + " --out " + (dir.path() / "out2").string());
  EXPECT_NE(refused.status, 0);
  EXPECT_EQ(test::CountLines(refused.err), 1) << refused.err;
  EXPECT_NE(refused.err.find("bad.txt:1"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(dir.path() / "out2" / "transitions.csv"));
}

}  // namespace
}  // namespace jgpm
