#include "tracker/cli/validation_commands.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <thread>

#include "io/data_root.h"
#include "io/error.h"
#include "io/gait_dataset.h"
#include "io/json_file.h"
#include "io/split.h"
#include "io/text_reader.h"
#include "prior/cholesky.h"
#include "prior/model_file.h"
#include "prior/validation.h"
#include "prior/validation_report.h"

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
  std::string json;
  std::string out;
};

void PrintResult(const std::string& model, const ValidationResult& r) {
  std::printf("%-22s %-34s %8.2f mm  (std %6.2f, %zu trials, %.1f s)\n", model.c_str(),
              r.validation_case.Label().c_str(), r.mean_error_mm, r.std_error_mm, r.trials.size(), r.seconds);
  std::fflush(stdout);
}

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
  for (const std::string& path : a.models) models.push_back(ReadModelFile(path));
  const std::vector<TrialId> trial_ids = ReadSplit(ResolveSplitPath(a.trials, JGPM_SPLITS_DIR));
  const std::filesystem::path root = ResolveDataRoot(a.data.empty() ? std::nullopt : std::optional(a.data));
  const GaitDataset dataset = PrepareGaitDataset(root, a.trials, trial_ids, GaitCycleOptions{});
  if (!a.out.empty()) std::filesystem::create_directories(a.out);
  const int threads = a.threads > 0 ? a.threads : std::max(1u, std::thread::hardware_concurrency());
  SetLinearAlgebraThreads(1);  // the trials run in parallel instead

  const auto start = std::chrono::steady_clock::now();
  std::vector<ModelResults> suite;
  const size_t total = models.size() * cases.size();
  for (size_t m = 0; m < models.size(); ++m) {
    const std::vector<ValidationTrial> trials = LoadValidationTrials(dataset, *models[m]);
    ModelResults results{std::filesystem::path(a.models[m]).stem().string(), {}};
    for (const ValidationCase& c : cases) {
      results.results.push_back(Validate(*models[m], trials, c, InferenceOptions{}, threads));
      PrintResult(results.model, results.results.back());
      const size_t done = m * cases.size() + results.results.size();
      const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (total > 1) std::fprintf(stderr, "  %zu/%zu cases, %.0f s, about %.0f s left\n", done, total, elapsed, elapsed / done * (total - done));
    }
    suite.push_back(std::move(results));
  }

  if (!a.json.empty()) {
    nlohmann::json j;
    if (suite.size() == 1 && suite[0].results.size() == 1) {
      j = ValidationResultJson(suite[0].results[0]);  // one case: its fields at the top
      j["model"] = a.models[0];
    } else {
      j["models"] = nlohmann::json::array();
      for (size_t m = 0; m < suite.size(); ++m) {
        nlohmann::json results = nlohmann::json::array();
        for (const ValidationResult& r : suite[m].results) results.push_back(ValidationResultJson(r));
        j["models"].push_back({{"model", a.models[m]}, {"results", results}});
      }
    }
    j["split"] = a.trials;
    WriteFileAtomic(a.json, FormatJson(j));
    std::printf("wrote %s\n", a.json.c_str());
  }
  if (!a.out.empty()) {
    const std::filesystem::path csv = std::filesystem::path(a.out) / (a.suite.empty() ? "eval.csv" : a.suite + ".csv");
    WriteFileAtomic(csv, SuiteCsv(suite));
    std::printf("wrote %s\n", csv.string().c_str());
    for (const auto& png : PlotSuite(suite, a.out)) std::printf("wrote %s\n", png.string().c_str());
  }
  std::printf("%zu case(s) x %zu model(s) in %.1f s\n", cases.size(), models.size(),
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
  eval->add_option("--json", a->json, "write mean_error_mm and per-trial errors here");
  eval->add_option("--out", a->out, "folder for the CSV and the PNG charts");
  eval->callback([a] { RunEval(*a); });
}

}  // namespace jgpm::cli
