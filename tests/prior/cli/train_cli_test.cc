// `jgpm train` options that must do what the README says: --max-iterations bounds both
// learnings, a prepared --dataset needs no data root of its own, and --start continues
// from a model's parameters (or refuses a model of another kind); and `jgpm bench
// learning` and `jgpm bench inducing`, whose figures are what the library evaluates.
#include <algorithm>
#include <cstdio>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "io/base/json_file.h"
#include "io/base/text_reader.h"
#include "prior/eval/inducing_gap.h"
#include "prior/eval/learning_scaling.h"
#include "prior/model/model_file.h"
#include "prior/model/model_report.h"
#include "prior/numerics/blas_threads.h"
#include "test_support.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

using Result = test::CommandResult;
Result Jgpm(const std::string& arguments) { return test::RunJgpm(arguments); }

// The training split's cycles, prepared once for the suite.
const fs::path& Dataset() {
  static const test::TempDir* dir = new test::TempDir;
  static const fs::path path = [] {
    const fs::path out = dir->path() / "train.json";
    const test::CommandResult r =
        test::RunJgpm("data cycles --split train --data " + test::CmuRoot().string() + " --out " + out.string());
    EXPECT_EQ(r.status, 0) << r.err;
    return out;
  }();
  return path;
}

// Pixels of exactly colour `bgr` in `image` within `area`, as points.
std::vector<cv::Point> PixelsOf(const cv::Mat& image, const cv::Vec3b& bgr, const cv::Rect& area) {
  std::vector<cv::Point> points;
  for (int v = area.y; v < area.y + area.height; ++v) {
    for (int u = area.x; u < area.x + area.width; ++u) {
      if (image.at<cv::Vec3b>(v, u) == bgr) points.push_back({u, v});
    }
  }
  return points;
}

// Local learning counts steps; the cap was ignored (only full learning's was set).
TEST(TrainCli, MaxIterationsBoundsLocalLearning) {
  test::TempDir dir;
  const fs::path model = dir.path() / "m.json";
  const test::CommandResult r = test::RunJgpm("train --model jgpm --learning local --max-iterations 7 --dataset " +
                                              Dataset().string() + " --out " + model.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json summary = ReadJsonFile(model, "model")["model"]["summary"];
  EXPECT_EQ(summary["iterations"], 7);
  EXPECT_EQ(summary["termination"], "no convergence");
  EXPECT_NE(r.out.find("local learning: no convergence after 7 iterations"), std::string::npos) << r.out;
}

// A prepared dataset records its data root: training from it works where no data root
// can be found (another folder, no $JGPM_DATA), and the skeleton comes from that root.
TEST(TrainCli, DatasetBringsItsOwnDataRoot) {
  test::TempDir dir;
  const fs::path model = dir.path() / "pca.json";
  std::string out, err;
  const int status = test::RunCommand("cd " + dir.path().string() + " && env -u JGPM_DATA " + JGPM_BINARY +
                                          " train --model pca --dataset " + Dataset().string() + " --out pca.json",
                                      &out, &err);
  ASSERT_EQ(status, 0) << err;
  const nlohmann::json m = ReadJsonFile(model, "model")["model"];
  EXPECT_EQ(m["skeleton"]["trial"], "02_01");
  EXPECT_NE(m["skeleton"]["asf"].get<std::string>().find(":name VICON"), std::string::npos);
  // An explicit --data that holds nothing is still refused, naming it.
  const int refused = test::RunCommand("cd " + dir.path().string() + " && " + JGPM_BINARY +
                                           " train --model pca --dataset " + Dataset().string() +
                                           " --data nowhere --out pca2.json",
                                       &out, &err);
  EXPECT_NE(refused, 0);
  EXPECT_NE(err.find("--data nowhere"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(dir.path() / "pca2.json"));
}

// Continuing a training: the second run starts where the first one ended (its initial
// objective is the first's final one), and a model of another kind is refused untouched.
TEST(TrainCli, StartContinuesFromAModel) {
  test::TempDir dir;
  const fs::path first = dir.path() / "first.json", second = dir.path() / "second.json";
  const std::string common = "train --model gplvm --learning full --dataset " + Dataset().string();
  test::CommandResult r = test::RunJgpm(common + " --max-iterations 5 --out " + first.string());
  ASSERT_EQ(r.status, 0) << r.err;
  r = test::RunJgpm(common + " --max-iterations 5 --start " + first.string() + " --out " + second.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json a = ReadJsonFile(first, "model")["model"]["summary"];
  const nlohmann::json b = ReadJsonFile(second, "model")["model"]["summary"];
  const double end_of_first = a["final_objective"];
  EXPECT_NEAR(b["initial_objective"].get<double>(), end_of_first, 1e-9 * std::abs(end_of_first));
  EXPECT_LT(b["final_objective"].get<double>(), end_of_first);
  // Another kind's parameters mean nothing here: one error naming the option, no output.
  r = test::RunJgpm("train --model gpdm --learning full --dataset " + Dataset().string() + " --start " +
                    first.string() + " --out " + (dir.path() / "third.json").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("--start " + first.string()), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path() / "third.json"));
}

TEST(TrainCli, BenchLearningTimesWhatTheLibraryEvaluates) {
  test::TempDir dir;
  const fs::path out = dir.path() / "scaling";
  test::CommandResult r =
      test::RunJgpm("bench learning --n 60,90 --m 10 --exact-max 60 --repeats 1 --converge-time 60 --out " +
                    out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  // N = 60 exact and sparse, N = 90 sparse only; each row's objective is the library's.
  const std::string csv = ReadTextFile(out / "scaling.csv", "scaling");
  std::istringstream lines(csv);
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line, "n,m,seconds_per_evaluation,objective");
  std::vector<std::pair<int, int>> rows;
  while (std::getline(lines, line)) {
    int n = 0, m = 0;
    double seconds = 0, objective = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%d,%d,%lf,%lf", &n, &m, &seconds, &objective), 4) << line;
    rows.push_back({n, m});
    EXPECT_GT(seconds, 0);
    const SyntheticGpProblem problem = MakeSyntheticGpProblem(n, m);
    ObjectiveTerms terms;
    terms.channel_scales = terms.dynamics = true;
    const double expected = GpObjective(problem.y, problem.sequences, nullptr, terms).Evaluate(problem.params, nullptr).total;
    EXPECT_NEAR(objective, expected, 1e-5 * std::abs(expected) + 1e-6) << line;  // printed to 6 decimals
  }
  EXPECT_EQ(rows, (std::vector<std::pair<int, int>>{{60, 0}, {60, 10}, {90, 10}}));
  // Learning to convergence for each of the same points, as the library learns.
  std::istringstream converge(ReadTextFile(out / "convergence.csv", "convergence"));
  std::getline(converge, line);
  EXPECT_EQ(line, "n,m,seconds,iterations,termination,initial_objective,final_objective");
  for (const auto& [n, m] : rows) {
    ASSERT_TRUE(std::getline(converge, line));
    const LinearAlgebraThreadScope threads(1);  // as the command's default
    const ConvergencePoint c = TimeToConverge(n, m, 60);
    char expected[64];
    std::snprintf(expected, sizeof(expected), "%d,%d,", n, m);
    EXPECT_EQ(line.rfind(expected, 0), 0u) << line;
    // Same learning (deterministic): same iterations and ending; the time differs.
    const std::string tail = "," + std::to_string(c.iterations) + "," + std::string(TerminationName(c.termination)) + ",";
    EXPECT_NE(line.find(tail), std::string::npos) << line << " expected " << tail;
  }
  EXPECT_FALSE(cv::imread((out / "scaling.png").string()).empty());
  // More inducing inputs than points: one line naming the option, nothing written.
  r = test::RunJgpm("bench learning --n 60 --m 61 --out " + (dir.path() / "bad").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "jgpm: error: --m 61: expected 3 <= M <= N (60)\n");
  EXPECT_FALSE(fs::exists(dir.path() / "bad" / "scaling.csv"));
}

TEST(TrainCli, BenchInducingReportsTheLibrarysBound) {
  test::TempDir dir;
  const fs::path model = dir.path() / "gpdm.json";
  test::CommandResult r = test::RunJgpm("train --model gpdm --max-iterations 20 --dataset " + Dataset().string() +
                                        " --out " + model.string());
  ASSERT_EQ(r.status, 0) << r.err;
  // M above N (600) is capped at N, and a repeated M is measured once.
  r = test::RunJgpm("bench inducing --model " + model.string() + " --m 100,20,700,100 --threads 1 --out " +
                    (dir.path() / "gap").string());
  ASSERT_EQ(r.status, 0) << r.err;
  const InducingGapReport expected = MeasureInducingGap(*ReadModelFile(model), {20, 100, 600});
  std::istringstream lines(ReadTextFile(dir.path() / "gap" / "inducing_gap.csv", "gap"));
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line, "m,bound,exact,gap,relative_gap,mapping_gap,dynamics_gap,optimised_gap,optimiser_iterations,"
                  "seconds_per_evaluation,exact_seconds_per_evaluation,mean_error_deg,exact_mean_error_deg,"
                  "seconds_per_mean_pose,exact_seconds_per_mean_pose");
  for (const InducingGapPoint& e : expected.points) {
    ASSERT_TRUE(std::getline(lines, line));
    int m = 0;
    int iterations = 0;
    double bound = 0, exact = 0, gap = 0, relative = 0, mapping = 0, dynamics = 0, optimised = 0, seconds = 0;
    double exact_seconds = 0, error = 0, exact_error = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%d,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%d,%lf,%lf,%lf,%lf", &m, &bound, &exact, &gap,
                          &relative, &mapping, &dynamics, &optimised, &iterations, &seconds, &exact_seconds, &error,
                          &exact_error),
              13)
        << line;
    EXPECT_EQ(iterations, 0);
    EXPECT_NEAR(optimised, gap, 1e-6 * std::abs(exact));
    EXPECT_EQ(m, e.m);
    EXPECT_NEAR(bound, e.bound, 1e-9 * std::abs(e.bound) + 1e-6) << line;
    EXPECT_NEAR(exact, expected.exact, 1e-9 * std::abs(expected.exact) + 1e-6);
    EXPECT_NEAR(gap, e.gap(), 1e-6 * std::abs(expected.exact)) << line;
    EXPECT_NEAR(error, e.mean_error_deg, 1e-5 * e.mean_error_deg) << line;  // printed to 7 digits
    EXPECT_NEAR(exact_error, expected.exact_mean_error_deg, 1e-5 * expected.exact_mean_error_deg) << line;
  }
  EXPECT_FALSE(std::getline(lines, line)) << line;
  EXPECT_EQ(cv::imread((dir.path() / "gap" / "inducing_gap.png").string()).size(), cv::Size(760, 480));
  // Too few inducing inputs (a bad option), or a model without a GP (bad data): one line,
  // nothing written.
  r = test::RunJgpm("bench inducing --model " + model.string() + " --m 2 --out " + (dir.path() / "bad").string());
  EXPECT_EQ(r.status, 2);  // a bad option
  EXPECT_EQ(r.err.rfind("jgpm: error: --m", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  const fs::path pca = dir.path() / "pca.json";
  ASSERT_EQ(test::RunJgpm("train --model pca --dataset " + Dataset().string() + " --out " + pca.string()).status, 0);
  r = test::RunJgpm("bench inducing --model " + pca.string() + " --out " + (dir.path() / "bad").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.err, "jgpm: error: model: pca has no GP to make sparse\n");
  EXPECT_FALSE(fs::exists(dir.path() / "bad"));
}

// `jgpm train` for every model kind on the default split (few iterations: the point is
// the command, the file and its reload); `jgpm model info` on each says what the library
// says of the file (kind, size, how training ended, the training reconstruction error);
// then `jgpm plot latent` on one of them.
TEST(TrainCli, TrainEveryKindAndPlot) {
  test::TempDir dir;
  for (const char* kind : {"pca", "gplvm", "gpdm", "bgpdm", "llgpdm", "jgpm", "mljgpm-torus", "mljgpm-cyl"}) {
    SCOPED_TRACE(kind);
    const fs::path model = dir.path() / (std::string(kind) + ".json");
    const Result r = Jgpm(std::string("train --model ") + kind + " --max-iterations 3 --data " +
                          test::CmuRoot().string() + " --out " + model.string());
    ASSERT_EQ(r.status, 0) << kind << "\n" << r.err;
    EXPECT_NE(r.out.find("wrote " + model.string()), std::string::npos) << r.out;
    const nlohmann::json j = nlohmann::json::parse(ReadTextFile(model, "json"));
    EXPECT_EQ(j["model"]["kind"], kind);
    const size_t expected = std::string(kind).rfind("mljgpm", 0) == 0 ? 1800 : 600;
    EXPECT_EQ(j["model"]["latent"].size(), expected) << kind;

    const Result info = Jgpm("model info " + model.string());
    ASSERT_EQ(info.status, 0) << info.err;
    EXPECT_EQ(info.out.rfind(std::string(kind) + " model: " + std::to_string(expected) + " latent points", 0), 0u)
        << info.out;
    const auto loaded = ReadModelFile(model);
    EXPECT_NE(info.out.find(loaded->data().summary.BriefReport()), std::string::npos) << info.out;
    const double error_mm = TrainingReconstructionErrorMm(*loaded);
    char line[96];
    std::snprintf(line, sizeof line, "training reconstruction error: %.2f mm", error_mm);
    EXPECT_NE(info.out.find(line), std::string::npos) << info.out << "lacks: " << line;
    // A model reproduces its training poses to within centimetres (PCA's 3 components: 51 mm).
    EXPECT_GT(error_mm, 0.0);
    EXPECT_LT(error_mm, 80.0);
  }
  // The picture: 1400 x 740, the 3-D view in its left half with the latent points in their
  // layers' colours (BGR; innermost stride scale 0.4 first), each layer's markers spread
  // over the view and the smaller strides nested inside the larger.
  const fs::path png = dir.path() / "latent.png";
  const Result r = Jgpm("plot latent " + (dir.path() / "mljgpm-torus.json").string() + " --out " + png.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const cv::Mat image = cv::imread(png.string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(image.empty());
  EXPECT_EQ(image.cols, 1400);
  EXPECT_EQ(image.rows, 740);
  const cv::Rect view(0, 20, 700, 700);
  std::vector<double> extents;
  for (const cv::Vec3b& colour : {cv::Vec3b(220, 120, 30), cv::Vec3b(40, 170, 40), cv::Vec3b(40, 40, 220)}) {
    const std::vector<cv::Point> markers = PixelsOf(image, colour, view);
    EXPECT_GT(markers.size(), 600u) << colour;  // 600 points a layer, a few pixels each
    const auto [left, right] = std::minmax_element(markers.begin(), markers.end(),
                                                   [](const cv::Point& a, const cv::Point& b) { return a.x < b.x; });
    const int width = markers.empty() ? 0 : right->x - left->x;
    std::cout << "layer " << colour << ": " << markers.size() << " pixels, " << width << " px wide\n";
    EXPECT_GT(width, 100) << colour;
    extents.push_back(width);
  }
  EXPECT_LT(extents[0], extents[1]);
  EXPECT_LT(extents[1], extents[2]);
}

// A time budget ends (local) learning early and the model is still written, saying so.
TEST(TrainCli, TrainStopsAtTheTimeBudgetAndWritesTheModel) {
  test::TempDir dir;
  const fs::path model = dir.path() / "m.json";
  const Result r = Jgpm("train --model mljgpm-cyl --learning local --neighbourhood 60 --max-time 0.5 --data " +
                        test::CmuRoot().string() + " --out " + model.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("local learning: stopped (time budget of 0.5 s used up)"), std::string::npos) << r.out;
  const nlohmann::json j = nlohmann::json::parse(ReadTextFile(model, "json"));
  EXPECT_EQ(j["model"]["summary"]["termination"], "stopped");
  EXPECT_LT(j["model"]["summary"]["wall_seconds"].get<double>(), 5.0);
}

TEST(TrainCli, TrainAndPlotBadInput) {
  test::TempDir dir;
  Result r = Jgpm("train --model svm --out " + (dir.path() / "m.json").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("--model svm: expected one of pca, gplvm"), std::string::npos) << r.err;
  r = Jgpm("train --learning sideways --out x.json");
  EXPECT_EQ(r.status, 2);
  for (const char* option : {"--neighbourhood 2", "--max-time -1", "--threads -1"}) {
    r = Jgpm(std::string("train ") + option + " --out x.json");
    EXPECT_EQ(r.status, 2) << option;
    EXPECT_NE(r.err.find(std::string(option).substr(0, std::string(option).find(' '))), std::string::npos) << r.err;
  }
  const fs::path bad = dir.Write("bad.json", "{\"format\": \"jgpm-model\", \"version\": 99}");
  r = Jgpm("plot latent " + bad.string() + " --out " + (dir.path() / "p.png").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("version 99 is not supported"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir.path() / "p.png"));
  EXPECT_FALSE(fs::exists(dir.path() / "m.json"));
}

TEST(TrainCli, SynthWritesMotionAnAnimationToolLoads) {
  test::TempDir dir;
  const std::string data = " --data " + test::CmuRoot().string();
  const fs::path jgpm = dir.path() / "jgpm.json", pca = dir.path() / "pca.json";
  ASSERT_EQ(Jgpm("train --model jgpm --max-iterations 3" + data + " --out " + jgpm.string()).status, 0);
  ASSERT_EQ(Jgpm("train --model pca" + data + " --out " + pca.string()).status, 0);
  const fs::path amc = dir.path() / "walk.amc", png = dir.path() / "walk.png";
  Result r = Jgpm("synth --model " + jgpm.string() + " --path inner-spiral --frames 40 --out " + amc.string() +
                  " --png " + png.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir.path() / "walk.asf"));
  EXPECT_TRUE(fs::exists(png));
  r = Jgpm("data info " + amc.string() + " --fps 30");  // finds walk.asf beside it
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("frames 40"), std::string::npos) << r.out;

  r = Jgpm("synth --model " + pca.string() + " --out " + amc.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("manifold"), std::string::npos) << r.err;
  r = Jgpm("synth --model " + jgpm.string() + " --out " + (dir.path() / "w.fbx").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find(".amc or .bvh"), std::string::npos) << r.err;
  r = Jgpm("synth --model " + jgpm.string() + " --path zigzag --out " + amc.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("--path"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace jgpm
