// `jgpm render` end to end: a short clip from a real trial, and every kind of bad request
// refused on one line with nothing written.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <Eigen/Geometry>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "calibration/camera.h"
#include "io/base/json_file.h"
#include "test_support.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

using Result = test::CommandResult;
Result Jgpm(const std::string& arguments) { return test::RunJgpm(arguments); }

std::string Amc() { return (test::CmuRoot() / "subjects/35/35_12.amc").string(); }

// Foreground (non-zero) pixels of a mask within `radius` pixels of `at`.
bool ForegroundNear(const cv::Mat& mask, const Eigen::Vector2d& at, int radius) {
  const int u0 = static_cast<int>(std::lround(at.x())), v0 = static_cast<int>(std::lround(at.y()));
  for (int v = std::max(0, v0 - radius); v <= std::min(mask.rows - 1, v0 + radius); ++v) {
    for (int u = std::max(0, u0 - radius); u <= std::min(mask.cols - 1, u0 + radius); ++u) {
      if (mask.at<uint8_t>(v, u)) return true;
    }
  }
  return false;
}

// A body part of the clip's body model: the joints it spans, its larger end radius.
struct PartEnds {
  int from, to;
  double radius_mm;
};

// The exact masks of a clip against its cameras and ground truth: each camera read back
// from its camK.yaml, each kept frame's joints (world mm) projected through it. The joints
// a body part spans are inside the body (the centres of its capsules' end spheres), so
// they project onto the silhouette (within a pixel: the mask samples pixel centres), and
// the silhouette's bounding box holds theirs. It reaches no further than the parts do: a
// part's capsule is within its radius r of the segment between its joints, whose balls at
// depth z or more project within f r / (z - r) pixels of the projected segment, times the
// secant of the angle off the optical axis (largest at an end), plus a pixel of sampling.
// (A pinhole bound: the default rig's cameras have no lens distortion.)
// A walker's body: the joints its parts span and the parts.
struct WalkerParts {
  std::vector<std::string> joint_names;
  std::set<int> inside;
  std::vector<PartEnds> parts;
};

WalkerParts ReadParts(const nlohmann::json& walker) {
  WalkerParts w;
  w.joint_names = walker["joint_names"].get<std::vector<std::string>>();
  for (const auto& part : walker["body_model"]["parts"]) {
    int ends[2];
    for (int e = 0; e < 2; ++e) {
      const auto at = std::find(w.joint_names.begin(), w.joint_names.end(), part[e ? "to" : "from"].get<std::string>());
      EXPECT_NE(at, w.joint_names.end()) << part;
      ends[e] = static_cast<int>(at - w.joint_names.begin());
      w.inside.insert(ends[e]);
    }
    w.parts.push_back({ends[0], ends[1], std::max(part["radius_from_mm"].get<double>(), part["radius_to_mm"].get<double>())});
  }
  for (const char* joint : {"head", "root", "ltibia", "rtibia"}) {  // head, pelvis, ankles
    const int j = static_cast<int>(std::find(w.joint_names.begin(), w.joint_names.end(), joint) - w.joint_names.begin());
    EXPECT_TRUE(w.inside.count(j)) << joint;
  }
  return w;
}

// The exact masks of a clip against its cameras and ground truth: each camera read back
// from its camK.yaml, each kept frame's joints (world mm) projected through it. The joints
// a body part spans are inside the body (the centres of its capsules' end spheres), so
// they project onto the silhouette (within a pixel: the mask samples pixel centres), and
// the silhouette's bounding box holds theirs. It reaches no further than the parts do: a
// part's capsule is within its radius r of the segment between its joints, whose balls at
// depth z or more project within f r / (z - r) pixels of the projected segment, times the
// secant of the angle off the optical axis (largest at an end), plus a pixel of sampling.
// (A pinhole bound: the default rig's cameras have no lens distortion.) With several
// walkers, each walker in the frame is checked so and the reach is all of theirs.
void ExpectMasksMatchTheCameras(const std::filesystem::path& clip, const nlohmann::json& truth) {
  // walkers[i] and, per clip frame, the joints of each walker in it.
  std::vector<WalkerParts> walkers;
  std::map<int, std::vector<std::pair<int, nlohmann::json>>> posed;
  if (truth.contains("people")) {
    for (const auto& person : truth["people"]) {
      walkers.push_back(ReadParts(person));
      for (const auto& f : person["frames"])
        posed[f["frame"].get<int>()].push_back({static_cast<int>(walkers.size()) - 1, f["joints_mm"]});
    }
  } else {
    walkers.push_back(ReadParts(truth));
    for (const auto& f : truth["frames"]) posed[f["frame"].get<int>()].push_back({0, f["joints_mm"]});
  }
  int checked = 0;
  for (const auto& c : truth["cameras"]) {
    const Camera camera = ReadCameraYaml((clip / c["yaml"].get<std::string>()).string()).camera;
    ASSERT_TRUE(std::all_of(camera.distortion.begin(), camera.distortion.end(), [](double k) { return k == 0; }));
    auto secant = [&](const Eigen::Vector2d& p) {
      return std::hypot(1.0, (p.x() - camera.cx) / camera.fx, (p.y() - camera.cy) / camera.fy);
    };
    for (const auto& frame : truth["frames"]) {
      char name[32];
      std::snprintf(name, sizeof name, "%06d.png", frame["frame"].get<int>());
      const std::filesystem::path path = clip / c["masks"].get<std::string>() / name;
      if (frame["dropped"].get<bool>()) {
        EXPECT_FALSE(std::filesystem::exists(path)) << path;
        continue;
      }
      const cv::Mat mask = cv::imread(path.string(), cv::IMREAD_GRAYSCALE);
      ASSERT_FALSE(mask.empty()) << path;
      ASSERT_EQ(mask.cols, camera.width);
      ASSERT_EQ(mask.rows, camera.height);
      Eigen::AlignedBox2d reach_box, mask_box;
      std::vector<Eigen::AlignedBox2d> joints_boxes;
      for (const auto& [w, joints] : posed[frame["frame"].get<int>()]) {
        const WalkerParts& walker = walkers[w];
        std::map<int, Eigen::Vector2d> pixel;
        std::map<int, double> depth_mm;
        Eigen::AlignedBox2d joints_box;
        for (int j : walker.inside) {
          const auto& p = joints[j];
          const Eigen::Vector3d world(p[0].get<double>(), p[1].get<double>(), p[2].get<double>());
          ASSERT_TRUE(camera.Project(world, &pixel[j]));
          depth_mm[j] = camera.ToCamera(world).z();
          EXPECT_TRUE(ForegroundNear(mask, pixel[j], 1)) << path << ": " << walker.joint_names[j] << " at " << pixel[j].transpose();
          joints_box.extend(pixel[j]);
        }
        joints_boxes.push_back(joints_box);
        for (const PartEnds& part : walker.parts) {
          const double z = std::min(depth_mm[part.from], depth_mm[part.to]);
          const double reach_px = std::max(camera.fx, camera.fy) * part.radius_mm / (z - part.radius_mm) *
                                      std::max(secant(pixel[part.from]), secant(pixel[part.to])) + 1;
          const Eigen::Vector2d pad = Eigen::Vector2d::Constant(reach_px);
          for (int end : {part.from, part.to}) reach_box.extend(pixel[end] - pad).extend(pixel[end] + pad);
        }
      }
      for (int v = 0; v < mask.rows; ++v) {
        for (int u = 0; u < mask.cols; ++u) {
          if (mask.at<uint8_t>(v, u)) mask_box.extend(Eigen::Vector2d(u, v));
        }
      }
      ASSERT_FALSE(mask_box.isEmpty()) << path;
      for (const Eigen::AlignedBox2d& joints_box : joints_boxes) {
        EXPECT_TRUE(mask_box.contains(Eigen::AlignedBox2d(joints_box.min().array() + 1, joints_box.max().array() - 1)))
            << path << ": mask " << mask_box.min().transpose() << " .. " << mask_box.max().transpose() << ", joints "
            << joints_box.min().transpose() << " .. " << joints_box.max().transpose();
      }
      EXPECT_TRUE(reach_box.contains(mask_box)) << path << ": mask " << mask_box.min().transpose() << " .. "
                                                << mask_box.max().transpose() << ", the parts' reach "
                                                << reach_box.min().transpose() << " .. " << reach_box.max().transpose();
      ++checked;
    }
  }
  EXPECT_GT(checked, 0);
}

TEST(RenderCli, RendersAShortClipWithTheDefaultRig) {
  test::TempDir dir;
  const fs::path out = dir.path() / "clip";
  const Result r = Jgpm("render --amc " + Amc() + " --out " + out.string() +
                        " --max-frames 6 --cameras 2 --clutter 2 --drop-rate 0.2 --seed 3");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("rendered 6 frames"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("cam1: f "), std::string::npos) << r.out;
  EXPECT_EQ(r.err.find("error"), std::string::npos) << r.err;  // progress lines at most
  const nlohmann::json truth = ReadJsonFile(out / "ground_truth.json", "truth");
  EXPECT_EQ(truth["frames"].size(), 6u);
  EXPECT_EQ(truth["degradations"]["clutter_blobs"], 2);
  EXPECT_NE(truth["source"]["asf"].get<std::string>().find("35.asf"), std::string::npos);
  for (const char* file : {"cam0.yaml", "cam1.yaml", "cam0.avi", "cam1.avi", "contact_sheet.png"})
    EXPECT_TRUE(fs::exists(out / file)) << file;
  ExpectMasksMatchTheCameras(out, truth);
}

// Two walkers sent to cross: both in the ground truth, each at its place, and the masks
// still agree with the cameras (for the first walker, the top level).
TEST(RenderCli, RendersTwoWalkersCrossing) {
  test::TempDir dir;
  const fs::path out = dir.path() / "clip";
  const Result r = Jgpm("render --amc " + Amc() + " --amc " + Amc() + " --walk 0,0,0,0 --walk 1000,0,90,0.2 --out " +
                        out.string() + " --max-frames 8 --rig surveillance --cameras 1 --body-seed 2");
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json truth = ReadJsonFile(out / "ground_truth.json", "truth");
  ASSERT_EQ(truth["people"].size(), 2u);
  EXPECT_EQ(truth["people"][1]["placement"]["heading_deg"], 90.0);
  EXPECT_EQ(truth["people"][0]["body_model"]["body_seed"], 2);  // --body-seed, then + 1 each
  EXPECT_EQ(truth["people"][1]["body_model"]["body_seed"], 3);
  EXPECT_NEAR(truth["people"][1]["start_s"].get<double>(), 0.2, 1e-12);  // the same trial, 0.2 s later
  EXPECT_EQ(truth["people"][1]["frames"][0]["frame"], 6);                  // 0.2 s at 30 fps
  ExpectMasksMatchTheCameras(out, truth);
}

TEST(RenderCli, BadRequestsGiveOneLineAndWriteNothing) {
  test::TempDir dir;
  const std::string out = (dir.path() / "clip").string();
  dir.Write("unplaced.yaml",
            "%YAML:1.0\n---\nimage_width: 320\nimage_height: 240\n"
            "camera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n   data: [ 300., 0., 160., 0., 300., 120., 0., 0., 1. ]\n"
            "distortion_coefficients: !!opencv-matrix\n   rows: 1\n   cols: 5\n   dt: d\n   data: [ 0., 0., 0., 0., 0. ]\n");
  fs::create_directories(dir.path() / "full");
  dir.Write("full/x.txt", "mine");
  const std::string unplaced = (dir.path() / "unplaced.yaml").string();
  struct Case {
    std::string arguments;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"--amc " + Amc() + " --out " + out + " --cameras 5", "--cameras"},
      {"--amc " + Amc() + " --out " + out + " --camera " + unplaced + " --cameras 2", "excludes"},
      {"--amc " + Amc() + " --out " + out + " --camera " + unplaced, "place the camera"},
      {"--amc " + Amc() + " --out " + out + " --fps 500", "exceeds the motion's 120"},
      {"--amc " + Amc() + " --out " + out + " --drop-rate 1.5", "--drop-rate"},
      {"--amc " + Amc() + " --out " + (dir.path() / "full").string(), "not empty"},
      {"--amc " + (dir.path() / "none.amc").string() + " --out " + out, "none.amc"},
      {"--amc " + Amc(), "--out"},
      {"--amc " + Amc() + " --amc " + Amc() + " --out " + out + " --walk 0,0,90,0", "--walk"},
      {"--amc " + Amc() + " --out " + out + " --walk 0,0,ninety,0", "X_MM,Z_MM,HEADING_DEG,DELAY_S"},
      {"--amc " + Amc() + " --out " + out + " --walk 0,0,90,nan", "X_MM,Z_MM,HEADING_DEG,DELAY_S"},
      {"--amc " + Amc() + " --out " + out + " --walk 0,0,90,1", "delay must be 0"},
  };
  for (const Case& c : cases) {
    const Result r = Jgpm("render " + c.arguments);
    EXPECT_NE(r.status, 0) << c.arguments;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.arguments << "\n" << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.arguments << "\n" << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.arguments;
    EXPECT_FALSE(fs::exists(out + ".partial")) << c.arguments;
  }
  EXPECT_TRUE(fs::exists(dir.path() / "full/x.txt"));
}

// Every clip of the tracking benchmark names a test-split trial (never training data) and
// options `jgpm render` accepts, and renders masks that agree with its cameras.
TEST(RenderCli, TrackingSuiteDefinitionRenders) {
  const std::vector<TrialId> test_split = test::SplitTrials("test");
  const std::vector<TrialId> train_split = test::SplitTrials("train");
  auto contains = [](const std::vector<TrialId>& ids, const std::string& name) {
    return std::any_of(ids.begin(), ids.end(), [&](const TrialId& id) { return id.name == name; });
  };
  std::ifstream suite(fs::path(JGPM_SOURCE_DIR) / "datasets_scripts/tracking_suite.txt");
  ASSERT_TRUE(suite.good());
  test::TempDir dir;
  int clips = 0;
  for (std::string line; std::getline(suite, line);) {
    std::istringstream words(line);
    std::string name, trial, options, word;
    if (!(words >> name) || name[0] == '#') continue;
    ASSERT_TRUE(static_cast<bool>(words >> trial)) << line;
    while (words >> word) options += " " + word;
    EXPECT_TRUE(contains(test_split, trial)) << trial;
    EXPECT_FALSE(contains(train_split, trial)) << trial;
    const fs::path amc = test::CmuRoot() / "subjects" / trial.substr(0, 2) / (trial + ".amc");
    const Result r = Jgpm("render --amc " + amc.string() + " --out " + (dir.path() / name).string() +
                          options + " --max-frames 2 --no-contact-sheet");
    EXPECT_EQ(r.status, 0) << line << "\n" << r.err;
    if (r.status == 0) ExpectMasksMatchTheCameras(dir.path() / name, ReadJsonFile(dir.path() / name / "ground_truth.json", "truth"));
    ++clips;
  }
  EXPECT_GE(clips, 4);
}

}  // namespace
}  // namespace jgpm
