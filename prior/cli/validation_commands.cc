#include "prior/cli/validation_commands.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <numeric>
#include <sstream>
#include <thread>

#include <opencv2/imgproc.hpp>

#include "io/base/error.h"
#include "io/base/json_file.h"
#include "io/base/output_batch.h"
#include "io/base/png_file.h"
#include "io/cli/progress.h"
#include "io/gait/data_root.h"
#include "io/gait/gait_dataset.h"
#include "io/gait/split.h"
#include "prior/eval/loso.h"
#include "prior/eval/validation.h"
#include "prior/eval/validation_report.h"
#include "prior/model/model_file.h"
#include "prior/model/posture_prior.h"
#include "prior/motion/synthesis.h"
#include "prior/motion/transition_event.h"
#include "prior/motion/transition_report.h"
#include "prior/motion/transition_suite.h"

namespace jgpm::cli {
namespace {

struct EvalArguments {
  std::vector<std::string> models;
  std::string task;
  std::string suite;
  std::string trials = "test";
  std::string data;
  double scale = 1.0;
  std::string missing;
  double noise = 0;
  int draws = 5;
  int threads = 0;
  std::string adapt = "none";
  InferenceOptions inference;  // --gain-std, --common-gain-std
  std::string kinds = "pca,jgpm,mljgpm-torus,mljgpm-cyl";
  double max_time = 0;
  int max_per_subject = 9;
  bool trials_given = false;
  std::string json;
  std::string out;
  std::string events;
  std::string methods = "lsopa,li,ri,slerp,hold,oracle,lsopa-rt";
  std::string frames = "5,15,30";
  double peak_offset = LatentTransitionOptions{}.peak_offset;
  double max_angle = LatentTransitionOptions{}.max_angle_deg;
};

// Comma-separated items of an option, each parsed by `parse` (false: refused, naming it).
template <typename T, typename Parse>
std::vector<T> ParseList(const std::string& text, const std::string& option, const std::string& expected, Parse parse) {
  std::vector<T> items;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    T value{};
    if (!parse(item, &value)) ThrowInputError(option, "'" + item + "' is not " + expected);
    items.push_back(value);
  }
  if (items.empty()) ThrowInputError(option, "expected " + expected + ", comma-separated");
  return items;
}

// What the posture prior's selection chose for a model (prior/model/posture_prior.h).
void PrintPosturePrior(const std::string& name, const GaitModel& model) {
  const PosturePrior prior = PosturePrior::FromTrainingSet(model.data().set);
  std::printf("%s: posture prior from %d subjects, correlation weight %.2f, floor %.1f deg (%s)\n", name.c_str(),
              prior.NumSubjects(), prior.correlation_weight(), prior.floor_deg(),
              prior.selected() ? "chosen by leave-one-subject-out" : "fixed: fewer than 3 subjects");
}

// "  LABEL" and the five names whose `score(value)` is largest, each printed by `format`
// (a name and its value).
template <typename Score>
void PrintLargest(const char* label, const std::vector<std::string>& names, const std::vector<double>& values,
                  const char* format, Score score) {
  std::vector<size_t> order(names.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](size_t x, size_t y) { return score(values[x]) > score(values[y]); });
  std::printf("  %s", label);
  for (size_t k = 0; k < std::min<size_t>(5, order.size()); ++k) std::printf(format, names[order[k]].c_str(), values[order[k]]);
  std::printf("\n");
}

std::vector<bool> AdaptModes(const std::string& adapt) {  // none, posture, both
  std::vector<bool> modes;
  if (adapt != "posture") modes.push_back(false);
  if (adapt != "none") modes.push_back(true);
  return modes;
}

// `jgpm eval --suite loso`: trains each kind per held-out subject (or reads the model an
// earlier run left in OUT/models, after checking it was trained on the same trials), then
// validates it on that subject.
void RunLoso(const EvalArguments& a) {
  if (!a.models.empty()) ThrowInputError("--model", "--suite loso trains its own models: give --kinds instead");
  if (!a.task.empty()) ThrowInputError("--task", "--suite loso validates interpolation at s = 1; give no --task");
  if (a.out.empty()) ThrowInputError("--suite loso", "needs --out DIR for the CSV and the fold models");
  LosoOptions options;
  options.kinds = ParseList<ModelKind>(a.kinds, "--kinds", "a model kind (" + ModelKindList() + ")",
                                      [](const std::string& t, ModelKind* k) { return ParseModelKind(t, k); });
  options.adapt = AdaptModes(a.adapt);
  options.inference = a.inference;
  options.max_trials_per_subject = a.max_per_subject;
  options.max_training_seconds = a.max_time;
  options.threads = a.threads > 0 ? a.threads : std::max(1u, std::thread::hardware_concurrency());
  std::string why;
  if (!options.Check(&why)) ThrowInputError("--suite loso", why);
  const std::string split = a.trials_given ? a.trials : "walking";
  const std::vector<TrialId> trial_ids = ReadSplit(ResolveSplitPath(split, JGPM_SPLITS_DIR));
  const std::filesystem::path root = ResolveDataRoot(a.data.empty() ? std::nullopt : std::optional(a.data));
  const GaitDataset dataset = PrepareGaitDataset(root, split, trial_ids, GaitCycleOptions{});
  const std::vector<LosoFold> folds = LosoFolds(dataset, options.max_trials_per_subject);
  const std::filesystem::path models = std::filesystem::path(a.out) / "models";
  std::filesystem::create_directories(models);
  std::printf("leave-one-subject-out on %s: %zu subjects, %zu model kinds\n", split.c_str(), folds.size(),
              options.kinds.size());
  std::fflush(stdout);

  const auto start = std::chrono::steady_clock::now();
  auto print_posture_prior = [&options](const std::string& name, const GaitModel& model) {
    if (std::find(options.adapt.begin(), options.adapt.end(), true) != options.adapt.end()) {
      PrintPosturePrior(name, model);
    }
    std::fflush(stdout);
  };
  auto model_for = [&](const LosoFold& fold, ModelKind kind) -> std::unique_ptr<GaitModel> {
    const std::string name = std::string(ModelKindName(kind)) + "-without-" + fold.subject;
    const std::filesystem::path path = models / (name + ".json");
    std::vector<std::string> ids;
    for (const GaitTrial& t : fold.train.trials) ids.push_back(t.id.name);
    if (std::filesystem::exists(path)) {
      std::unique_ptr<GaitModel> model = ReadModelFile(path);
      if (model->kind() != kind || model->data().set.gait_ids != ids) {
        ThrowInputError(path.string(), "was trained on other trials or is another kind; remove it to train it again");
      }
      std::printf("%-26s read from %s\n", name.c_str(), path.string().c_str());
      print_posture_prior(name, *model);
      return model;
    }
    ProgressLine line("train " + name);
    const auto begin = std::chrono::steady_clock::now();
    std::unique_ptr<GaitModel> model =
        TrainLosoModel(fold, kind, options.max_training_seconds, options.threads, [&line](const TrainingProgress& p) {
          line.Update(p.iteration, p.max_iterations, p.stage == "local" ? "steps" : "iterations");
        });
    line.Finish();
    WriteModelFile(path, *model);
    std::printf("%-26s trained on %zu trials in %.0f s: %s\n", name.c_str(), ids.size(),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count(), path.string().c_str());
    print_posture_prior(name, *model);
    return model;
  };
  const std::vector<LosoResult> results = RunLoso(folds, options, model_for, [](const LosoResult& r, size_t, size_t) {
    std::printf("without %-4s %-14s %-9s %8.2f mm  (std %6.2f, %zu trials, %.1f s)\n", r.subject.c_str(),
                std::string(ModelKindName(r.kind)).c_str(), r.adapted ? "+posture" : "", r.validation.mean_error_mm,
                r.validation.std_error_mm, r.validation.trials.size(), r.validation.seconds);
    std::fflush(stdout);
  });
  OutputBatch batch;
  const std::string csv = LosoCsv(results);
  batch.Add(std::filesystem::path(a.out) / "loso.csv", csv);
  nlohmann::json j = nlohmann::json::array();
  for (const LosoResult& r : results) {
    nlohmann::json row = ValidationResultJson(r.validation);
    row["held_out_subject"] = r.subject;
    row["model"] = std::string(ModelKindName(r.kind));
    row["adapted"] = r.adapted;
    j.push_back(row);
  }
  batch.Add(std::filesystem::path(a.out) / "loso.json", FormatJson(nlohmann::json{{"split", split}, {"results", j}}));
  if (!a.json.empty()) batch.Add(a.json, FormatJson(nlohmann::json{{"split", split}, {"results", j}}));
  std::printf("\nmean over the held-out subjects (each weighing alike):\n");
  std::istringstream rows(csv);
  for (std::string row; std::getline(rows, row);) {
    if (row.rfind("mean,", 0) == 0) std::printf("  %s\n", row.c_str());
  }
  for (const auto& file : batch.Commit()) std::printf("wrote %s\n", file.string().c_str());
  std::printf("%zu fold(s) in %.1f s\n", folds.size(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

// `jgpm eval --suite transitions`: every event x shift x N x method of the event list.
// OUT/transitions.csv (one row per case and method), per_frame.csv, intervals.csv (paired
// bootstrap of LSOPA against each other method), plots/KIND-N.png (mean error per
// transition frame), strips/TRIAL-KIND.png (the truth over each method, shift 0, middle N
// or the first N that fits).
void RunTransitions(const EvalArguments& a) {
  if (!a.models.empty() || !a.task.empty()) ThrowInputError("--suite transitions", "takes no --model or --task");
  if (a.out.empty()) ThrowInputError("--suite transitions", "needs --out DIR for the CSV and the strips");
  TransitionSuiteOptions options;
  options.methods = ParseList<TransitionMethod>(a.methods, "--methods", "a method (lsopa, li, ri, slerp, hold, oracle or lsopa-rt)",
                                                [](const std::string& t, TransitionMethod* m) {
                                                  return ParseTransitionMethod(t, m);
                                                });
  options.frames = ParseList<int>(a.frames, "--frames", "a frame count from 1 to 300", [](const std::string& t, int* n) {
    char* end = nullptr;
    const long v = std::strtol(t.c_str(), &end, 10);
    *n = static_cast<int>(v);
    return !t.empty() && *end == '\0' && v >= 1 && v <= 300;
  });
  options.transition.transition.path.peak_offset = a.peak_offset;
  options.transition.transition.path.max_angle_deg = a.max_angle;
  std::string why;
  if (!options.transition.transition.path.Check(&why)) ThrowInputError("--peak-offset/--max-angle", why);
  const std::filesystem::path events_path =
      a.events.empty() ? std::filesystem::path(JGPM_SPLITS_DIR).parent_path() / "transitions.txt"
                       : std::filesystem::path(a.events);
  const std::vector<TransitionEvent> events = ReadTransitionEvents(events_path);
  const std::filesystem::path root = ResolveDataRoot(a.data.empty() ? std::nullopt : std::optional(a.data));
  const std::filesystem::path out(a.out);
  if (std::filesystem::exists(out / "transitions.csv")) {
    ThrowInputError((out / "transitions.csv").string(), "exists; give another --out");
  }
  std::filesystem::create_directories(out / "strips");
  std::filesystem::create_directories(out / "plots");
  ProgressLine line("transitions");
  const TransitionSuiteResult result = RunTransitionSuite(
      events, root, options,
      [&](int done, int total, const std::string& label) { line.Update(done, total, "cases", label); });
  line.Finish();
  OutputBatch batch;
  batch.Add(out / "transitions.csv", TransitionSuiteCsv(result));
  batch.Add(out / "per_frame.csv", TransitionPerFrameCsv(result));
  // The bootstrap once per event set: reported (tune = false), then tuning.
  const std::vector<PairedInterval> intervals[2] = {LsopaIntervals(result, false), LsopaIntervals(result, true)};
  std::vector<PairedInterval> all = intervals[0];
  for (PairedInterval p : intervals[1]) {
    p.scope = "tuning " + p.scope;
    all.push_back(p);
  }
  batch.Add(out / "intervals.csv", PairedIntervalsCsv(all));
  for (const TransitionStrip& s : result.strips) {
    std::vector<cv::Mat> rows;
    for (const auto& [name, motion] : s.motions) {
      cv::Mat row = StickFigures(s.skeleton, motion, std::min(12, motion.NumFrames()));
      cv::putText(row, name, {8, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.6, {0, 0, 0}, 1, cv::LINE_AA);
      rows.push_back(row);
    }
    cv::Mat strip;
    cv::vconcat(rows, strip);
    const std::filesystem::path png = out / "strips" / (s.trial + "-" + std::string(TransitionKindName(s.kind)) + ".png");
    batch.Add(png, EncodePng(strip, png.string()));
  }
  for (const bool tune : {false, true}) {
    for (TransitionKind kind : {TransitionKind::kStart, TransitionKind::kStop, TransitionKind::kKick,
                                TransitionKind::kJump, TransitionKind::kDuck}) {
      for (int n : options.frames) {
        const cv::Mat plot = PerFramePlot(result, kind, n, tune);
        if (plot.empty()) continue;
        const std::filesystem::path png = out / "plots" / ((tune ? "tuning-" : "") + std::string(TransitionKindName(kind)) +
                                                          "-" + std::to_string(n) + ".png");
        batch.Add(png, EncodePng(plot, png.string()));
      }
    }
  }
  for (const auto& file : batch.Commit()) std::printf("wrote %s\n", file.string().c_str());
  for (const bool tune : {true, false}) {
    const std::string table = TransitionSummaryTable(result, tune);
    if (table.empty()) continue;
    std::printf("\n%s events, eq. 23 (mm, root placed as in the truth), mean over events and shifts:\n%s",
                tune ? "tuning" : "reported", table.c_str());
    std::printf("foot skating (m/s, horizontal foot speed within 2.5 cm of the floor), mean over the cases:\n%s",
                FootSkateTable(result, tune).c_str());
    bool header = false;
    for (const PairedInterval& p : intervals[tune]) {
      if (p.scope != "all") continue;
      if (!header) {
        std::printf("LSOPA minus each method, mean and 95%% paired bootstrap interval (mm), all %s cases:\n",
                    tune ? "tuning" : "reported");
        header = true;
      }
      std::printf("  %-9s %+7.1f  [%+7.1f, %+7.1f]  LSOPA lower in %d of %d\n",
                  std::string(TransitionMethodName(p.other)).c_str(), p.mean_mm, p.low_mm, p.high_mm, p.lsopa_lower,
                  p.cases);
    }
  }
  std::printf("%zu rows, %d case(s) skipped (not within their trial)\n", result.rows.size(), result.skipped);
}

void RunEval(const EvalArguments& a) {
  if (a.suite == "loso") return RunLoso(a);
  if (a.suite == "transitions") return RunTransitions(a);
  if (a.models.empty()) ThrowInputError("--model", "give at least one model file");
  std::vector<ValidationCase> cases;
  if (!a.suite.empty()) {
    if (!a.task.empty()) ThrowInputError("--task", "give either --task or --suite, not both");
    if (a.out.empty()) ThrowInputError("--suite " + a.suite, "needs --out DIR for the CSV and charts");
    cases = PaperSuite();
  } else {
    if (a.task.empty()) ThrowInputError("--task", "give --task interpolation|reconstruction|filtering, or --suite paper");
    if (a.models.size() > 1) ThrowInputError("--model", "one model per --task run (several go with --suite)");
    ValidationCase c;
    ParseValidationTask(a.task, &c.task);
    c.scale = a.scale;
    if (!a.missing.empty()) ParseMissingPart(a.missing, &c.missing);
    c.noise = a.noise;
    c.draws = a.draws;
    std::string why;
    if (!c.Check(&why)) ThrowInputError("--task " + a.task, why);
    cases.push_back(c);
  }
  // Check everything that can fail before the long part: models, trials, output folder.
  std::vector<std::unique_ptr<GaitModel>> models;
  std::vector<const GaitModel*> model_pointers;
  std::vector<std::string> names;
  for (const std::string& path : a.models) {
    models.push_back(ReadModelFile(path));
    model_pointers.push_back(models.back().get());
    names.push_back(std::filesystem::path(path).stem().string());
  }
  const std::vector<TrialId> trial_ids = ReadSplit(ResolveSplitPath(a.trials, JGPM_SPLITS_DIR));
  const std::filesystem::path root = ResolveDataRoot(a.data.empty() ? std::nullopt : std::optional(a.data));
  const GaitDataset dataset = PrepareGaitDataset(root, a.trials, trial_ids, GaitCycleOptions{});
  if (!a.out.empty()) std::filesystem::create_directories(a.out);
  const int threads = a.threads > 0 ? a.threads : std::max(1u, std::thread::hardware_concurrency());

  // Each model without and/or with posture adaptation ("+posture" in its name).
  const std::vector<bool> adapt_modes = AdaptModes(a.adapt);
  const size_t runs = adapt_modes.size() * models.size() * cases.size();

  const auto start = std::chrono::steady_clock::now();
  ProgressLine line("eval", 0);
  std::vector<ModelResults> suite;
  std::vector<std::string> model_paths;
  for (const bool adapt : adapt_modes) {
    InferenceOptions inference = a.inference;
    inference.adapt_posture = adapt;
    std::vector<std::string> run_names = names;
    if (adapt) for (std::string& name : run_names) name += "+posture";
    for (size_t m = 0; adapt && m < models.size(); ++m) PrintPosturePrior(run_names[m], *models[m]);
    const size_t before = suite.size() * cases.size();
    std::vector<ModelResults> results = ValidateSuite(
        model_pointers, run_names, dataset, cases, inference, threads,
        [&](const ModelResults& m, size_t done, size_t) {
          done += before;
          const size_t total = runs;
        const ValidationResult& r = m.results.back();
        line.Finish();
        std::printf("%-22s %-34s %8.2f mm  (std %6.2f, %zu trials, %.1f s)\n", m.model.c_str(),
                    r.validation_case.Label().c_str(), r.mean_error_mm, r.std_error_mm, r.trials.size(), r.seconds);
        if (cases.size() == 1 && models.size() == 1) {  // one case: where its error comes from
          PrintLargest("largest joint errors:", r.joint_names, r.joint_errors_mm, " %s %.1f mm",
                       [](double mm) { return mm; });
          PrintLargest("largest angle errors:", r.channel_names, r.channel_errors_deg, " %s %.1f deg",
                       [](double deg) { return deg; });
          if (!r.channel_gain.empty()) {
            // Their common level trades against the latent stride, so what stands out is a
            // channel's distance from it (a low one may be hedging; prior/model/inference.h).
            const double mean = std::accumulate(r.channel_gain.begin(), r.channel_gain.end(), 0.0) /
                                static_cast<double>(r.channel_gain.size());
            char label[64];
            std::snprintf(label, sizeof label, "gains (mean %.2f) furthest from their mean:", mean);
            PrintLargest(label, r.channel_names, r.channel_gain, " %s %.2f",
                         [mean](double gain) { return std::abs(gain - mean); });
          }
        }
        std::fflush(stdout);
        if (total > 1) line.Update(done, total, "cases");
      });
    suite.insert(suite.end(), results.begin(), results.end());
    model_paths.insert(model_paths.end(), a.models.begin(), a.models.end());
  }
  line.Finish();
  const std::string csv_name = a.suite.empty() ? "eval.csv" : a.suite + ".csv";
  for (const auto& file : WriteValidationOutputs(suite, model_paths, a.trials, a.json, a.out, csv_name)) {
    std::printf("wrote %s\n", file.string().c_str());
  }
  std::printf("%zu case(s) x %zu model(s) in %.1f s\n", cases.size(), suite.size(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace

void AddValidationCommands(CLI::App& app) {
  auto a = std::make_shared<EvalArguments>();
  CLI::App* eval = app.add_subcommand("eval", "Validate gait priors as the paper does: interpolation, reconstruction, filtering");
  eval->add_option("--model", a->models, "model file (repeat for several with --suite paper)");
  eval->add_option("--task", a->task, "one task")->check(CLI::IsMember({"interpolation", "reconstruction", "filtering"}));
  eval->add_option("--suite", a->suite,
                   "paper: every task, scale and condition of the paper (Figs. 9, 12, 13); loso: leave one subject "
                   "out, training --kinds on the other subjects of --trials (default walking); transitions: LSOPA and its "
                   "baselines on real transitions (--events)")
      ->check(CLI::IsMember({"paper", "loso", "transitions"}));
  eval->add_option("--trials", a->trials, "split name (datasets_scripts/splits/NAME.txt) or file of test trials")
      ->capture_default_str()
      ->each([a](const std::string&) { a->trials_given = true; });
  eval->add_option("--kinds", a->kinds, "loso: model kinds, comma-separated")->capture_default_str();
  eval->add_option("--max-time", a->max_time, "loso: training time limit per model, seconds (0: none)")
      ->check(CLI::NonNegativeNumber);
  eval->add_option("--max-per-subject", a->max_per_subject, "loso: training trials per subject, at most")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  eval->add_option("--data", a->data, "data root (default: $JGPM_DATA, ./data/cmu, ../shared/data/cmu)");
  eval->add_option("--scale", a->scale, "stride scale s applied to each test cycle (eq. 5)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  eval->add_option("--missing", a->missing, "reconstruction: the joints left out")
      ->check(CLI::IsMember({"left-arm", "left-leg", "left-side"}));
  eval->add_option("--noise", a->noise, "filtering: noise std as a fraction of each channel's std (0.1 = 10%)")
      ->check(CLI::Range(0.0, 10.0));
  eval->add_option("--draws", a->draws, "filtering: noise draws")->check(CLI::Range(1, 1000))->capture_default_str();
  eval->add_option("--threads", a->threads, "trials evaluated in parallel (0: all cores)")
      ->check(CLI::Range(0, 256))
      ->capture_default_str();
  eval->add_option("--adapt", a->adapt,
                   "posture: estimate a per-sequence posture offset and amplitude gains with the latent points "
                   "(for people the prior has not seen); both: each model without and with it")
      ->check(CLI::IsMember({"none", "posture", "both"}))
      ->capture_default_str();
  eval->add_option("--gain-std", a->inference.gain_std, "posture adaptation: std of the per-channel amplitude gain's prior")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  eval->add_option("--common-gain-std", a->inference.common_gain_std,
                   "posture adaptation: std of the part all channels' gains share (0: independent gains)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  eval->add_option("--events", a->events, "transitions: the event list (default datasets_scripts/transitions.txt)");
  eval->add_option("--methods", a->methods, "transitions: methods, comma-separated")->capture_default_str();
  eval->add_option("--frames", a->frames, "transitions: transition lengths N, comma-separated")->capture_default_str();
  eval->add_option("--peak-offset", a->peak_offset, "transitions: LSOPA's largest distance from the line a-b, over |b - a|")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  eval->add_option("--max-angle", a->max_angle, "transitions: LSOPA's theta, degrees either side of C")
      ->check(CLI::Range(0.0, 180.0))
      ->capture_default_str();
  eval->add_option("--json", a->json, "write mean_error_mm and per-trial errors here");
  eval->add_option("--out", a->out, "folder for the CSV and the PNG charts");
  eval->callback([a] { RunEval(*a); });
}

}  // namespace jgpm::cli
