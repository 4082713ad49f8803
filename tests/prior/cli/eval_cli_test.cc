// `jgpm eval`: one case and the paper suite, posture adaptation, leave one subject out and
// bad input; the figures it prints and writes against the library run here on the same
// model files and trials.
#include <map>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "io/base/text_reader.h"
#include "io/gait/gait_dataset.h"
#include "io/gait/split.h"
#include "prior/eval/loso.h"
#include "prior/eval/validation.h"
#include "prior/model/model_file.h"
#include "test_support.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

using Result = test::CommandResult;
Result Jgpm(const std::string& arguments) { return test::RunJgpm(arguments); }

// A CSV row's cells (no quoting in jgpm's CSVs).
std::vector<std::string> Cells(const std::string& row) {
  std::vector<std::string> cells;
  std::istringstream fields(row);
  for (std::string cell; std::getline(fields, cell, ',');) cells.push_back(cell);
  return cells;
}

// The filled bars of colour `bgr` in a chart, left to right: for each run of adjacent
// columns whose longest vertical run of the colour (3 px or more) ends on the bars' common
// baseline, that run's length. Text and legend swatches end elsewhere or are shorter.
std::vector<int> BarHeights(const cv::Mat& image, const cv::Vec3b& bgr) {
  std::vector<int> length(image.cols, 0), bottom(image.cols, -1);
  std::map<int, int> bottoms;
  for (int u = 0; u < image.cols; ++u) {
    for (int v = 0, run = 0; v < image.rows; ++v) {
      run = image.at<cv::Vec3b>(v, u) == bgr ? run + 1 : 0;
      if (run >= std::max(3, length[u])) {
        length[u] = run;
        bottom[u] = v;
      }
    }
    if (length[u] >= 3) ++bottoms[bottom[u]];
  }
  if (bottoms.empty()) return {};
  const int baseline = std::max_element(bottoms.begin(), bottoms.end(), [](auto& a, auto& b) { return a.second < b.second; })->first;
  std::vector<int> bars;
  for (int u = 0; u < image.cols; ++u) {
    if (bottom[u] != baseline || length[u] < 3) continue;
    if (u > 0 && bottom[u - 1] == baseline && length[u - 1] >= 3) {
      bars.back() = std::max(bars.back(), length[u]);
    } else {
      bars.push_back(length[u]);
    }
  }
  return bars;
}

// `jgpm eval`: one case to JSON, the paper suite on two trials to CSV and charts; the
// numbers are what prior/eval/validation.h computes here for the same model files and trials.
TEST(EvalCli, EvalOneCaseAndTheSuite) {
  test::TempDir dir;
  const std::string data = " --data " + test::CmuRoot().string();
  const fs::path pca = dir.path() / "pca.json", gplvm = dir.path() / "gplvm.json";
  ASSERT_EQ(Jgpm("train --model pca" + data + " --out " + pca.string()).status, 0);
  ASSERT_EQ(Jgpm("train --model gplvm --max-iterations 3" + data + " --out " + gplvm.string()).status, 0);
  const fs::path trials = dir.Write("two.txt", "07_01\n35_10\n");
  const GaitDataset dataset =
      PrepareGaitDataset(test::CmuRoot(), trials.string(), ReadSplit(trials), GaitCycleOptions{});
  const auto pca_model = ReadModelFile(pca), gplvm_model = ReadModelFile(gplvm);
  auto validate = [&](const GaitModel& model, const ValidationCase& c) {
    return Validate(model, LoadValidationTrials(dataset, model), c);
  };

  const fs::path json = dir.path() / "filtering.json";
  Result r = Jgpm("eval --model " + pca.string() + " --task filtering --noise 0.1 --draws 2 --scale 0.5 --trials " +
                  trials.string() + data + " --json " + json.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(ReadTextFile(json, "json"));
  ValidationCase filtering;
  filtering.task = ValidationTask::kFiltering;
  filtering.noise = 0.1;
  filtering.draws = 2;
  filtering.scale = 0.5;
  const ValidationResult expected = validate(*pca_model, filtering);
  ASSERT_EQ(expected.trials.size(), 2u);
  ASSERT_EQ(j["trials"].size(), 2u);
  for (int t = 0; t < 2; ++t) {
    EXPECT_EQ(j["trials"][t]["trial"], expected.trials[t]);
    EXPECT_NEAR(j["trials"][t]["error_mm"].get<double>(), expected.trial_errors_mm[t], 1e-9 * expected.trial_errors_mm[t]);
  }
  EXPECT_EQ(j["trials"][0]["trial"], "07_01");
  EXPECT_NEAR(j["mean_error_mm"].get<double>(), expected.mean_error_mm, 1e-9 * expected.mean_error_mm);
  EXPECT_NEAR(j["std_error_mm"].get<double>(), expected.std_error_mm, 1e-9 * expected.mean_error_mm);
  ASSERT_EQ(j["draw_errors_mm"].size(), 2u);
  for (int d = 0; d < 2; ++d) {
    EXPECT_NEAR(j["draw_errors_mm"][d].get<double>(), expected.draw_errors_mm[d], 1e-9 * expected.mean_error_mm);
  }
  EXPECT_EQ(j["case"], "filtering 10% s=0.5");
  char line[96];  // the case and its mean error, as the table prints them
  std::snprintf(line, sizeof line, "%-34s %8.2f mm", "filtering 10% s=0.5", expected.mean_error_mm);
  EXPECT_NE(r.out.find(line), std::string::npos) << r.out << "lacks: " << line;

  const fs::path out = dir.path() / "suite";
  r = Jgpm("eval --suite paper --model " + pca.string() + " --model " + gplvm.string() + " --trials " +
           trials.string() + data + " --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string csv = ReadTextFile(out / "paper.csv", "csv");
  EXPECT_EQ(test::CountLines(csv), 1 + 2 * 35);
  // model,task,missing,noise,scale -> mean_error_mm.
  std::map<std::string, double> mean_mm;
  {
    std::istringstream rows(csv);
    std::string row;
    std::getline(rows, row);
    EXPECT_EQ(row, "model,task,missing,noise,scale,mean_error_mm,std_error_mm,trials,seconds");
    while (std::getline(rows, row)) {
      const std::vector<std::string> cells = Cells(row);
      ASSERT_EQ(cells.size(), 9u) << row;
      EXPECT_EQ(cells[7], "2") << row;
      mean_mm[cells[0] + "," + cells[1] + "," + cells[2] + "," + cells[3] + "," + cells[4]] = std::stod(cells[5]);
    }
  }
  ASSERT_EQ(mean_mm.size(), 70u);
  // The detail: a row per joint and channel of every case, the joints averaging to the
  // case's mean (both written to 0.001).
  const std::string detail = ReadTextFile(out / "paper_detail.csv", "detail csv");
  const int channels = gplvm_model->NumChannels();
  EXPECT_EQ(test::CountLines(detail), 1 + 2 * 35 * (17 + channels));
  {
    std::map<std::string, double> joint_sum;
    std::istringstream rows(detail);
    std::string row;
    std::getline(rows, row);
    EXPECT_EQ(row, "model,task,missing,noise,scale,kind,name,error");
    while (std::getline(rows, row)) {
      const std::vector<std::string> cells = Cells(row);
      ASSERT_EQ(cells.size(), 8u) << row;
      const std::string key = cells[0] + "," + cells[1] + "," + cells[2] + "," + cells[3] + "," + cells[4];
      if (cells[5] == "joint_mm") joint_sum[key] += std::stod(cells[7]) / 17;
    }
    ASSERT_EQ(joint_sum.size(), 70u);
    for (const auto& [key, mean] : joint_sum) EXPECT_NEAR(mean, mean_mm.at(key), 2e-3) << key;
  }
  // joints.png: a horizontal bar per joint and model, its length proportional to the
  // joint's error averaged over the 35 cases (from the detail CSV), to within 2 px. Turned
  // a quarter so that the bars stand on one baseline.
  {
    std::map<std::string, std::vector<double>> per_joint;  // model -> 17, in the CSV's order
    std::istringstream rows(detail);
    std::string row;
    std::getline(rows, row);
    std::map<std::string, int> seen;
    while (std::getline(rows, row)) {
      const std::vector<std::string> cells = Cells(row);
      if (cells[5] != "joint_mm") continue;
      std::vector<double>& v = per_joint[cells[0]];
      v.resize(17, 0.0);
      v[seen[cells[0]]++ % 17] += std::stod(cells[7]) / 35;
    }
    const cv::Mat joints_png = cv::imread((out / "joints.png").string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(joints_png.empty());
    cv::Mat turned;
    cv::transpose(joints_png, turned);
    cv::flip(turned, turned, 0);
    const std::vector<int> lengths[2] = {BarHeights(turned, {60, 60, 60}), BarHeights(turned, {200, 120, 30})};
    ASSERT_EQ(lengths[0].size(), 17u);
    ASSERT_EQ(lengths[1].size(), 17u);
    const double longest_mm = std::max(*std::max_element(per_joint["pca"].begin(), per_joint["pca"].end()),
                                       *std::max_element(per_joint["gplvm"].begin(), per_joint["gplvm"].end()));
    const int longest_px = std::max(*std::max_element(lengths[0].begin(), lengths[0].end()),
                                    *std::max_element(lengths[1].begin(), lengths[1].end()));
    for (int j = 0; j < 17; ++j) {
      EXPECT_NEAR(lengths[0][j], longest_px * per_joint["pca"][j] / longest_mm, 2.0) << "pca, joint " << j;
      EXPECT_NEAR(lengths[1][j], longest_px * per_joint["gplvm"][j] / longest_mm, 2.0) << "gplvm, joint " << j;
    }
  }
  ValidationCase left_side;
  left_side.task = ValidationTask::kReconstruction;
  left_side.missing = MissingPart::kLeftSide;
  left_side.scale = 0.667;
  EXPECT_NEAR(mean_mm.at("gplvm,reconstruction,left-side,0,0.667"), validate(*gplvm_model, left_side).mean_error_mm, 6e-4);
  std::vector<double> interpolation[2];  // per model, scales 1.25 .. 0.4 (the charts' order)
  for (const double scale : {1.25, 1.0, 0.667, 0.5, 0.4}) {
    ValidationCase c;
    c.scale = scale;
    char key[64];
    std::snprintf(key, sizeof key, "interpolation,none,0,%g", scale);
    interpolation[0].push_back(mean_mm.at(std::string("pca,") + key));
    interpolation[1].push_back(mean_mm.at(std::string("gplvm,") + key));
    EXPECT_NEAR(interpolation[0].back(), validate(*pca_model, c).mean_error_mm, 6e-4) << scale;
  }

  // The charts: panels of 520 x 380 side by side (at least two panels wide) over a legend
  // row; a bar per model and scale in the model's colour, its height proportional to the
  // error (here against the tallest bar, to within 2 px).
  for (const auto& [png, panels] : {std::pair{"interpolation.png", 1}, {"reconstruction.png", 3}, {"filtering.png", 3}}) {
    const cv::Mat chart = cv::imread((out / png).string(), cv::IMREAD_COLOR);
    ASSERT_FALSE(chart.empty()) << png;
    EXPECT_EQ(chart.cols, 520 * std::max(2, panels)) << png;
    EXPECT_EQ(chart.rows, 380 + 40 + 22) << png;
    EXPECT_EQ(BarHeights(chart, {60, 60, 60}).size(), 5u * panels) << png;     // pca
    EXPECT_EQ(BarHeights(chart, {200, 120, 30}).size(), 5u * panels) << png;  // gplvm
  }
  const cv::Mat chart = cv::imread((out / "interpolation.png").string(), cv::IMREAD_COLOR);
  const std::vector<int> bars[2] = {BarHeights(chart, {60, 60, 60}), BarHeights(chart, {200, 120, 30})};
  ASSERT_EQ(bars[0].size(), 5u);
  ASSERT_EQ(bars[1].size(), 5u);
  const double tallest_mm = std::max(*std::max_element(interpolation[0].begin(), interpolation[0].end()),
                                     *std::max_element(interpolation[1].begin(), interpolation[1].end()));
  const int tallest_px = std::max(*std::max_element(bars[0].begin(), bars[0].end()), *std::max_element(bars[1].begin(), bars[1].end()));
  for (int m = 0; m < 2; ++m) {
    for (int s = 0; s < 5; ++s) {
      EXPECT_NEAR(bars[m][s], tallest_px * interpolation[m][s] / tallest_mm, 2.0) << "model " << m << ", scale " << s;
    }
  }
}

// --adapt both: each model twice, as the library validates it without and with posture
// adaptation; the unseen subject (07) comes closer with it, and its offsets are written.
TEST(EvalCli, EvalAdaptsPosture) {
  test::TempDir dir;
  const std::string data = " --data " + test::CmuRoot().string();
  const fs::path pca = dir.path() / "pca.json", json = dir.path() / "e.json";
  ASSERT_EQ(Jgpm("train --model pca" + data + " --out " + pca.string()).status, 0);
  const fs::path trials = dir.Write("two.txt", "07_01\n35_10\n");
  const Result r = Jgpm("eval --model " + pca.string() + " --task interpolation --adapt both --trials " +
                        trials.string() + data + " --json " + json.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("pca+posture"), std::string::npos) << r.out;
  const size_t gains = r.out.find("gains (mean ");  // printed for the adapted run only
  ASSERT_NE(gains, std::string::npos) << r.out;
  EXPECT_GT(gains, r.out.find("pca+posture")) << r.out;
  EXPECT_EQ(r.out.find("gains (mean ", gains + 1), std::string::npos) << r.out;
  const double printed_mean = std::stod(r.out.substr(gains + std::string("gains (mean ").size()));
  const nlohmann::json j = nlohmann::json::parse(ReadTextFile(json, "json"));
  ASSERT_EQ(j["models"].size(), 2u);
  EXPECT_EQ(j["models"][0]["name"], "pca");
  EXPECT_EQ(j["models"][1]["name"], "pca+posture");
  const auto model = ReadModelFile(pca);
  const GaitDataset dataset = PrepareGaitDataset(test::CmuRoot(), trials.string(), ReadSplit(trials), GaitCycleOptions{});
  InferenceOptions adapt;
  adapt.adapt_posture = true;
  const ValidationResult plain = Validate(*model, LoadValidationTrials(dataset, *model), ValidationCase{});
  const ValidationResult adapted = Validate(*model, LoadValidationTrials(dataset, *model), ValidationCase{}, adapt);
  const nlohmann::json& a = j["models"][1]["results"][0];
  EXPECT_NEAR(j["models"][0]["results"][0]["mean_error_mm"].get<double>(), plain.mean_error_mm, 1e-9 * plain.mean_error_mm);
  EXPECT_NEAR(a["mean_error_mm"].get<double>(), adapted.mean_error_mm, 1e-9 * adapted.mean_error_mm);
  EXPECT_LT(adapted.trial_errors_mm[0], 0.8 * plain.trial_errors_mm[0]);  // 07_01
  ASSERT_EQ(a["per_channel_deg"].size(), static_cast<size_t>(model->NumChannels()));
  ASSERT_EQ(adapted.channel_posture_deg.size(), static_cast<size_t>(model->NumChannels()));
  EXPECT_TRUE(plain.channel_posture_deg.empty());
  for (int k = 0; k < model->NumChannels(); ++k) {
    EXPECT_NEAR(a["per_channel_deg"][k]["posture_offset_deg"].get<double>(), adapted.channel_posture_deg[k], 1e-9);
    EXPECT_NEAR(a["per_channel_deg"][k]["gain"].get<double>(), adapted.channel_gain[k], 1e-9);
  }
  EXPECT_GT(*std::max_element(adapted.channel_gain.begin(), adapted.channel_gain.end()), 1.01);  // gains moved
  // The printed level is the channels' mean gain.
  EXPECT_NEAR(printed_mean,
              std::accumulate(adapted.channel_gain.begin(), adapted.channel_gain.end(), 0.0) / model->NumChannels(),
              0.006);
  EXPECT_FALSE(j["models"][0]["results"][0]["per_channel_deg"][0].contains("posture_offset_deg"));
  // --gain-std reaches the inference: the library's result with that prior.
  ASSERT_EQ(Jgpm("eval --model " + pca.string() + " --task interpolation --adapt posture --gain-std 0.3 --trials " +
                 trials.string() + data + " --json " + json.string())
                .status,
            0);
  adapt.gain_std = 0.3;
  const double wide = Validate(*model, LoadValidationTrials(dataset, *model), ValidationCase{}, adapt).mean_error_mm;
  const nlohmann::json w = nlohmann::json::parse(ReadTextFile(json, "json"));
  EXPECT_NEAR(w["mean_error_mm"].get<double>(), wide, 1e-9 * wide);  // one model, one case: the result itself
  EXPECT_GT(std::abs(wide - adapted.mean_error_mm), 1e-6);
  // And --common-gain-std: 0 gives independent gains.
  ASSERT_EQ(Jgpm("eval --model " + pca.string() + " --task interpolation --adapt posture --common-gain-std 0 --trials " +
                 trials.string() + data + " --json " + json.string())
                .status,
            0);
  adapt.gain_std = InferenceOptions{}.gain_std;
  adapt.common_gain_std = 0;
  const double independent = Validate(*model, LoadValidationTrials(dataset, *model), ValidationCase{}, adapt).mean_error_mm;
  EXPECT_NEAR(nlohmann::json::parse(ReadTextFile(json, "json"))["mean_error_mm"].get<double>(), independent,
              1e-9 * independent);
  EXPECT_GT(std::abs(independent - adapted.mean_error_mm), 1e-6);
  for (const char* option : {" --adapt size", " --gain-std 0", " --gain-std -1", " --common-gain-std -0.1"}) {
    const Result bad = Jgpm("eval --model " + pca.string() + " --task interpolation" + option + data);
    EXPECT_EQ(bad.status, 2) << option;
    EXPECT_NE(bad.err.find(std::string(option).substr(1, std::string(option).find(' ', 1) - 1)), std::string::npos) << bad.err;
  }
}

// --suite loso with PCA on three subjects: each fold's errors are those of a PCA the
// library trains on the other subjects' trials, validated on the held-out one's; a second
// run reads the fold models back and writes the same table; a model file of other trials
// in their place is refused by name, and the table is left as it was.
TEST(EvalCli, EvalLeaveOneSubjectOut) {
  test::TempDir dir;
  const std::string data = " --data " + test::CmuRoot().string();
  const fs::path trials = dir.Write("three.txt", "02_01\n05_01\n07_01\n07_02\n");
  const fs::path out = dir.path() / "loso";
  const std::string command = "eval --suite loso --kinds pca --adapt both --trials " + trials.string() + data +
                              " --out " + out.string();
  Result r = Jgpm(command);
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string csv = ReadTextFile(out / "loso.csv", "csv");
  EXPECT_EQ(test::CountLines(csv), 1 + 3 * 2 + 2) << csv;
  const GaitDataset dataset = PrepareGaitDataset(test::CmuRoot(), trials.string(), ReadSplit(trials), GaitCycleOptions{});
  const std::vector<LosoFold> folds = LosoFolds(dataset, 9);
  ASSERT_EQ(folds.size(), 3u);
  std::istringstream rows(csv);
  std::string row;
  std::getline(rows, row);
  for (const LosoFold& fold : folds) {
    const auto model = TrainLosoModel(fold, ModelKind::kPca, 0, 1, {});
    for (bool adapt : {false, true}) {
      InferenceOptions inference;
      inference.adapt_posture = adapt;
      const ValidationResult expected = Validate(*model, LoadValidationTrials(fold.test, *model), ValidationCase{}, inference);
      std::getline(rows, row);
      const std::vector<std::string> cells = Cells(row);
      ASSERT_EQ(cells.size(), 7u) << row;
      EXPECT_EQ(cells[0], fold.subject);
      EXPECT_EQ(cells[2], adapt ? "yes" : "no");
      EXPECT_EQ(cells[3], std::to_string(fold.test.trials.size()));
      EXPECT_NEAR(std::stod(cells[4]), expected.mean_error_mm, 1e-3) << row;
    }
  }
  EXPECT_TRUE(fs::exists(out / "models" / "pca-without-07.json"));
  const nlohmann::json j = nlohmann::json::parse(ReadTextFile(out / "loso.json", "json"));
  EXPECT_EQ(j["results"].size(), 6u);
  EXPECT_EQ(j["results"][5]["held_out_subject"], "07");

  r = Jgpm(command);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("read from"), std::string::npos) << r.out;
  auto errors = [](const std::string& table) {  // the table without its seconds column
    std::istringstream lines(table);
    std::string kept;
    for (std::string line; std::getline(lines, line);) kept += line.substr(0, line.rfind(',')) + "\n";
    return kept;
  };
  EXPECT_EQ(errors(ReadTextFile(out / "loso.csv", "csv")), errors(csv));

  fs::copy_file(out / "models" / "pca-without-02.json", out / "models" / "pca-without-05.json",
                fs::copy_options::overwrite_existing);
  fs::remove(out / "loso.csv");
  r = Jgpm(command);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("pca-without-05.json"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("other trials"), std::string::npos) << r.err;
  EXPECT_EQ(test::CountLines(r.err), 1) << r.err;
  EXPECT_FALSE(fs::exists(out / "loso.csv"));
  r = Jgpm("eval --suite loso --kinds pca,banana --out " + out.string() + data);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("banana"), std::string::npos) << r.err;
}

TEST(EvalCli, EvalBadInput) {
  test::TempDir dir;
  const fs::path json = dir.path() / "e.json";
  const fs::path pca = dir.path() / "pca.json";
  ASSERT_EQ(Jgpm("train --model pca --data " + test::CmuRoot().string() + " --out " + pca.string()).status, 0);
  const struct {
    std::string arguments;
    int status;
    std::string message;
  } cases[] = {
      {"--task reconstruction", 1, "--task reconstruction: missing joints go with reconstruction"},
      {"--task filtering", 1, "--task filtering: filtering needs a noise level > 0"},
      {"--task interpolation --missing left-arm", 1, "missing joints go with reconstruction"},
      {"--task sideways", 2, "--task"},
      {"--task filtering --noise -1", 2, "--noise"},
      {"--suite paper", 1, "--suite paper: needs --out DIR"},
      {"", 1, "give --task"},
      {"--task interpolation --trials nosuchsplit", 1, "nosuchsplit"},
  };
  for (const auto& c : cases) {
    const Result r = Jgpm("eval --model " + pca.string() + " " + c.arguments + " --data " + test::CmuRoot().string() +
                          " --json " + json.string());
    EXPECT_EQ(r.status, c.status) << c.arguments << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.arguments << "\n" << r.err;
    EXPECT_EQ(test::CountLines(r.err), 1) << r.err;
  }
  const Result r = Jgpm("eval --model " + (dir.path() / "none.json").string() + " --task interpolation --json " + json.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("none.json"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(json));
}

}  // namespace
}  // namespace jgpm
