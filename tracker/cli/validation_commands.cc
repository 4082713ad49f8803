#include "tracker/cli/validation_commands.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <thread>

#include "io/data_root.h"
#include "io/error.h"
#include "io/gait_dataset.h"
#include "io/split.h"
#include "prior/model_file.h"
#include "prior/validation.h"
#include "prior/validation_report.h"
#include "tracker/cli/progress.h"

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
  std::string json;
  std::string out;
};

void RunEval(const EvalArguments& a) {
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
    ParseTask(a.task, &c.task);
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
  std::vector<bool> adapt_modes;
  if (a.adapt != "posture") adapt_modes.push_back(false);
  if (a.adapt != "none") adapt_modes.push_back(true);
  const size_t runs = adapt_modes.size() * models.size() * cases.size();

  const auto start = std::chrono::steady_clock::now();
  ProgressLine line("eval", 0);
  std::vector<ModelResults> suite;
  std::vector<std::string> model_paths;
  for (const bool adapt : adapt_modes) {
    InferenceOptions inference;
    inference.adapt_posture = adapt;
    std::vector<std::string> run_names = names;
    if (adapt) for (std::string& name : run_names) name += "+posture";
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
          std::vector<size_t> order(r.joint_names.size());
          for (size_t k = 0; k < order.size(); ++k) order[k] = k;
          std::sort(order.begin(), order.end(), [&r](size_t x, size_t y) { return r.joint_errors_mm[x] > r.joint_errors_mm[y]; });
          std::printf("  largest joint errors:");
          for (size_t k = 0; k < std::min<size_t>(5, order.size()); ++k) {
            std::printf(" %s %.1f mm", r.joint_names[order[k]].c_str(), r.joint_errors_mm[order[k]]);
          }
          order.resize(r.channel_names.size());
          for (size_t k = 0; k < order.size(); ++k) order[k] = k;
          std::sort(order.begin(), order.end(), [&r](size_t x, size_t y) { return r.channel_errors_deg[x] > r.channel_errors_deg[y]; });
          std::printf("\n  largest angle errors:");
          for (size_t k = 0; k < std::min<size_t>(5, order.size()); ++k) {
            std::printf(" %s %.1f deg", r.channel_names[order[k]].c_str(), r.channel_errors_deg[order[k]]);
          }
          std::printf("\n");
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
  eval->add_option("--model", a->models, "model file (repeat for several with --suite)")->required();
  eval->add_option("--task", a->task, "one task")->check(CLI::IsMember({"interpolation", "reconstruction", "filtering"}));
  eval->add_option("--suite", a->suite, "every task, scale and condition of the paper (Figs. 9, 12, 13)")
      ->check(CLI::IsMember({"paper"}));
  eval->add_option("--trials", a->trials, "split name (datasets_scripts/splits/NAME.txt) or file of test trials")
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
                   "posture: estimate a per-sequence posture offset with the latent points (for people the "
                   "prior has not seen); both: each model without and with it")
      ->check(CLI::IsMember({"none", "posture", "both"}))
      ->capture_default_str();
  eval->add_option("--json", a->json, "write mean_error_mm and per-trial errors here");
  eval->add_option("--out", a->out, "folder for the CSV and the PNG charts");
  eval->callback([a] { RunEval(*a); });
}

}  // namespace jgpm::cli
